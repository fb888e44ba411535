"""A slow lab pass with an edge zone (R 0.1 m, 10 -> 8 mm, 0.1 m/s, Norton-Hoff m 0.1, Tresca
0.8, 40 mm wide, zone 10 mm): exact scalings, the frame, threads (issue 53 check).

    PYTHONPATH=. python docs/notes/issue53-edge-zone/lab_scalings.py
"""
import json
from dataclasses import replace

from hotroll.config.case import load_case
from hotroll.fem.reproducible import threaded
from hotroll.solvers.spread_3d import Spread3D
from hotroll.solvers.steady import SteadyRun
from hotroll.workflows.build import build_model, steady_settings

LAB = {"pass.roll_radius": 0.1, "pass.entry_thickness": 0.01, "pass.exit_thickness": 0.008,
       "pass.roll_angular_velocity": 1.0, "pass.width": 0.04, "plate.length": 0.1,
       "material.law": "norton-hoff", "material.K": 1.5e8, "material.m": 0.1,
       "material.grade": None, "friction.factor": 0.8}


def go(extra=None, change=lambda p: p, threads=None):
    with threaded(threads):
        case = load_case("hotroll/examples/cases/narrow_bar.toml", {**LAB, **(extra or {})})
        problem, _ = build_model(case)
        problem = change(problem)
        run = SteadyRun(problem, steady_settings(case), case.plate.length)
        assert run.run().status == "steady"
        s3 = Spread3D(run, 0.02, edge=0.0025, zone=0.01)
        assert s3.solve()
        f = s3.figures()
        return {k: f[k] for k in ("spread", "roll_force", "roll_torque", "flux_in",
                                  "forward_slip", "newton_iterations")}


a = go(threads=2)
print("base", json.dumps(a), flush=True)
m = 0.1
fast = go(change=lambda p: replace(p, rp=replace(p.rp, omega=100 * p.rp.omega),
                                   friction=replace(p.friction, v_reg=100 * p.friction.v_reg),
                                   material=replace(p.material, eps0=100 * p.material.eps0)))
K = go(change=lambda p: replace(p, material=replace(p.material, K=1000 * p.material.K)))
moved = go({"pass.roll_axis_x": -7.5})
one = go(threads=1)


def rel(x, y):
    return abs(x / y - 1)


print("speed x100: spread", rel(fast["spread"], a["spread"]), "slip",
      rel(fast["forward_slip"], a["forward_slip"]), "force/100^m",
      rel(fast["roll_force"], 100**m * a["roll_force"]), "flux/100",
      rel(fast["flux_in"], 100 * a["flux_in"]))
print("K x1000: spread", rel(K["spread"], a["spread"]), "force",
      rel(K["roll_force"], 1000 * a["roll_force"]), "slip", rel(K["forward_slip"], a["forward_slip"]))
print("axis -7.5: spread", rel(moved["spread"], a["spread"]), "force",
      rel(moved["roll_force"], a["roll_force"]), "slip", rel(moved["forward_slip"], a["forward_slip"]))
print("threads 1: spread", rel(one["spread"], a["spread"]), "force",
      rel(one["roll_force"], a["roll_force"]), "its", one["newton_iterations"], a["newton_iterations"])
