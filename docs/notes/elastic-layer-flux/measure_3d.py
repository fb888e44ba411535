"""The bundled narrow bar through the CLI (in-process, its outputs in OUTDIR) and the 3D
arc's net flux and the layer's width divergence after it, over the inflow (the quarter's).
usage: PYTHONPATH=. python docs/notes/elastic-layer-flux/measure_3d.py OUTDIR (a fresh dir)"""
import json
import sys

import hotroll.workflows.spread as sp

keep = {}


class Kept(sp.Spread3D):
    def solve(self, *a, **k):
        ok = super().solve(*a, **k)
        keep["s3"] = self
        return ok


sp.Spread3D = Kept
from hotroll.cli import main  # noqa: E402

out = sys.argv[1]
sys.argv = ["hotroll", "example", "narrow_bar", "--out", out]
try:
    main()
except SystemExit as e:
    print("exit", e.code)
import ngsolve as ng  # noqa: E402

from hotroll.fem.reproducible import integrate  # noqa: E402

s3 = keep["s3"]
f, mesh = s3.form, s3.mesh
u, lam = f.nonlinear.velocity, f.multiplier
n, t = f.roll_frame()
arc = integrate(u * n, mesh, ng.BND, definedon=mesh.Boundaries("arc"))
inflow = -integrate(u * ng.specialcf.normal(3), mesh, ng.BND, definedon=mesh.Boundaries("in"))
depth = ng.y if f.strip_depth is None else ng.IfPos(ng.y - f.strip_depth, f.strip_depth, ng.y)
e_z = ng.CF((0.0, 0.0, 1.0))
width = f.lam_scale * integrate(f.compliance * depth * (u[2] * (ng.grad(lam) * e_z)
                                                        + lam * (ng.grad(u) * e_z)[2]),
                                mesh, ng.BND, definedon=mesh.Boundaries("arc"))
d = json.load(open(out + "/summary.json"))
print(json.dumps({"arc_over_inflow": arc / inflow, "width_div_over_inflow": width / inflow,
                  "inflow": inflow,
                  **{k: d.get(k) for k in ("roll_force_total", "roll_torque_total", "spread",
                                           "spread_mass_flux_error", "spread_newton_iterations",
                                           "spread_rounds", "spread_forward_slip",
                                           "spread_power_balance_error", "spread_wall_time",
                                           "spread_settled", "exit_width", "edge_bulge")}},
                 indent=1))
