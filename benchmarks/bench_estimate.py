"""Benchmark (not a test): the memory and time estimate made before meshing (workflows/estimate.py)
against what runs really take. The fits in workflows/estimate.py come from this table.

Part 1, the mesh count: for bundled passes, sizes and both methods, the estimated triangles
against the mesh the solver builds (no solve). Part 2, the cost: Example 1, steady, one
thread, for contact sizes from 30 mm to 0.8 mm, each in a fresh process: unknowns, Newton
iterations, solver seconds and peak resident memory beside the estimate. Results:
benchmarks/results/bench_estimate.md (and .csv).

    python benchmarks/bench_estimate.py                      # both parts (about 12 min)
    python benchmarks/bench_estimate.py --sizes 0.03,0.01    # a quick look
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "scripts"))

from _common import print_table, write_table  # noqa: E402

MESH_CASES = [("example1", {"solver.method": "steady"}),
              ("example1", {"solver.method": "steady", "mesh.h_contact": 0.01}),
              ("example1", {"solver.method": "steady", "mesh.h_contact": "F2"}),
              ("hot_strip_finishing", {}), ("roughing_slab", {}), ("hot_aluminium", {}),
              ("tension_pass", {}), ("example1", {"mesh.h_contact": 0.02}), ("example1", {})]

COST = r'''
import json, resource, sys, time
from hotroll.config.case import load_case
from hotroll.workflows.estimate import estimate
from hotroll.examples import example_path
from hotroll.workflows.runner import run_case
h, out = float(sys.argv[1]), sys.argv[2]
case = load_case(example_path("example1")).with_overrides(**{
    "solver.method": "steady", "mesh.h_contact": h, "solver.threads": 1,
    "output.figures": False, "output.vtk": False, "solver.force": True})
est = estimate(case)
s = run_case(case, out, resume=False)
print(json.dumps({"h_mm": 1e3 * h, "dofs": s["dofs"], "est_dofs": est.dofs,
                  "newton": s["nonlinear_iterations"], "solve_s": round(s["wall_time_s"], 2),
                  "est_s": round(est.seconds, 2),
                  "peak_MB": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024),
                  "est_MB": round(est.memory_bytes / 1e6)}))
'''


def mesh_rows() -> list[dict]:
    from hotroll.config.case import load_case
    from hotroll.examples import example_path
    from hotroll.fem.mesh import build_plate_mesh
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.estimate import estimate
    from hotroll.workflows.runner import build_model, steady_settings

    rows = []
    for name, over in MESH_CASES:
        case = load_case(example_path(name)).with_overrides(**over)
        est = estimate(case)
        model, _ = build_model(case)
        if case.solver.method == "steady":
            mesh = SteadyRun(model, steady_settings(case), case.plate.length).mesh
        else:
            mesh = build_plate_mesh(case.pass_.roll_pass(), case.plate.length, model.mesh)
        rows.append({"case": name, "overrides": json.dumps(over), "est_triangles": est.triangles,
                     "triangles": mesh.ne, "ratio": round(mesh.ne / est.triangles, 3)})
        print(rows[-1], flush=True)
    return rows


def cost_rows(sizes: list[float], tmp: Path) -> list[dict]:
    rows = []
    env = {**os.environ, "NGS_NUM_THREADS": "1"}
    for h in sizes:
        r = subprocess.run([sys.executable, "-c", COST, str(h), str(tmp / f"h{h:g}")],
                           capture_output=True, text=True, env=env)
        if r.returncode != 0:
            raise SystemExit(f"h = {h}: {r.stderr[-800:]}")
        rows.append(json.loads(r.stdout.strip().splitlines()[-1]))
        print(rows[-1], flush=True)
    return rows


def main(argv=None) -> int:
    import tempfile

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--sizes", default="0.03,0.01,0.0042,0.002,0.0012,0.0008",
                   help="contact mesh sizes in m (part 2)")
    p.add_argument("--out", type=Path, default=HERE / "results" / "bench_estimate")
    args = p.parse_args(argv)
    mesh = mesh_rows()
    with tempfile.TemporaryDirectory() as tmp:
        cost = cost_rows([float(x) for x in args.sizes.split(",")], Path(tmp))
    write_table(mesh, list(mesh[0]), args.out.with_name(args.out.name + "_mesh"),
                title="estimated against built triangles")
    write_table(cost, list(cost[0]), args.out, title="Example 1, steady, one thread: "
                "estimate against measurement", notes=["peak_MB: the process's peak resident "
                                                       "memory; solve_s: summary wall_time_s"])
    print_table(mesh, list(mesh[0]), "triangles")
    print_table(cost, list(cost[0]), "cost")
    return 0


if __name__ == "__main__":
    sys.exit(main())
