"""Case R on the test mesh across a wide strip, the whole half width or an edge zone
(docs/validation/spread_3d.md, "The edge zone's interior"): one JSON line.

    PYTHONPATH=. python docs/notes/issue53-edge-zone/zone_small.py HALF ZONE|none [EDGE]

HALF, ZONE and EDGE (the edge layer, default 2.5 mm) in m.
"""
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "tests" / "solvers"))
from test_full_strip import _setup  # noqa: E402

from hotroll.solvers.spread_3d import Spread3D  # noqa: E402
from hotroll.solvers.steady import SteadyRun  # noqa: E402

half = float(sys.argv[1])
zone = None if sys.argv[2] == "none" else float(sys.argv[2])
edge = float(sys.argv[3]) if len(sys.argv) > 3 else 0.0025
case, problem, st = _setup()
run = SteadyRun(problem, st, case.plate.length)
assert run.run().status == "steady"
t0 = time.perf_counter()
s3 = Spread3D(run, half, edge=edge, zone=zone)
s3.solve()
f = s3.figures()
two = run.state.history[-1]
print(json.dumps({
    "half": half, "zone": zone, "z": [float(v) for v in s3.z], "dofs": f["dofs"],
    "its": f["newton_iterations"], "rounds": f["rounds"], "spread": f["spread"],
    "fpw": f["roll_force_per_width"] / two["roll_force"],
    "mass": (f["flux_out"] + f["flux_edge"] - f["flux_in"]) / f["flux_in"],
    "power_balance": f["power_balance_error"], "settled": f["settled"],
    "wall": time.perf_counter() - t0}))
