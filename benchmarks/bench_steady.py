"""Benchmark (not a test): the direct steady solver on Example 1 over the meshes of Table 2.

For each mesh, in a fresh subprocess (so that peak memory is that mesh's): DOFs, Newton
iterations (all continuation stages and a_f / free-surface updates), wall time with meshing,
time per factorisation (assembly excluded), the share of time outside the linear solves, peak
memory, a warm-started neighbour (m + 0.01 from the solved state), and the results. With
``--transient`` each mesh also runs the report's scheme to its steady state and the ratio of the
wall times is printed (hours on C1..F2: not the default).

    python benchmarks/bench_steady.py                       # C1,C2,M1,M2,F1,F2
    python benchmarks/bench_steady.py --meshes C1,C2 --threads 2
    python benchmarks/bench_steady.py --meshes 0.01 --transient   # ratio on a coarse mesh
    python benchmarks/bench_steady.py --meshes auto,C2,M2 --a-f estimate,5   # issue 14's targets
"""
from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "scripts"))

from _common import example1, list_arg, mesh_arg, mesh_label, print_table, write_table  # noqa: E402

COLUMNS = ["mesh", "h", "a_f_rule", "dofs", "newton_iterations", "surface_updates", "wall_s",
           "mesh_s", "factorisation_s",
           "outside_linear_share", "peak_memory_mb", "warm_iterations", "warm_s",
           "neutral_angle", "roll_force", "forward_slip", "a_f", "converged", "transient_s",
           "ratio"]


TRANSIENT_KEYS = ("status", "steps", "neutral_angle", "roll_force", "roll_torque",
                  "forward_slip", "a_f", "iterations_per_step")


def one(mesh, threads: int, transient: bool, a_f: str = "estimate") -> dict:
    """Run one mesh in this process and return its row."""
    from dataclasses import replace

    import ngsolve

    from hotroll.fem import quantities as Q
    from hotroll.model.material import NortonHoff
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.runner import build_model, run_case, steady_settings

    ngsolve.SetNumThreads(threads)
    case = example1(**{"mesh.h_contact": mesh, "solver.method": "steady",
                       "friction.a_f": a_f if a_f == "estimate" else float(a_f)})
    model, _ = build_model(case)
    t0 = time.perf_counter()
    run = SteadyRun(model, steady_settings(case), case.plate.length)
    run.record = False
    res = run.solve()
    wall = time.perf_counter() - t0
    row = Q.measure(run.form, run.top, run.d, 1.0, model.h, run.head_x())
    lin = sum(s.time_linear for s in res.stats)
    its = res.iterations
    # warm start: the neighbouring case m + 0.01 from the solved state
    mat = model.material
    run.problem = replace(run.problem, material=NortonHoff(mat.K, mat.m + 0.01, mat.eps0))
    t1 = time.perf_counter()
    warm = run.solve(warm=run.warm_start())
    out = {
        "mesh": mesh_label(mesh), "h": model.h, "a_f_rule": a_f, "dofs": run.dofs,
        "newton_iterations": its, "surface_updates": len(res.surface_moves),
        "wall_s": wall, "mesh_s": res.mesh_time, "factorisation_s": lin / max(its, 1),
        "outside_linear_share": 1.0 - lin / wall,
        "peak_memory_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
        "warm_iterations": warm.iterations, "warm_s": time.perf_counter() - t1,
        "neutral_angle": row["neutral_angle"], "roll_force": row["roll_force"],
        "forward_slip": row["forward_slip"], "a_f": row["a_f"], "converged": res.converged,
    }
    if transient:
        import tempfile

        tcase = case.with_overrides(**{"solver.method": "transient", "solver.threads": threads,
                                       "output.figures": False, "output.vtk": False})
        with tempfile.TemporaryDirectory() as tmp:
            s = run_case(tcase, Path(tmp), resume=False)
        out["transient_s"] = s["wall_time_s"]
        out["ratio"] = s["wall_time_s"] / wall
        out.update({f"transient_{k}": s[k] for k in TRANSIENT_KEYS})
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--meshes", type=list_arg(mesh_arg),
                   default=["C1", "C2", "M1", "M2", "F1", "F2"])
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--a-f", type=list_arg(str), default=["estimate"],
                   help='friction parameters: "estimate" and/or numbers (default estimate)')
    p.add_argument("--transient", action="store_true",
                   help="also run the transient scheme to steady state (slow) for the ratio")
    p.add_argument("--one", default=None, help=argparse.SUPPRESS)
    p.add_argument("--report", type=Path, default=HERE / "results" / "bench_steady")
    args = p.parse_args(argv)
    if args.one is not None:
        print("ROW " + json.dumps(one(mesh_arg(args.one), args.threads, args.transient,
                                      args.a_f[0])))
        return 0
    rows = []
    columns = COLUMNS + ([f"transient_{k}" for k in TRANSIENT_KEYS] if args.transient else [])
    for mesh, a_f in ((m, a) for a in args.a_f for m in args.meshes):
        cmd = [sys.executable, __file__, "--one", mesh_label(mesh), "--threads",
               str(args.threads), "--a-f", a_f] + (["--transient"] if args.transient else [])
        proc = subprocess.run(cmd, capture_output=True, text=True)
        line = [ln for ln in proc.stdout.splitlines() if ln.startswith("ROW ")]
        if proc.returncode or not line:
            print(f"{mesh_label(mesh)}: failed\n{proc.stderr[-2000:]}", file=sys.stderr)
            continue
        rows.append(json.loads(line[-1][4:]))
        args.report.parent.mkdir(parents=True, exist_ok=True)
        write_table(rows, columns, args.report, title="Example 1: direct steady solver",
                    notes=[f"{args.threads} threads; wall_s includes meshing; warm = m + 0.01 "
                           "from the solved state; ratio = transient / steady wall time."])
    print_table(rows, columns, "Example 1: direct steady solver")
    return 0


if __name__ == "__main__":
    sys.exit(main())
