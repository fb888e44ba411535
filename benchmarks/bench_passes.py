"""Benchmark (not a test): the bundled passes with the steady solver on the automatic mesh.

One fresh process per pass (`hotroll run`, figures and VTK off), so that every row is a cold run:
DOFs, Newton iterations, the solver's wall time (meshing included; Python start and imports
excluded: `wall_total_s` has them), the roll force, torque, forward slip and the balance errors.

    python benchmarks/bench_passes.py                       # all realistic passes and Example 1
    python benchmarks/bench_passes.py --cases hot_strip_finishing     (2 threads: the cases' own)
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

CASES = ["example1", "hot_strip_finishing", "roughing_slab", "hot_aluminium", "tension_pass"]
COLUMNS = ["case", "friction", "material", "h_contact_m", "dofs", "newton_iterations",
           "wall_s", "wall_total_s", "roll_force_MN_per_m", "roll_torque_kNm_per_m",
           "forward_slip_pct", "neutral_angle_rad", "balance_error", "power_balance_error",
           "converged"]


def one(name: str) -> dict:
    from hotroll.examples import example_path

    with tempfile.TemporaryDirectory() as tmp:
        cmd = [sys.executable, "-m", "hotroll.cli", "run", str(example_path(name)),
               "--out", tmp, "--no-figures"]
        over = ["--mesh", "auto"]
        t0 = time.perf_counter()
        proc = subprocess.run(cmd + over + ["--method", "steady"], capture_output=True, text=True)
        total = time.perf_counter() - t0
        if proc.returncode != 0:
            return {"case": name, "converged": f"failed: {proc.stderr.strip()[-200:]}"}
        s = json.loads((Path(tmp) / "summary.json").read_text())
    return {"case": name, "friction": s.get("friction_law"),
            "material": "hensel-spittel" if s.get("exit_strain") is not None else "norton-hoff",
            "h_contact_m": s["h_contact"], "dofs": s["dofs"],
            "newton_iterations": s["nonlinear_iterations"], "wall_s": s["wall_time_s"],
            "wall_total_s": total, "roll_force_MN_per_m": s["roll_force"] / 1e6,
            "roll_torque_kNm_per_m": s["roll_torque"] / 1e3,
            "forward_slip_pct": 100 * s["forward_slip"], "neutral_angle_rad": s["neutral_angle"],
            "balance_error": s["balance_error"], "power_balance_error": s["power_balance_error"],
            "converged": s["converged"]}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cases", type=list_arg(str), default=CASES)
    p.add_argument("--out", type=Path, default=HERE / "results" / "bench_passes")
    args = p.parse_args(argv)
    rows = [one(name) for name in args.cases]
    title = "Bundled passes, steady solver, automatic mesh (cold process each)"
    write_table(rows, COLUMNS, args.out, title=title,
                notes=["wall_s: the solver's own wall time with meshing; wall_total_s: the "
                       "whole command (Python start, imports, output)."])
    print_table(rows, COLUMNS, title)
    return 0


if __name__ == "__main__":
    sys.exit(main())
