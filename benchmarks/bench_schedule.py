"""Benchmark (not a test): a six-pass finishing schedule (issue 17's target: under 10 s with
warm starts on 2 cores).

Each repeat is one fresh process, ``hotroll schedule finishing_mill --no-figures`` (cold:
imports, meshing and form compilation included), with each pass started from the previous one
mapped onto its mesh (the default) and, alternated, from the slab guess (``--cold``). The
table keeps, per pass, the median wall time, the FE solves (a tandem stand is solved again at
the speed that passes the first stand's mass flux) and the Newton iterations, and the whole
command's wall time.

    python benchmarks/bench_schedule.py                 # 3 repeats, both starts
    python benchmarks/bench_schedule.py --repeat 1 --schedule my_schedule.toml
"""
from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "scripts"))

from _common import print_table, to_toml, write_table  # noqa: E402

COLUMNS = ["pass", "h0_h1_mm", "U_m_s", "force_MN_m", "fe_solves", "newton", "s",
           "cold_fe_solves", "cold_newton", "cold_s"]


def _run(schedule: Path, threads: int, cold: bool) -> tuple[float, dict]:
    """One fresh `hotroll schedule` process: (command wall time s, schedule.json)."""
    data = tomllib.loads(schedule.read_text())
    data.setdefault("mill", {})["start_from_previous"] = not cold
    data.setdefault("solver", {})["threads"] = threads
    data.setdefault("output", {}).update(figures=False, vtk=False)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "schedule.toml"
        path.write_text(to_toml(data))
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "hotroll.cli", "schedule", str(path),
                               "--out", str(Path(tmp) / "out"), "--no-figures"],
                              capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if proc.returncode != 0:
            raise SystemExit(f"schedule failed: {proc.stderr.strip()[-400:]}")
        return wall, json.loads((Path(tmp) / "out" / "schedule.json").read_text())


def main(argv=None) -> int:
    from hotroll.examples import schedule_path

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--schedule", type=Path, default=schedule_path("finishing_mill"))
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--out", type=Path, default=HERE / "results" / "bench_schedule")
    args = p.parse_args(argv)
    warm, cold = [], []
    for _ in range(args.repeat):            # alternated: slow spells of the machine hit both
        warm.append(_run(args.schedule, args.threads, cold=False))
        cold.append(_run(args.schedule, args.threads, cold=True))
    rows = []
    for k, r in enumerate(warm[-1][1]["passes"]):
        c = cold[-1][1]["passes"][k]
        rows.append({
            "pass": r["name"],
            "h0_h1_mm": f"{1e3 * r['entry_thickness']:.2f} -> {1e3 * r['exit_thickness']:.2f}",
            "U_m_s": r["roll_surface_speed"], "force_MN_m": r["roll_force"] / 1e6,
            "fe_solves": r["fe_solves"], "newton": r["newton_iterations"],
            "s": statistics.median(w[1]["passes"][k]["wall_time"] for w in warm),
            "cold_fe_solves": c["fe_solves"], "cold_newton": c["newton_iterations"],
            "cold_s": statistics.median(w[1]["passes"][k]["wall_time"] for w in cold)})
    total = {"pass": "all passes", "fe_solves": sum(r["fe_solves"] for r in rows),
             "newton": sum(r["newton"] for r in rows), "s": sum(r["s"] for r in rows),
             "cold_fe_solves": sum(r["cold_fe_solves"] for r in rows),
             "cold_newton": sum(r["cold_newton"] for r in rows),
             "cold_s": sum(r["cold_s"] for r in rows)}
    command = {"pass": "whole command (process)",
               "s": statistics.median(w[0] for w in warm),
               "cold_s": statistics.median(w[0] for w in cold)}
    rows += [total, command]
    title = (f"Schedule {args.schedule.stem}: median of {args.repeat} fresh processes, "
             f"{args.threads} threads; s: each pass from the previous one, cold_s: each from "
             f"the slab guess")
    write_table(rows, COLUMNS, args.out, title=title,
                notes=["s: wall time of the pass (its FE solves, output, transport); the "
                       "whole command adds Python's and NGSolve's imports. Target: the whole "
                       "schedule under 10 s."])
    print_table(rows, COLUMNS, title)
    return 0


if __name__ == "__main__":
    sys.exit(main())
