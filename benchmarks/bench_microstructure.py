"""Benchmark (not a test): what the recrystallisation kinetics cost in a schedule (issue 33).

Rolls the bundled finishing_mill_microstructure schedule (six stands, thermal, mass-flow
speeds, Hodgson and Gibbs' kinetics) in this process, with timers around the two parts the
kinetics add: the streamline histories of each pass (``solvers/streamlines.streamline_means``,
called once per FE solve, also by the mass-flow correction solves) and the softening over each
transport (``workflows/microstructure.deformed`` + ``after_transport``, with the recorded
cooling's extra memory). Target: the kinetics cost less than 10 % of a pass's solve.

Columns per stand: the stand's wall time (its FE solves, s), the streamline time (s), the
softening time (s) and their share of the stand's time. Warm: the process has imported
NGSolve and compiled nothing for the schedule before the first stand (cold for F1's forms).

    python benchmarks/bench_microstructure.py      # about 30 s on 2 cores
Written to benchmarks/results/bench_microstructure.{csv,md}.
"""
from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "scripts"))

from _common import print_table, write_table  # noqa: E402

COLUMNS = ["stand", "stand_wall_s", "fe_solves", "streamlines_s", "softening_s",
           "kinetics_share"]


def _timed(module, name: str, bucket: list):
    inner = getattr(module, name)

    def wrapper(*args, **kwargs):
        t0 = time.perf_counter()
        try:
            return inner(*args, **kwargs)
        finally:
            bucket.append(time.perf_counter() - t0)

    setattr(module, name, wrapper)


def main() -> None:
    from hotroll.config.schedule import load_schedule
    from hotroll.examples import schedule_path
    from hotroll.results import profiles
    from hotroll.workflows import microstructure as MS
    from hotroll.workflows.schedule import run_schedule

    lines, soft = [], []
    _timed(profiles, "streamline_means", lines)
    _timed(MS, "deformed", soft)
    _timed(MS, "after_transport", soft)
    sch = load_schedule(schedule_path("finishing_mill_microstructure"))
    marks = []
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        rows = run_schedule(sch, Path(tmp), resume=False, figure=False,
                            progress=lambda m: marks.append((len(lines), len(soft))))
        total = time.perf_counter() - t0
    out, start = [], (0, 0)
    for r, (nl, ns) in zip(rows, marks):
        t_lines, t_soft = sum(lines[start[0]:nl]), sum(soft[start[1]:ns])
        out.append({"stand": r["name"], "stand_wall_s": r["wall_time"],
                    "fe_solves": r["fe_solves"], "streamlines_s": t_lines,
                    "softening_s": t_soft,
                    "kinetics_share": (t_lines + t_soft) / r["wall_time"]})
        start = (nl, ns)
    t_k = sum(lines) + sum(soft)
    out.append({"stand": "all", "stand_wall_s": sum(r["wall_time"] for r in rows),
                "fe_solves": sum(r["fe_solves"] for r in rows), "streamlines_s": sum(lines),
                "softening_s": sum(soft), "kinetics_share": t_k / total})
    title = "finishing_mill_microstructure: the kinetics' cost per stand (2 threads)"
    print_table(out, COLUMNS, title)
    write_table(out, COLUMNS, HERE / "results" / "bench_microstructure", title=title,
                notes=[f"whole schedule {total:.1f} s (in process, figures off); the stand's "
                       "wall time includes its streamlines; the softening runs after it"])


if __name__ == "__main__":
    main()
