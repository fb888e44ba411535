"""Benchmark (not a test): Example 1 of the report to steady state on the meshes C1 and C2,
with the Newton and the Picard nonlinear solver.

This is slow.  On a 2-core machine Newton reached the steady state on C2 in 23 min (549
steps; 39 min for the whole command at 3b1583e, 2026-11-28: benchmarks/bench_claims.py
--transient; C1, 495 steps, took 25 min before the BLAS-thread and Jacobian speed-ups,
which made C2 1.7 times faster); Picard needs 17-18 iterations a step against Newton's 7-8,
about 2.5 times as long, so the default four runs (C1, C2 x newton, picard) need some 2-3
hours.  Use ``--end-time`` to cap the simulated time (the run
then stops with status ``end_time`` before the steady state) and ``--meshes``/``--methods``
to choose a subset.  Not collected by pytest.

Every run goes to OUT/<mesh>_<method> (default results/bench_example1); the table is printed
and written to benchmarks/results/bench_example1.md (``--report`` to change).  Runs start
afresh by default so that the wall times are those of complete runs (``--resume`` reuses
finished runs and continues interrupted ones; their wall time is then only the last part).

    python benchmarks/bench_example1.py
    python benchmarks/bench_example1.py --meshes C1 --methods newton --end-time 0.2
    python benchmarks/bench_example1.py --meshes 0.015 --end-time 0.005 \\
        --out /tmp/bench --report /tmp/bench/bench_example1.md            # smoke test
"""
from __future__ import annotations

import argparse
import datetime
import os
import platform
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "scripts"))

from _common import (  # noqa: E402
    add_common_args,
    common_overrides,
    flat,
    list_arg,
    make_case,
    mesh_arg,
    mesh_label,
    print_table,
    run,
    write_table,
)

METHODS = ("newton", "picard")
COLUMNS = ["mesh", "method", "dofs", "steps", "status", "neutral_x", "neutral_y",
           "neutral_angle", "roll_force", "a_f", "iterations_per_step", "wall_time_s",
           "time_per_step_s"]


def method_arg(text: str) -> str:
    text = text.strip().lower()
    if text not in METHODS:
        raise argparse.ArgumentTypeError(f"{text!r}: method must be one of {', '.join(METHODS)}")
    return text


def machine() -> str:
    import ngsolve

    return (f"{platform.node()} ({platform.machine()}, {os.cpu_count()} CPUs), "
            f"Python {platform.python_version()}, NGSolve {ngsolve.__version__}")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--meshes", type=list_arg(mesh_arg), default=["C1", "C2"],
                   help="comma-separated Table 2 names and/or sizes h in m (default C1,C2)")
    p.add_argument("--methods", type=list_arg(method_arg), default=list(METHODS),
                   help="comma-separated nonlinear solvers (default newton,picard)")
    p.add_argument("--report", type=Path, default=HERE / "results" / "bench_example1.md",
                   help="Markdown report (default benchmarks/results/bench_example1.md)")
    add_common_args(p, "results/bench_example1", resume=False)
    args = p.parse_args(argv)

    over = common_overrides(args)
    cases = {(mesh_label(m), meth): make_case(p, **over, **{"mesh.h_contact": m,
                                                             "solver.nonlinear": meth})
             for m in args.meshes for meth in args.methods}
    threads = next(iter(cases.values())).solver.threads
    title = "Benchmark: Example 1 to steady state"
    notes = [f"{datetime.datetime.now():%Y-%m-%d %H:%M}, {machine()}, {threads} NGSolve "
             f"thread(s) per run" + (f", end time capped at {args.end_time:g} s"
                                     if args.end_time is not None else "") + ".",
             "wall_time_s: setup and time stepping of the run (of its last invocation when "
             "resumed); time_per_step_s = wall_time_s / steps.",
             "neutral point (x, y) in m, neutral_angle in rad, roll force per unit width, "
             "a_f in m^-m (mean over the last averaging window)."]
    rows = []
    for (mesh, meth), case in cases.items():
        summary = run(case, args.out / f"{mesh}_{meth}", f"{mesh} {meth}", resume=args.resume)
        wall, steps = summary.get("wall_time_s"), summary.get("steps")
        rows.append(flat(summary, mesh=mesh, method=meth,
                         time_per_step_s=wall / steps if wall is not None and steps else None))
        write_table(rows, COLUMNS, args.report.with_suffix(""), title=title, notes=notes,
                    csv=False)
    print_table(rows, COLUMNS, title)
    print(f"report: {args.report}")
    return 0 if all(r.get("status") in ("steady", "end_time") for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
