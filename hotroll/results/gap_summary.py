"""The summary of an asymmetric pass (issue 52): a full-thickness strip between two rolls
(``solvers/record_full.py`` fills its ``Solution``: two contacts, each in its roll's own frame).

Its history rows carry each roll's figures (``upper_*``, ``lower_*``: solvers/gap_measure.py)
and the strip's (cross-shear length, exit curl, the entry guide's reaction, the balances). The
summary gives:

- ``rolls``: one entry per roll (``ROLL_ENTRY``: the upper's, then the lower's), each figure the
  window's mean of that roll's history column (an identity: the steady solver's window is its
  last converged row);
- the legacy one-roll keys, so that every reader of a summary keeps working: the integrated
  figures (``roll_force``, ``roll_torque``, ``roll_power``, ``horizontal_force``,
  ``contact_length``, ``forward_slip``) are the MEANS of the two rolls' (``legacy_row``: the
  sum of the two is twice the key; ``mill_power`` with a width is both rolls' power); the
  figures read off one contact profile (the neutral story, the contact's start, end and
  angles, ``min_contact_pressure``, ``entry_pressure``, ``roll_centre``, ``roll_radius``,
  ``roll_surface_speed``) are the UPPER roll's; ``force_balance`` holds each roll's and the
  entry guide's force on the strip; ``balance_error`` is the vertical balance's;
- ``speed_ratio``, ``cross_shear_length``, ``exit_curvature`` (and its second measure
  ``exit_surface_curvature``), ``exit_angle``, ``entry_guide_force_y``,
  ``vertical_balance_error``, the exit's shear strain ``exit_shear_strain_*`` (``GAP_KEYS``).
"""
from __future__ import annotations

import math

import numpy as np

from hotroll.results.summary import ROLL_ENTRY, ROLL_FLATTENING_ENTRY

SIDES = ("upper", "lower")
#: The one-roll figures of the half model that an asymmetric pass gives as the two rolls' mean.
MEAN_OF_ROLLS = ("roll_torque", "roll_power", "horizontal_force", "contact_length",
                 "forward_slip")
#: The strip's own figures of the full-thickness history (window means), summary keys as named.
GAP_KEYS = ("cross_shear_length", "exit_curvature", "exit_surface_curvature", "exit_angle",
            "entry_guide_force_y", "vertical_balance_error", "exit_shear_strain_upper",
            "exit_shear_strain_mid", "exit_shear_strain_lower", "exit_shear_strain_mean")
#: The per-roll history columns the summary moves by the frame shift (x positions, m).
X_COLUMNS = ("neutral_x", "contact_start", "contact_end")


def legacy_row(row: dict, a_f: float | None) -> dict:
    """A full-thickness history row with the half model's one-roll keys added: the means of
    the two rolls' (``MEAN_OF_ROLLS``; ``roll_force`` is already), the upper roll's neutral
    angle, ``a_f`` (the upper roll's, m^-m, or None), the penalty's share of both rolls'
    power; the half model's keys that have no meaning here NaN (the symmetry line's and the
    free tops' forces, the outlet penalty's power, the measures of (3.15))."""
    out = dict(row)
    for key in MEAN_OF_ROLLS:
        out[key] = 0.5 * (row[f"upper_{key}"] + row[f"lower_{key}"])
    out["neutral_angle"] = row["upper_neutral_angle"]
    out["a_f"] = math.nan if a_f is None else a_f
    supplied = abs(row["upper_roll_power"] + row["lower_roll_power"])
    out["penalty_share"] = abs(row["penalty_power"]) / max(supplied, 1e-300)
    for key in ("outlet_penalty_power", "strain_rate_measure", "slip_measure",
                "symmetry_stress_force_y", "balance_error", "free_top_force_share"):
        out.setdefault(key, math.nan)
    for part in ("roll", "free_top", "face", "tension", "symmetry"):
        out.setdefault(f"{part}_force_y", math.nan)
    return out


def upper_a_f(case) -> float | None:
    """The upper roll's a_f (m^-m) of an asymmetric ``case``, None for a law without it."""
    section = case.friction.upper or case.friction
    return float(section.a_f) if section.uses_a_f else None


def shifted_history(rows: list[dict], shift: float) -> list[dict]:
    """history.csv's rows of a full-thickness run with their x positions moved by ``shift``
    (m; the solver's frame to the case's)."""
    keys = [f"{s}_{k}" for s in SIDES for k in X_COLUMNS]
    return [{**r, **{k: r[k] + shift for k in keys if k in r}} for r in rows]


def _mean(rows: list[dict], key: str) -> float:
    vals = np.asarray([r[key] for r in rows], dtype=float)
    vals = vals[np.isfinite(vals)]
    return float(vals.mean()) if len(vals) else math.nan


def gap_figures(solved: list[dict], contacts, speed_ratio: float, shift: float) -> dict:
    """The summary keys of an asymmetric pass from the window's ``solved`` history rows and
    the two ``contacts`` (upper, lower: their arcs give the radius and surface speed):
    ``rolls`` (``ROLL_ENTRY``), ``speed_ratio`` (-) and ``GAP_KEYS``; x positions moved by
    ``shift`` (m)."""
    rolls = []
    for name, contact in zip(SIDES, contacts):
        entry = {"side": name, "radius": contact.rp.radius,
                 "surface_speed": contact.rp.u_roll, "roll_overlap": contact.overlap,
                 "contact_end_kind": None,     # the summary's (results/run_summary.py)
                 "contact_end_pressure": (float(-contact.profile["normal_stress"][-1])
                                          if contact.exact and len(contact.profile["x"])
                                          else None)}
        for key in ROLL_ENTRY:
            if key not in entry:
                entry[key] = _mean(solved, f"{name}_{key}") + (shift if key in X_COLUMNS
                                                                 else 0.0)
        rolls.append(entry)
    out = {"rolls": rolls, "speed_ratio": speed_ratio}
    out.update({k: _mean(solved, k) for k in GAP_KEYS})
    return out


def gap_force_balance(last: dict) -> dict:
    """The forces on the strip (x, y; N/m) of the last row: each roll's (its horizontal
    force, and its roll force pushing the strip away from it) and the entry guide's."""
    return {"upper_roll": [last["upper_horizontal_force"], -last["upper_roll_force"]],
            "lower_roll": [last["lower_horizontal_force"], last["lower_roll_force"]],
            "entry_guide": [0.0, last["entry_guide_force_y"]]}


def roll_units() -> dict[str, str]:
    """summary.json's ``units`` lines of the ``rolls`` entries: ``rolls.<key>`` -> SI unit."""
    return {f"rolls.{k}": unit for k, (unit, _) in (*ROLL_ENTRY.items(),
                                                     *ROLL_FLATTENING_ENTRY.items()) if unit}
