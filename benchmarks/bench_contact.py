"""Benchmark (not a test): the roll contact's formulations side by side (issue 30).

For every bundled example (steady solver, automatic mesh) and Example 1 at C2 and M2: the
report's penalty (Table 1), exact contact held to the whole arc (bilateral multiplier) and
exact unilateral contact (the default), each in a fresh subprocess on 2 threads. Columns: DOFs,
Newton iterations, wall time (meshing included: cold), roll force, torque, forward slip,
neutral angle, how the contact ends and the separation angle (issue 50), the leak (mass-flux
error) and the penalty share, the most tensile contact stress over the peak pressure, the exit
code. Figures are printed and written to benchmarks/results/bench_contact.{csv,md}.

    python benchmarks/bench_contact.py                     # all (about 3 minutes)
    python benchmarks/bench_contact.py --cases example1@M2 --methods penalty,bilateral
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

COLUMNS = ["case", "contact", "dofs", "newton_iterations", "wall_s", "roll_force",
           "roll_torque", "forward_slip", "neutral_angle", "contact_end_kind",
           "separation_angle", "mass_flux_error", "penalty_share", "tensile_over_peak",
           "exit_code"]
METHODS = {"penalty": {"contact.method": "penalty"},
           "bilateral": {"contact.method": "multiplier", "contact.unilateral": False},
           "unilateral": {"contact.method": "multiplier", "contact.unilateral": True}}
CASES = ["example1@C1", "example1@C2", "example1@M2", "example2", "hot_strip_finishing",
         "roughing_slab", "hot_aluminium", "tension_pass", "thermal_pass", "thin_strip"]


def one(name: str, method: str, threads: int) -> dict:
    """Run one case in this process and return its row."""
    from hotroll.config.case import load_case
    from hotroll.examples import example_path
    from hotroll.workflows.runner import run_case

    example, _, mesh = name.partition("@")
    over = {"solver.method": "steady", "solver.threads": threads, "output.figures": False,
            "output.vtk": False, **METHODS[method]}
    if mesh:
        over["mesh.h_contact"] = mesh
    case = load_case(example_path(example)).with_overrides(**over)
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        s = run_case(case, Path(tmp), resume=False)
        import csv

        with open(Path(tmp) / "contact.csv") as f:
            sn = [float(r["normal_stress"]) for r in csv.DictReader(f)]
    wall = time.perf_counter() - t0
    peak = max(-min(sn), 1e-300)
    return {"case": name, "contact": method, "dofs": s["dofs"],
            "newton_iterations": s["nonlinear_iterations"], "wall_s": wall,
            **{k: s.get(k) for k in ("roll_force", "roll_torque", "forward_slip",
                                     "neutral_angle", "contact_end_kind", "separation_angle",
                                     "mass_flux_error", "penalty_share", "exit_code")},
            "tensile_over_peak": max(max(sn), 0.0) / peak}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cases", type=list_arg(str), default=CASES)
    p.add_argument("--methods", type=list_arg(str), default=list(METHODS))
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--one", nargs=2, default=None, help=argparse.SUPPRESS)
    p.add_argument("--report", type=Path, default=HERE / "results" / "bench_contact")
    args = p.parse_args(argv)
    if args.one is not None:
        print("ROW " + json.dumps(one(*args.one, args.threads)))
        return 0
    rows = []
    for name in args.cases:
        for method in args.methods:
            cmd = [sys.executable, __file__, "--one", name, method, "--threads",
                   str(args.threads)]
            proc = subprocess.run(cmd, capture_output=True, text=True)
            line = [ln for ln in proc.stdout.splitlines() if ln.startswith("ROW ")]
            if proc.returncode or not line:
                print(f"{name} {method}: failed\n{proc.stderr[-2000:]}", file=sys.stderr)
                continue
            rows.append(json.loads(line[-1][4:]))
            write_table(rows, COLUMNS, args.report, title="Roll contact: penalty vs exact",
                        notes=[f"{args.threads} threads, cold (a fresh process per run, "
                               "meshing and output included); steady solver; automatic mesh "
                               "unless @mesh; tensile_over_peak: the most tensile raw contact "
                               "stress over the peak pressure."])
    print_table(rows, COLUMNS, "Roll contact: penalty vs exact")
    return 0


if __name__ == "__main__":
    sys.exit(main())
