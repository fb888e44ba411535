"""The bundled asymmetric pass with the full strip's couplings (issue 52 session 2): rigid
and isothermal as bundled, with a temperature field, with Hitchcock's and with the elastic
disc's flattening rolls; and the symmetric pass (no speed ratio) of each for comparison.

    python scripts/asymmetric_physics.py [--out DIR]
    python scripts/asymmetric_physics.py --case thin_strip --ratios 1.0001,1.05

With ``--case``: that bundled case as it is (its own roll model and strip elasticity) as the
half model and at each speed ratio on the full strip.

Each variant through ``run_case`` (figures off); prints a markdown table: status, wall s,
each roll's force and torque, the exit curvature, the exit temperatures, the rolls' flattened
equivalent radii.
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.workflows.runner import run_case

THERMAL = {"thermal": {"htc_contact": 2.0e4, "roll_temperature": 350.0, "htc_air": 20.0,
                       "emissivity": 0.8},
           "material.density": 7800.0, "material.specific_heat": 650.0,
           "material.conductivity": 30.0}
VARIANTS = {"rigid, isothermal (bundled)": {}, "with [thermal]": THERMAL,
            "hitchcock rolls": {"roll.model": "hitchcock"},
            "elastic-disc rolls": {"roll.model": "elastic"}}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", type=Path, default=None)
    ap.add_argument("--case", default=None, help="a bundled case, run as it is")
    ap.add_argument("--ratios", default="1.1", help="speed ratios (upper/lower), comma-separated")
    a = ap.parse_args()
    out = a.out or Path(tempfile.mkdtemp())
    name = a.case or "asymmetric_plate"
    variants = VARIANTS if a.case is None else {f"{name} as bundled": {}}
    ratios = [float(r) for r in a.ratios.split(",")]
    print("| variant | speed ratio | status (exit code) | wall s | force upper / lower MN/m | torque upper "
          "/ lower kN m/m | curvature 1/m | exit T mean / upper / lower K | R' upper / "
          "lower mm |")
    print("|---|---|---|---|---|---|---|---|---|")
    for label, over in variants.items():
        for ratio in (*ratios, None):
            extra = {"pass.mill_modulus": None} if name == "thin_strip" else {}
            case = load_case(example_path(name), {**over, **extra, "pass.speed_ratio": ratio,
                                                  "output.figures": False})
            t = time.perf_counter()
            s = run_case(case, out / f"{name}_{len(over)}_{ratio}_{label[:5]}", resume=False)
            wall = time.perf_counter() - t
            if "rolls" in s:
                up, lo = s["rolls"]
                force = f"{up['roll_force'] / 1e6:.4f} / {lo['roll_force'] / 1e6:.4f}"
                torque = f"{up['roll_torque'] / 1e3:.1f} / {lo['roll_torque'] / 1e3:.1f}"
                radii = " / ".join(f"{1e3 * r['roll_equivalent_radius']:.2f}"
                                   if "roll_equivalent_radius" in r else "-" for r in (up, lo))
                curv = f"{s['exit_curvature']:.4f}"
                lower_T = s.get("exit_temperature_surface_lower")
            else:
                force = f"{s['roll_force'] / 1e6:.4f}"
                torque = f"{s['roll_torque'] / 1e3:.1f}"
                radii = (f"{1e3 * s['roll_equivalent_radius']:.2f}"
                         if "roll_equivalent_radius" in s else "-")
                curv, lower_T = "0", s.get("exit_temperature_surface")
            temps = ("-" if "exit_temperature_mean" not in s else
                     f"{s['exit_temperature_mean']:.1f} / {s['exit_temperature_surface']:.1f} / "
                     f"{lower_T:.1f}")
            print(f"| {label} | {ratio or 1.0:g} | {s['status']} ({s['exit_code']}) | {wall:.1f} | {force} | "
                  f"{torque} | {curv} | {temps} | {radii} |", flush=True)


if __name__ == "__main__":
    main()
