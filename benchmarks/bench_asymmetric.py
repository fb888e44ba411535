"""The full-thickness strip's cost against the half model's (issue 52: an asymmetric pass at
most 2.5x the time of the same pass's half model).

    python benchmarks/bench_asymmetric.py [--repeat 3] [--h 1e-3] [--ratio 1.15]
    python benchmarks/bench_asymmetric.py --example [--repeat 3]     # the bundled asymmetric_plate

Case R of ../shared/notes/asymmetric-rolling.md (R = 250 mm, 10 -> 8 mm, Tresca 0.3, Norton-Hoff
m = 0.05), solved in one process: the half model (today's path, its default coupling threshold),
the full strip with two equal rolls and with the upper roll ``--ratio`` times faster. Each run
is a whole solve (mesh, form, the coupled Newton, one history row per solve and coupling update,
as the runner solves); the first of each kind in the process is cold (NGSolve compiles the
forms), the median of the rest warm. ``--example``: the bundled ``asymmetric_plate`` through
``run_case`` as ``hotroll example`` solves it (figures off), against the same pass with equal
rolls (no ``speed_ratio``: the half model). Prints a table: wall seconds (median), Newton iterations,
unknowns, and the ratio to the half model. Time on 2 cores with nothing else running.
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))

from asymmetric_case_r import case_r  # noqa: E402

from hotroll.solvers.full_steady import FullSteadyRun  # noqa: E402
from hotroll.solvers.steady import SteadyRun  # noqa: E402


def solve(kind: str, h: float, ratio: float) -> tuple[float, int, int, str]:
    case, problem, st = case_r(0.05, h)
    rp = problem.rp
    t0 = time.perf_counter()
    if kind == "half":
        run = SteadyRun(problem, st, case.plate.length)
    else:
        r = 1.0 if kind == "full, equal rolls" else ratio
        run = FullSteadyRun(problem, st, case.plate.length,
                            {1: replace(rp, omega=rp.omega * r), -1: rp},
                            {1: problem.friction, -1: problem.friction})
    sol = run.run()
    wall = time.perf_counter() - t0
    its = sum(s.iterations for s in run.result.stats)
    return wall, its, run.form.fes.ndof, sol.status


def solve_example(asymmetric: bool, out: Path) -> tuple[float, int, int, str]:
    """The bundled asymmetric_plate through run_case (with ``asymmetric`` False: without its
    speed ratio, the half model)."""
    from hotroll.config.case import load_case
    from hotroll.examples import example_path
    from hotroll.workflows.runner import run_case

    over = {"output.figures": False} if asymmetric else {"output.figures": False,
                                                         "pass.speed_ratio": None}
    case = load_case(example_path("asymmetric_plate"), over)
    t0 = time.perf_counter()
    s = run_case(case, out, resume=False)
    wall = time.perf_counter() - t0
    return wall, int(s["nonlinear_iterations"]), int(s.get("dofs") or 0), str(s.get("status"))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--h", type=float, default=1e-3, help="contact mesh size, m")
    ap.add_argument("--ratio", type=float, default=1.15, help="upper/lower surface speed")
    ap.add_argument("--example", action="store_true", help="the bundled asymmetric_plate")
    a = ap.parse_args()
    if a.example:
        import tempfile

        rows = {}
        with tempfile.TemporaryDirectory() as tmp:
            for kind, asym in (("half (no speed ratio)", False), ("full, its speed ratio (1.1: wraps)", True)):
                runs = [solve_example(asym, Path(tmp) / f"{asym}{i}") for i in range(a.repeat + 1)]
                rows[kind] = (runs[0][0], statistics.median(r[0] for r in runs[1:]),
                              runs[-1][1], runs[-1][2], runs[-1][3])
        _table("asymmetric_plate (hotroll example), figures off", a.repeat, rows)
        return
    kinds = ("half", "full, equal rolls", f"full, r = {a.ratio:g}")
    rows = {}
    for kind in kinds:
        runs = [solve(kind, a.h, a.ratio) for _ in range(a.repeat + 1)]
        cold, warm = runs[0], runs[1:]
        rows[kind] = (cold[0], statistics.median(r[0] for r in warm), warm[-1][1], warm[-1][2],
                      warm[-1][3])
    _table(f"Case R, h = {a.h:g} m", a.repeat, rows)


def _table(title: str, repeat: int, rows: dict) -> None:
    half_warm = next(iter(rows.values()))[1]
    print(f"{title}, {repeat} warm runs each (median), 2 cores")
    print("| model | status | cold s | warm s | Newton iterations | unknowns | warm / half |")
    print("|---|---|---|---|---|---|---|")
    for kind, (cold, warm, its, dofs, status) in rows.items():
        print(f"| {kind} | {status} | {cold:.2f} | {warm:.2f} | {its} | {dofs} | "
              f"{warm / half_warm:.2f} |")


if __name__ == "__main__":
    main()
