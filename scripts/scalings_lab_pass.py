"""The equations' exact scalings on a slow lab pass (issue 52 session 2).

The bundled asymmetric_plate made a lab pass (R 0.1 m, 5 -> 4 mm, 0.01 m/s), with a speed
ratio of 1.1 (the full strip) and without one (the half model):
- roll speed x100, with the law's rate regularisation eps0: forces and torques x 100^m;
  slips, neutral angles, curl and cross-shear unchanged;
- K x1000: forces and torques only;
- roll_axis_x moved: nothing changes;
- solver.threads = 1: the default's figures.

    python scripts/scalings_lab_pass.py      # the worst relative difference of each
    python scripts/scalings_lab_pass.py --case asymmetric_radii   # a bundled case as it is
                                             # (its strip wraps the slower roll: session 3)
"""
from __future__ import annotations

import tempfile
from pathlib import Path

from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.workflows.runner import run_case

LAB = {"pass.roll_radius": 0.1, "pass.entry_thickness": 0.005, "pass.exit_thickness": 0.004,
       "pass.roll_angular_velocity": 0.1, "mesh.h_contact": 2.5e-4, "plate.length": 0.05,
       "output.figures": False}
OUT = Path(tempfile.mkdtemp())


CASE = {"name": "asymmetric_plate", "over": LAB, "ratios": (1.1, None)}


def figures(name: str, extra: dict, ratio: float | None) -> dict:
    """The run's figures: each roll's force, torque, slip and neutral angle, the curl and the
    cross-shear length (an asymmetric pass), or the one roll's."""
    ratio_over = {"pass.speed_ratio": ratio} if CASE["ratios"] != (None,) else {}
    case = load_case(example_path(CASE["name"]), {**CASE["over"], **ratio_over, **extra})
    s = run_case(case, OUT / f"{name}_{ratio}", resume=False)
    assert s["status"] == "steady", (name, s["status"])
    if "rolls" not in s:
        return {"F": s["roll_force"], "T": s["roll_torque"], "slip": s["forward_slip"],
                "angle": s["neutral_angle"]}
    out = {"kappa": s["exit_curvature"], "cross_shear": s["cross_shear_length"]}
    for entry in s["rolls"]:
        side = entry["side"]
        out.update({f"F_{side}": entry["roll_force"], f"T_{side}": entry["roll_torque"],
                    f"slip_{side}": entry["forward_slip"],
                    f"angle_{side}": entry["neutral_angle"]})
    return out


def main() -> None:
    import argparse

    ap = argparse.ArgumentParser()
    ap.add_argument("--case", default=None, help="a bundled case as it is (no lab pass)")
    a = ap.parse_args()
    if a.case:
        CASE.update(name=a.case, over={"output.figures": False}, ratios=(None,))
    base_case = load_case(example_path(CASE["name"]))
    eps0, K, m = base_case.material.eps0, base_case.material.K, base_case.material.m
    omega = base_case.pass_.roll_angular_velocity
    for ratio in CASE["ratios"]:
        base = figures("base", {}, ratio)
        # speed x100 on the lab pass; a bundled (mill-speed) case / 100 (x100 would be refused)
        f = 0.01 if a.case else 100.0
        checks = {f"speed x{f:g}": ({"pass.roll_angular_velocity": f * (omega if a.case else 0.1),
                                     "material.eps0": f * eps0}, f**m),
                  "K x1000": ({"material.K": 1000.0 * K}, 1000.0),
                  "axis +0.3 m": ({"pass.roll_axis_x": 0.3}, 1.0),
                  "threads 1": ({"solver.threads": 1}, 1.0)}
        for label, (extra, stress) in checks.items():
            got = figures(label.replace(" ", "_"), extra, ratio)
            worst = max(abs(got[k] / ((stress if k[0] in "FT" else 1.0) * v) - 1.0) if v
                        else abs(got[k]) for k, v in base.items())
            print(f"speed ratio {ratio}: {label}: worst relative difference {worst:.2e}")


if __name__ == "__main__":
    main()
