"""Thermal first look (docs/studies/thermal_first_look.md): scripts/cases/thermal_pass.toml on
contact mesh sizes auto, 3, 1.5 and 0.75 mm, plus the isothermal run; prints a Markdown table.

    .venv/bin/python scripts/thermal_study.py [--out DIR]
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

from hotroll.app.config import load_case
from hotroll.app.runner import run_case

CASE = Path(__file__).parent / "cases" / "thermal_pass.toml"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("results/thermal_study"))
    out = ap.parse_args().out
    case = load_case(CASE)
    iso = run_case(case.with_overrides(thermal=None), out / "isothermal")
    print(f"isothermal (auto mesh): force {iso['roll_force']:.0f} N/m")
    print("| h_contact (m) | dofs | wall (s) | force (N/m) | exit mean T (K) | exit surface T (K) "
          "| heat to roll (W/m) | heat to air (W/m) | plastic heat (W/m) | max T (K) | balance |")
    print("|---" * 11 + "|")
    for h in ("auto", 0.003, 0.0015, 0.00075):
        t0 = time.perf_counter()
        s = run_case(case.with_overrides(**{"mesh.h_contact": h}), out / f"h_{h}")
        wall = time.perf_counter() - t0
        print(f"| {s['h_contact']:.5f} | {s['dofs']} | {wall:.0f} | {s['roll_force']:.0f} | "
              f"{s['exit_temperature_mean']:.2f} | {s['exit_temperature_surface']:.1f} | "
              f"{s['heat_to_roll']:.0f} | {s['heat_to_air']:.0f} | {s['plastic_heat']:.0f} | "
              f"{s['max_temperature']:.1f} | {s['heat_balance_error']:.1e} |", flush=True)


if __name__ == "__main__":
    main()
