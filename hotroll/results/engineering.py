"""Engineering figures of a pass for the summary: whole-width totals, the mill's setting and
the unit of every number (issue 15; the means over the roll gap are the solver's,
``solvers/record_fields.gap_means``).

The FE figures are per unit width of the upper roll and its half of the strip (the strip's
upper half is all the upper roll touches): roll force = the separating force of one roll,
torque and power = one roll's. ``[pass] width`` turns them into a whole strip's figures; the
mill (drive) power is both rolls'.
"""
from __future__ import annotations

import math

from hotroll.results.units import UNITS


def width_totals(summary: dict, width: float | None) -> dict:
    """Whole-width figures (one roll's force and torque, the mill power of both rolls)."""
    if width is None:
        return {"width": None}
    return {"width": width,
            "roll_force_total": summary["roll_force"] * width,
            "roll_torque_total": summary["roll_torque"] * width,
            "roll_power_total": summary["roll_power"] * width,
            "mill_power": 2.0 * summary["roll_power"] * width}


def mill_setup(summary: dict, exit_thickness: float, modulus: float | None) -> dict:
    """The gaugemeter equation h1 = S + F/M (Weber 1973): the stand's stretch F/M under the
    whole-width force and the no-load gap S = h1 - F/M to set for the exit thickness h1 (m);
    {} without a mill modulus."""
    if modulus is None:
        return {}
    stretch = summary["roll_force_total"] / modulus
    return {"mill_modulus": modulus, "mill_stretch": stretch,
            "gap_setting": exit_thickness - stretch}


def negative_gap_warning(gap_setting: float | None, stretch: float | None) -> str | None:
    """What a negative gap to set means (``results/engineering.mill_setup``: S = h1 - F/M),
    or None where the gap is positive or not reported."""
    if gap_setting is None or stretch is None or not gap_setting < 0.0:
        return None
    h1 = gap_setting + stretch
    return (f"the gap to set is negative, S = h1 - F/M = {1e3 * gap_setting:.3f} mm: the "
            f"stand's stretch under the roll force, F/M = {1e3 * stretch:.3f} mm (the whole "
            f"stand's spring, the rolls' flattening included as far as the mill modulus counts "
            f"it), exceeds the exit thickness h1 = {1e3 * h1:.3f} mm. At no load the rolls "
            f"would have to be pressed {1e3 * -gap_setting:.3f} mm into each other: a "
            f"preloaded stand, set by its force or from a zero taken under load (kiss "
            f"rolling), not a gap that opens; pass.roll_gap takes a gap > 0 only, so give this "
            f"pass by its exit_thickness")


def display(key: str, value, unit: str | None = None):
    """(text, unit) for a person: forces in MN/m (MN), torques in kN m/m (kN m), powers in
    kW/m (kW), stresses in MPa, where the magnitude calls for it; SI otherwise. ``unit``: the
    SI unit when ``UNITS`` does not know the key (e.g. summary.json's ``units``)."""
    unit = UNITS.get(key, unit or "")
    if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
        return None, unit
    scale = {"N/m": (1e6, "MN/m"), "N": (1e6, "MN"), "N m/m": (1e3, "kN m/m"),
             "N m": (1e3, "kN m"), "W/m": (1e3, "kW/m"), "W": (1e3, "kW"), "Pa": (1e6, "MPa")}
    if unit in scale and abs(value) >= scale[unit][0] and key not in ("K",):
        factor, unit = scale[unit]
        return f"{value / factor:.4g}", unit
    return f"{value:.6g}", unit
