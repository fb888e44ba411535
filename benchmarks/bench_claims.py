"""Benchmark (not a test): the wall times the README and the how-to pages quote, measured as a
user waits for them (issue 51, item 8).

Each row is one command the docs give, run as written in a fresh process (start-up, meshing,
solve, output and figures included; cold: a new output directory, no warm start), ``--repeat``
times, the median kept with the spread. The machine (cores, CPU, memory), the commit and the
load average before the runs are written beside the table, so a page quoting a figure can name
this benchmark, its commit and its date. ``--transient`` adds the report's own scheme on C2
run to its steady state, once (the README's transient figure; about 20 minutes).

    python benchmarks/bench_claims.py                    # about 3 minutes on 2 cores
    python benchmarks/bench_claims.py --repeat 1 --transient

Prints the table and writes benchmarks/results/bench_claims.{csv,md}.
"""
from __future__ import annotations

import argparse
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "scripts"))

from _common import print_table, write_table  # noqa: E402

#: (where the docs quote it, the command as the docs write it, without its --out)
CLAIMS = [
    ("README: Example 1 on C2", ["example", "1", "--mesh", "C2"]),
    ("how-to/schedules.md: finishing_mill", ["schedule", "finishing_mill"]),
    ("how-to/thermal.md: hot_strip_finishing_thermal",
     ["example", "hot_strip_finishing_thermal"]),
]
TRANSIENT = ("README: Example 1 on C2, the report's scheme",
             ["example", "1", "--mesh", "C2", "--method", "transient"])


def _machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        mem = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    except (ValueError, OSError, AttributeError):
        mem = float("nan")
    return f"{os.cpu_count()} cores, {cpu}, {mem:.0f} GiB"


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--transient", action="store_true", help="also the report's scheme on C2")
    args = p.parse_args()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True).stdout.strip() or "?"
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    claims = CLAIMS + ([TRANSIENT] if args.transient else [])
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for where, cmd in claims:
            repeat = 1 if "transient" in cmd else args.repeat
            walls, codes = [], set()
            for k in range(repeat):
                out = Path(tmp) / f"{len(rows)}_{k}"
                t0 = time.perf_counter()
                r = subprocess.run([sys.executable, "-m", "hotroll.cli", *cmd, "--out", str(out)],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                walls.append(time.perf_counter() - t0)
                codes.add(r.returncode)
            rows.append({"claim": where, "command": "hotroll " + " ".join(cmd),
                         "runs": repeat, "median_s": round(statistics.median(walls), 1),
                         "min_s": round(min(walls), 1), "max_s": round(max(walls), 1),
                         "exit_codes": "/".join(map(str, sorted(codes)))})
    notes = [f"commit {commit}, {time.strftime('%Y-%m-%d', time.gmtime())}, {_machine()}; "
             f"load average before the runs {load:.2f}; whole commands in fresh processes, "
             "cold, figures included; the defaults' threads ([solver] threads = \"auto\")."]
    columns = list(rows[0])
    print_table(rows, columns)
    print(notes[0])
    write_table(rows, columns, HERE / "results" / "bench_claims", title="Quoted wall times",
                notes=notes)


if __name__ == "__main__":
    main()
