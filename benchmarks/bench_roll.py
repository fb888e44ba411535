"""Benchmark (not a test): the work roll's models side by side (issue 32).

Part 1, passes: hot_strip_finishing (8 -> 6 mm) and thin_strip (2.4 -> 2.0 mm) with a rigid
roll, Hitchcock's flattening and the elastic disc, each in a fresh subprocess (cold: meshing
and output included). Columns: Newton iterations, roll updates, wall time and its ratio to the
rigid roll's (target: elastic at most 2x), roll force, contact length, R_eq/R, flattening,
exit code.

Part 2, the bundled finishing_mill schedule (six stands, 35 -> 3.9 mm, mass-flow speeds,
thermal) with each roll model: per stand the force, R_eq/R, FE solves, Newton iterations and
wall time (each stand warm-started from the one before).

Written to benchmarks/results/bench_roll.{csv,md} and bench_roll_schedule.{csv,md}.

    python benchmarks/bench_roll.py                     # all (about 6 minutes on 2 cores)
    python benchmarks/bench_roll.py --parts passes --models rigid,elastic
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "scripts"))

from _common import list_arg, print_table, write_table  # noqa: E402

MODELS = ["rigid", "hitchcock", "elastic"]
CASES = ["hot_strip_finishing", "thin_strip"]
PASS_COLUMNS = ["case", "roll", "newton_iterations", "roll_updates", "wall_s", "wall_over_rigid",
                "roll_force", "contact_length", "R_eq_over_R", "roll_flattening", "exit_code"]
STAND_COLUMNS = ["roll", "stand", "exit_thickness", "roll_force", "R_eq_over_R", "fe_solves",
                 "newton_iterations", "wall_s"]


def one_pass(name: str, model: str, threads: int) -> dict:
    from hotroll.config.case import load_case
    from hotroll.examples import example_path
    from hotroll.workflows.runner import run_case

    case = load_case(example_path(name)).with_overrides(**{
        "roll.model": model, "solver.threads": threads, "output.figures": False,
        "output.vtk": False})
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        s = run_case(case, Path(tmp), resume=False)
    R = case.pass_.roll_radius
    return {"case": name, "roll": model, "newton_iterations": s["nonlinear_iterations"],
            "roll_updates": s.get("roll_updates"), "wall_s": time.perf_counter() - t0,
            "roll_force": s["roll_force"], "contact_length": s["contact_length"],
            "R_eq_over_R": s.get("roll_equivalent_radius", R) / R,
            "roll_flattening": s.get("roll_flattening"), "exit_code": s["exit_code"]}


def one_schedule(model: str, threads: int) -> list[dict]:
    from hotroll.config.schedule import load_schedule
    from hotroll.examples import schedule_path
    from hotroll.workflows.schedule import run_schedule

    sch = load_schedule(schedule_path("finishing_mill"))
    sch = sch.model_copy(update={"roll": sch.roll.model_copy(update={"model": model}),
                                 "solver": sch.solver.model_copy(update={"threads": threads})})
    with tempfile.TemporaryDirectory() as tmp:
        rows = run_schedule(sch, Path(tmp), resume=False, figure=False)
    return [{"roll": model, "stand": r["name"], "exit_thickness": r["exit_thickness"],
             "roll_force": r["roll_force"],
             "R_eq_over_R": r.get("roll_equivalent_radius", r["roll_radius"]) / r["roll_radius"],
             "fe_solves": r["fe_solves"], "newton_iterations": r["newton_iterations"],
             "wall_s": r["wall_time"]} for r in rows]


def _sub(args: list[str]):
    proc = subprocess.run([sys.executable, __file__, *args], capture_output=True, text=True)
    line = [ln for ln in proc.stdout.splitlines() if ln.startswith("ROW ")]
    if proc.returncode or not line:
        print(f"{args}: failed\n{proc.stderr[-2000:]}", file=sys.stderr)
        return None
    return json.loads(line[-1][4:])


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--parts", type=list_arg(str), default=["passes", "schedule"])
    p.add_argument("--cases", type=list_arg(str), default=CASES)
    p.add_argument("--models", type=list_arg(str), default=MODELS)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--one", nargs="+", default=None, help=argparse.SUPPRESS)
    p.add_argument("--report", type=Path, default=HERE / "results" / "bench_roll")
    args = p.parse_args(argv)
    if args.one is not None:
        row = (one_pass(*args.one, args.threads) if len(args.one) == 2
               else one_schedule(args.one[0], args.threads))
        print("ROW " + json.dumps(row))
        return 0
    note = (f"{args.threads} threads, cold (a fresh process per run, meshing and output "
            "included); steady solver; the cases' own meshes.")
    if "passes" in args.parts:
        rows = []
        for name in args.cases:
            rigid = None
            for model in args.models:
                row = _sub(["--one", name, model, "--threads", str(args.threads)])
                if row is None:
                    continue
                rigid = row["wall_s"] if model == "rigid" else rigid
                row["wall_over_rigid"] = row["wall_s"] / rigid if rigid else None
                rows.append(row)
                write_table(rows, PASS_COLUMNS, args.report, title="Roll models: passes",
                            notes=[note])
        print_table(rows, PASS_COLUMNS, "Roll models: passes")
    if "schedule" in args.parts:
        stands = []
        for model in args.models:
            stands += _sub(["--one", model, "--threads", str(args.threads)]) or []
            write_table(stands, STAND_COLUMNS, Path(f"{args.report}_schedule"),
                        title="Roll models: finishing_mill schedule", notes=[note])
        print_table(stands, STAND_COLUMNS, "Roll models: finishing_mill schedule")
    return 0


if __name__ == "__main__":
    sys.exit(main())
