"""Benchmark (not a test): throughput of a 200-case study on 2 cores (issue 18), serial against
a local dask cluster of 2 workers, warm starts on and off.

The study: the hot strip finishing pass (hotroll/examples/cases/hot_strip_finishing.toml, its
automatic mesh, steady solver, figures and VTK off) over 20 exit thicknesses
(8 mm -> 5.0-7.2 mm, 10-38 % reduction) x 10 roll speeds
(7-21 rad/s, 2.5-7.4 m/s).
Each mode is one fresh ``hotroll study`` process (imports, cluster start, meshing and form
compilation included: cold); the table gives the wall time and cases per minute, and for the
cluster the speed-up over serial. Results: benchmarks/results/bench_study.md (and .csv).

    python benchmarks/bench_study.py                       # 200 cases, all modes
    python benchmarks/bench_study.py --cases 40 --modes serial,cluster
"""
from __future__ import annotations

import argparse
import csv
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "scripts"))

from _common import print_table, write_table  # noqa: E402

COLUMNS = ["mode", "workers", "warm_start", "cases", "done", "wall_s", "cases_per_min",
           "speedup", "mean_case_s", "newton_per_case"]


def study_text(n_thick: int, n_speed: int, warm: bool) -> str:
    return f"""name = "throughput"
[base]
example = "hot_strip_finishing"
set = {{ "output.figures" = false, "output.vtk" = false }}
[vary]
"pass.exit_thickness" = {{ start = 0.0050, stop = 0.0072, num = {n_thick} }}
"pass.roll_angular_velocity" = {{ start = 7.0, stop = 21.0, num = {n_speed} }}
[run]
warm_start = {str(warm).lower()}
"""


def run_mode(mode: str, n_thick: int, n_speed: int, warm: bool) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "study.toml"
        path.write_text(study_text(n_thick, n_speed, warm))
        cmd = [sys.executable, "-m", "hotroll.cli", "study", str(path), "--out",
               str(Path(tmp) / "out")]
        cmd += ["--serial"] if mode == "serial" else ["--workers", "2"]
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        with open(Path(tmp) / "out" / "study.csv", newline="") as f:
            rows = list(csv.DictReader(f))
    if proc.returncode not in (0,) and not 64 <= proc.returncode < 128:
        raise SystemExit(f"{mode}: study failed ({proc.returncode}): {proc.stderr[-600:]}")
    done = [r for r in rows if r["status"] == "done"]
    n = len(rows)

    def mean(key):
        vals = [float(r[key]) for r in done if r.get(key) not in (None, "")]
        return sum(vals) / len(vals) if vals else float("nan")

    return {"mode": mode, "workers": 1 if mode == "serial" else 2, "warm_start": warm,
            "cases": n, "done": len(done), "wall_s": round(wall, 1),
            "cases_per_min": round(60.0 * n / wall, 1), "mean_case_s": round(mean(
                "wall_time_s"), 3), "newton_per_case": round(mean("nonlinear_iterations"), 1)}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cases", type=int, default=200, help="10 x this/10 cases")
    p.add_argument("--modes", default="serial,cluster,serial-cold,cluster-cold")
    p.add_argument("--out", type=Path, default=HERE / "results" / "bench_study")
    args = p.parse_args(argv)
    n_speed = 10
    n_thick = max(2, args.cases // n_speed)          # a range needs 2 values at least
    rows = []
    for mode in args.modes.split(","):
        base, _, cold = mode.partition("-")
        row = run_mode(base, n_thick, n_speed, warm=not cold)
        row["mode"] = mode
        rows.append(row)
        print(f"{mode}: {row['cases']} cases in {row['wall_s']} s, {row['cases_per_min']} "
              f"cases/min", flush=True)
    for r in rows:
        ref = next((s for s in rows if s["mode"] == ("serial" + r["mode"][len(
            r["mode"].split("-")[0]):])), None)
        r["speedup"] = round(ref["wall_s"] / r["wall_s"], 2) if ref else None
    args.out.parent.mkdir(parents=True, exist_ok=True)
    write_table(rows, COLUMNS, args.out, title="hotroll study: throughput on 2 cores (cold "
                "processes; wall_s includes imports, cluster start, meshing)", notes=[
                    "cases_per_min = cases / wall_s x 60; speedup: against serial with the "
                    "same warm_start; mean_case_s: the solver's own time per case (summary "
                    "wall_time_s), newton_per_case: Newton iterations per case."])
    print_table(rows, COLUMNS, "hotroll study throughput")
    return 0


if __name__ == "__main__":
    sys.exit(main())
