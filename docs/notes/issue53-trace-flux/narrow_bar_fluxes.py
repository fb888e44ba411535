"""The bundled narrow bar's 3D mass fluxes per boundary and per width band of the top (docs/validation/spread_3d.md,
"Mass flux"): PYTHONPATH=. python docs/notes/issue53-trace-flux/narrow_bar_fluxes.py [spread.edge_layer=0.0013333]."""
import sys, time
import numpy as np, ngsolve as ng
from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.workflows.build import build_model, steady_settings
from hotroll.solvers.steady import SteadyRun
from hotroll.solvers.spread_3d import Spread3D
from hotroll.fem.reproducible import integrate
over = {}
for a in sys.argv[1:]:
    k, v = a.split("="); over[k] = eval(v)
case = load_case(example_path("narrow_bar"), {"output.figures": False, **over})
problem, _ = build_model(case)
run = SteadyRun(problem, steady_settings(case), case.plate.length)
print("2D", run.run().status, "h", problem.h)
half = 0.5 * case.pass_.width
edge, growth, largest = case.spread.layers(half, case.mesh.h)
s3 = Spread3D(run, half, edge=edge, growth=growth, largest=largest, strain=case.spread.strain)
t = time.perf_counter(); s3.solve(max_rounds=case.spread.max_rounds); print("3D", time.perf_counter() - t, s3.iterations, s3.rounds)
m = s3.mesh; u = s3.form.nonlinear.velocity; nn = ng.specialcf.normal(3)
fin = -integrate(u * nn, m, ng.BND, definedon=m.Boundaries("in"))
for b in m.GetBoundaries() and sorted(set(m.GetBoundaries())):
    f = integrate(u * nn, m, ng.BND, definedon=m.Boundaries(b))
    print(f"{b:8s} flux/in {f / fin:+.3e}")
fig = s3.figures()
print("mass (out+edge-in)/in", (fig["flux_out"] + fig["flux_edge"] - fig["flux_in"]) / fig["flux_in"], "spread", fig.get("spread"))
zs = s3.z
print("levels", len(zs), np.round(zs * 1e3, 3))
for b in ("top", "exit", "arc"):
    row = []
    for k in range(len(zs) - 1):
        lo, hi = zs[k], zs[k + 1]
        band = ng.IfPos((ng.z - lo) * (hi - ng.z), 1.0, 0.0)
        row.append(integrate(band * (u * nn), m, ng.BND, definedon=m.Boundaries(b)) / fin)
    print(b, " ".join(f"{r:+.1e}" for r in row))
# the 2D pass's own fluxes
f2 = run.form; u2 = f2.nonlinear.velocity; n2 = ng.specialcf.normal(2); m2 = run.mesh
fin2 = -integrate(u2 * n2, m2, ng.BND, definedon=m2.Boundaries("in"))
for b in sorted(set(m2.GetBoundaries())):
    print("2D", b, f"{integrate(u2 * n2, m2, ng.BND, definedon=m2.Boundaries(b)) / fin2:+.3e}")
