"""Measure arc flux, balance, force etc. on bundled cases. usage: measure.py tag name[,name] [key=value ...]"""
import sys, json, time
import numpy as np
import ngsolve as ng
import hotroll
from hotroll.solvers import steady as S
from hotroll.config.case import load_case
from hotroll.examples import example_path

RUNS = []
orig = S.SteadyRun.run
def run(self, *a, **k):
    RUNS.append(self)
    return orig(self, *a, **k)
S.SteadyRun.run = run

tag, names = sys.argv[1], sys.argv[2].split(",")
ov = {"output.figures": False}
for a in sys.argv[3:]:
    k, v = a.split("=", 1)
    try: v = json.loads(v)
    except Exception: pass
    ov[k] = v
rows = []
for name in names:
    RUNS.clear()
    case = load_case(example_path(name), ov)
    t0 = time.time()
    res = hotroll.solve(case)
    wall = time.time() - t0
    s = res.summary
    r = RUNS[-1]
    u, n = r.form.nonlinear.velocity, ng.specialcf.normal(2)
    flux = {b: ng.Integrate(u * n, r.mesh, ng.BND, definedon=r.mesh.Boundaries(b), order=8)
            for b in set(r.mesh.GetBoundaries())}
    q = -flux["in"]
    c = res.contact
    keys = list(c.keys())
    pass
    row = dict(tag=tag, case=name, exit_code=s.get("exit_code"), status=s.get("status"),
               mass_flux_error=s.get("mass_flux_error"), arc_flux=flux["arc"] / q,
               top_flux=flux.get("top", 0) / q, exit_flux=flux.get("exit", 0) / q,
               out_flux=flux["out"] / q,
               roll_force=s.get("roll_force"), roll_torque=s.get("roll_torque"),
               forward_slip=s.get("forward_slip"), newton=s.get("newton_iterations"),
               nonlinear=s.get("nonlinear_iterations"), end_kind=s.get("contact_end_kind"),
               p_end=s.get("contact_end_pressure"), wall=wall)
    print(json.dumps(row), flush=True)
    print("contact.csv keys", keys)
    np.savez(f"/tmp/elm/{tag}_{name}.npz", **{k: np.asarray(v) for k, v in c.items() if np.asarray(v).dtype.kind in "fi"})
    # the multiplier at the arc vertices in x order
    f = r.form
    vp = f.vertex_pressure(); mv, _ = f.multiplier_vertices()
    X = np.array([r.mesh.vertices[int(v)].point for v in mv]); o = np.argsort(X[:, 0])
    pv = vp[mv][o] * f.material.K if hasattr(f.material, "K") else vp[mv][o]
    np.save(f"/tmp/elm/{tag}_{name}_mult.npy", np.c_[X[o], vp[mv][o]])
    pr = vp[mv][o] / vp[mv].max()
    print("mult/peak first 8:", np.round(pr[:8], 4).tolist())
    print("mult/peak last 8:", np.round(pr[-8:], 4).tolist())
    rows.append(row)
with open(f"/tmp/elm/{tag}.json", "a") as fh:
    for r_ in rows: fh.write(json.dumps(r_) + "\n")
