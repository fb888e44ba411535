"""Thermal mesh study (docs/studies/thermal_mesh.md): hotroll/examples/cases/thermal_pass.toml with the
temperature on its own strip mesh, the mechanics' contact size and the strip mesh's refinement
varied; and the isothermal pass on each mechanics mesh (the cost ratio). Prints a Markdown
table; one thread.

    .venv/bin/python scripts/thermal_study.py [--out DIR] [--quick]
"""
from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.workflows.runner import run_case

CASE = example_path("thermal_pass")
KEYS = ("roll_force", "exit_temperature_mean", "exit_temperature_surface", "heat_to_roll",
        "heat_to_air", "plastic_heat", "max_temperature", "heat_balance_error")


def main() -> None:
    os.environ.setdefault("NGS_NUM_THREADS", "1")
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("results/thermal_study"))
    ap.add_argument("--quick", action="store_true", help="auto mesh, refinement 1 and 2 only")
    args = ap.parse_args()
    case = load_case(CASE)
    meshes = ["auto"] if args.quick else ["auto", 0.003, 0.0015]
    refines = [1, 2] if args.quick else [1, 2, 4]
    print("| h_contact (m) | strip refinement | dofs (mech. + strip) | isothermal (s) | coupled (s)"
          " | force (N/m) | exit mean T (K) | exit surface T (K) | heat to roll (W/m) "
          "| heat to air (W/m) | plastic heat (W/m) | max T (K) | balance |")
    print("|---" * 13 + "|")
    for h in meshes:
        t0 = time.perf_counter()
        run_case(case.with_overrides(**{"mesh.h_contact": h}, thermal=None),
                 args.out / f"iso_{h}")
        iso = time.perf_counter() - t0
        for r in refines:
            t0 = time.perf_counter()
            s = run_case(case.with_overrides(**{"mesh.h_contact": h,
                                                "thermal.mesh_refinement": float(r)}),
                         args.out / f"h_{h}_r{r}")
            wall = time.perf_counter() - t0
            v = [s[k] for k in KEYS]
            print(f"| {s['h_contact']:.5f} | {r} | {s['dofs']} + {s['thermal_dofs']} | "
                  f"{iso:.1f} | {wall:.1f} | {v[0]:.0f} | {v[1]:.2f} | {v[2]:.1f} | {v[3]:.0f} | "
                  f"{v[4]:.0f} | {v[5]:.0f} | {v[6]:.1f} | {v[7]:.1e} |", flush=True)


if __name__ == "__main__":
    main()
