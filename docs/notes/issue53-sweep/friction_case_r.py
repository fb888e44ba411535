"""Spread against the Tresca factor on Case R's bar (tests/solvers/test_full_strip.py: CASE_R, b0/h0 = 1, l/h = 2.5),
and with v_reg 4 mm/s (docs/notes/issue53-sweep.md, flag 1). From the repository root: PYTHONPATH=. python THIS."""
import sys
sys.path.insert(0, "tests/solvers")
from test_full_strip import _setup
from hotroll.solvers.spread_3d import Spread3D
from hotroll.solvers.steady import SteadyRun
for factor, vreg in ((0.3, None), (0.9, None), (0.3, 0.004), (0.9, 0.004)):
    extra = {"friction.factor": factor}
    if vreg: extra["friction.v_reg"] = vreg
    case, problem, st = _setup(**{k: v for k, v in extra.items()})
    run = SteadyRun(problem, st, case.plate.length)
    status = run.run().status
    s3 = Spread3D(run, 0.005, edge=0.0025)
    s3.solve()
    f = s3.figures()
    print(f"Tresca {factor} v_reg {vreg}: 2D {status} fs {run.state.history[-1]['forward_slip']:.4f}; spread {f['spread']*1e3:.4f} mm force/width ratio {f['roll_force_per_width']/run.state.history[-1]['roll_force']:.4f} settled {s3.settled}")
