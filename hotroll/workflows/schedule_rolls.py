"""A schedule's asymmetric passes (issue 52; ``workflows/schedule.py`` rolls them): the state a
pass without a temperature or strain profile hands on (``asymmetric_exit``: an isothermal pass
whose law ignores the strain; an asymmetric pass's whole-thickness profile is folded by
``schedule.exit_state``) and the table's columns of every pass's curl and an asymmetric pass's
rolls (``curl_columns``)."""
from __future__ import annotations

import numpy as np

from hotroll.model.profile import ThicknessProfile


def asymmetric_exit(summary: dict, temperature: ThicknessProfile,
                    strain: ThicknessProfile) -> tuple[ThicknessProfile, ThicknessProfile]:
    """(temperature, strain) profiles leaving a pass without a temperature or strain profile
    (an isothermal one whose law ignores the strain) that entered with these: the entry
    temperature profile (the pass is isothermal) and the entry strain profile moved by a
    constant to the pass's mean exit strain (``exit_strain`` where the solve carries the
    strain, else the homogeneous ``entry + 2/sqrt3 ln(h0/h1)``; an asymmetric pass's
    through-thickness shear is not handed on)."""
    mean = summary.get("exit_strain")
    if mean is None:
        mean = summary["homogeneous_exit_strain"]
    e = strain
    e = ThicknessProfile(e.eta, tuple(np.maximum(np.asarray(e.values) + mean - e.mean(), 0.0)))
    return temperature, e


#: An asymmetric pass's per-roll columns: ``upper_<key>``, ``lower_<key>`` from ``rolls``.
ROLL_COLUMNS = {"radius": "roll_radius", "surface_speed": "roll_surface_speed",
                "roll_force": "roll_force", "roll_torque": "roll_torque",
                "roll_power": "roll_power"}


def curl_columns(s: dict) -> dict:
    """The strip's curl leaving the pass: ``exit_curvature`` (1/m, > 0 curls up) and
    ``exit_angle`` (rad, > 0 upwards), both 0 for a symmetric pass (the half model's symmetry
    plane holds the strip straight); an asymmetric pass adds ``speed_ratio``,
    ``cross_shear_length`` and each roll's radius, surface speed, force, torque and power
    (``upper_roll_force``, ...: the summary's ``rolls``, per unit width)."""
    if "rolls" not in s:
        return {"exit_curvature": 0.0, "exit_angle": 0.0}
    row = {"exit_curvature": s["exit_curvature"], "exit_angle": s["exit_angle"],
           "speed_ratio": s["speed_ratio"], "cross_shear_length": s["cross_shear_length"]}
    for entry in s["rolls"]:
        row.update({f"{entry['side']}_{col}": entry[key] for key, col in ROLL_COLUMNS.items()})
    return row
