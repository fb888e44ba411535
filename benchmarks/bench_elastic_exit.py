"""Benchmark (not a test): the thin strip's exit on a flattened roll (issue 50 item 2).

The bundled thin_strip (S355J2 at 900 degC, 2.4 -> 2.0 mm, R 0.35 m, 10 m/s, Coulomb 0.3) on
its rigid, Hitchcock and elastic roll, and on the elastic roll along other update paths (the
roll's relaxation 0.5 and 0.3, its tolerance / 10), with the strip's default elasticity; and
the elastic roll with a rigid-plastic strip (``strip_youngs_modulus = "off"``). Each run in a
fresh subprocess on 2 threads. Columns: Newton iterations, the solve's wall time (meshing
included, output not: ``wall_time_s``), roll force, forward slip, how the contact ends, the
lowest contact pressure over the peak, the sign changes of the pressure's slope over the last
third of the contact (a swing), the roll's shape against the disc under its final tractions
(``roll_shape_error``), the exit code. Figures printed and written to
benchmarks/results/bench_elastic_exit.{csv,md}.

    python benchmarks/bench_elastic_exit.py            # about a minute
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "scripts"))

from _common import print_table, write_table  # noqa: E402

COLUMNS = ["variant", "newton_iterations", "wall_s", "roll_force", "forward_slip",
           "contact_end_kind", "min_over_peak", "slope_sign_changes", "roll_shape_error",
           "exit_code"]
VARIANTS = {
    "rigid roll": {"roll.model": "rigid"},
    "hitchcock roll": {"roll.model": "hitchcock"},
    "elastic roll": {},
    "elastic roll, relaxation 0.5": {"roll.relaxation": 0.5},
    "elastic roll, relaxation 0.3": {"roll.relaxation": 0.3},
    "elastic roll, tolerance / 10": {"roll.tolerance": 1e-6},
    "elastic roll, rigid-plastic strip": {"contact.strip_youngs_modulus": "off"},
}


def one(variant: str, threads: int) -> dict:
    from hotroll.config.case import load_case
    from hotroll.examples import example_path
    from hotroll.workflows.runner import run_case

    over = {"solver.threads": threads, "output.figures": False, "output.vtk": False,
            **VARIANTS[variant]}
    case = load_case(example_path("thin_strip")).with_overrides(**over)
    with tempfile.TemporaryDirectory() as tmp:
        s = run_case(case, Path(tmp), resume=False)
        import csv

        with open(Path(tmp) / "contact.csv") as f:
            rows = [r for r in csv.DictReader(f) if r["vertex"] == "1"]
    x = np.array([float(r["x"]) for r in rows])
    p = -np.array([float(r["normal_stress"]) for r in rows])[np.argsort(x)]
    tail = np.diff(p[2 * len(p) // 3:])
    changes = int(np.count_nonzero(np.diff(np.sign(tail[np.abs(tail) > 1e-3 * p.max()]))))
    return {"variant": variant, "newton_iterations": s["nonlinear_iterations"],
            "wall_s": s["wall_time_s"], "roll_force": s["roll_force"],
            "forward_slip": s["forward_slip"], "contact_end_kind": s["contact_end_kind"],
            "min_over_peak": float(p.min() / p.max()), "slope_sign_changes": changes,
            "roll_shape_error": s.get("roll_shape_error"), "exit_code": s["exit_code"]}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--one", default=None, help=argparse.SUPPRESS)
    p.add_argument("--report", type=Path, default=HERE / "results" / "bench_elastic_exit")
    args = p.parse_args(argv)
    if args.one is not None:
        print("ROW " + json.dumps(one(args.one, args.threads)))
        return 0
    rows = []
    for variant in VARIANTS:
        cmd = [sys.executable, __file__, "--one", variant, "--threads", str(args.threads)]
        proc = subprocess.run(cmd, capture_output=True, text=True)
        line = [ln for ln in proc.stdout.splitlines() if ln.startswith("ROW ")]
        if proc.returncode or not line:
            print(f"{variant}: failed\n{proc.stderr[-2000:]}", file=sys.stderr)
            continue
        rows.append(json.loads(line[-1][4:]))
    by = {r["variant"]: r for r in rows}
    notes = [f"{args.threads} threads, cold (a fresh process per run); wall_s: the solve with "
             "its meshing (summary wall_time_s); slope_sign_changes: of the pressure's slope "
             "between vertices over the contact's last third (steps below 1e-3 of the peak "
             "ignored)."]
    if "rigid roll" in by and "elastic roll" in by:
        notes.append(f"elastic roll / rigid roll wall time: "
                     f"{by['elastic roll']['wall_s'] / by['rigid roll']['wall_s']:.2f}")
    paths = [r["roll_force"] for k, r in by.items()
             if k.startswith("elastic roll") and "rigid-plastic" not in k]
    if paths:
        notes.append(f"elastic roll's force over its update paths: spread "
                     f"{(max(paths) - min(paths)) / min(paths):.1e} (relative)")
    write_table(rows, COLUMNS, args.report, title="The thin strip's exit on a flattened roll",
                notes=notes)
    print_table(rows, COLUMNS, "The thin strip's exit on a flattened roll")
    for n in notes[1:]:
        print(n)
    return 0


if __name__ == "__main__":
    sys.exit(main())
