"""A strip that curls onto a roll (issue 52 session 3, docs/validation/asymmetric.md "A strip
that curls onto a roll"): the bundled asymmetric passes and variants of the plate through
``run_case`` (figures off), each row its exit code, the rolls' mean force, the exit curl, how
the lower roll's contact ends and how far past its gap, the overlap, the Newton iterations.

    python scripts/asymmetric_wrap.py [--only NAME,...]
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.workflows.runner import run_case

#: (row name, bundled case, overrides)
ROWS = [
    ("asymmetric_radii", "asymmetric_radii", {}),
    ("asymmetric_radii, h = 2.5 mm", "asymmetric_radii", {"mesh.h_contact": 0.0025}),
    ("asymmetric_radii, E = 150 GPa", "asymmetric_radii",
     {"contact.strip_youngs_modulus": 1.5e11}),
    ("asymmetric_plate (r = 1.1)", "asymmetric_plate", {}),
    ("asymmetric_plate at r = 1.15", "asymmetric_plate", {"pass.speed_ratio": 1.15}),
    ("plate, Tresca 0.5, r = 1.15", "asymmetric_plate",
     {"pass.speed_ratio": 1.15, "friction.factor": 0.5}),
    ("plate, Tresca 0.5, r = 1.1", "asymmetric_plate", {"friction.factor": 0.5}),
    ("plate 25 -> 18 mm, r = 1.15", "asymmetric_plate",
     {"pass.speed_ratio": 1.15, "pass.exit_thickness": 0.018}),
    ("plate 15 -> 12 mm, h = 0.75 mm, r = 1.15", "asymmetric_plate",
     {"pass.speed_ratio": 1.15, "pass.entry_thickness": 0.015, "pass.exit_thickness": 0.012,
      "mesh.h_contact": 0.00075}),
]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", default="", help="row names (comma-separated substrings)")
    a = ap.parse_args()
    keys = [k for k in a.only.split(",") if k]
    print("| pass | exit | force (mean) MN/m | curvature 1/m | lower end | past its gap mm "
          "| overlap um | iterations | wall s |")
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for i, (name, bundled, over) in enumerate(ROWS):
            if keys and not any(k in name for k in keys):
                continue
            case = load_case(example_path(bundled), {"output.figures": False, **over})
            t0 = time.perf_counter()
            s = run_case(case, Path(tmp) / str(i), resume=False)
            wall = time.perf_counter() - t0
            lower = s["rolls"][1]
            past = (lower["contact_end"] - 1.0) * 1e3       # the case's roll axes at x = 1 m
            print(f"| {name} | {s['exit_code']} | {s['roll_force'] / 1e6:.4f} | "
                  f"{s['exit_curvature']:.4g} | {lower['contact_end_kind']} | {past:.2f} | "
                  f"{(s['roll_overlap'] or 0.0) * 1e6:.3g} | {s['nonlinear_iterations']} | "
                  f"{wall:.1f} |", flush=True)


if __name__ == "__main__":
    main()
