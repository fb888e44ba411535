"""A flattening roll's figures in the summary (``results/run_summary.py``): how far its
flattened surface lies below the rigid roll, the circle fitted to it over the contact, its
updates, last move and shape error; the half model's top-level ``roll_*`` keys and an
asymmetric pass's per-roll entries."""
from __future__ import annotations

import numpy as np

from hotroll.config.case import Case
from hotroll.model.solution import RollContact


def roll_figures(case: Case, contact: RollContact, prof: dict, model: str | None = None) -> dict:
    """A flattening roll's figures (m): the flattening (how far the flattened surface lies
    below the rigid roll through the same gap, largest over the contact: at its entry) and the
    radius of the circle fitted to the surface over the contact, with its updates, last move
    and shape error (the solver's: ``solvers/record.shape_error``); {} for a rigid roll.
    ``model``: the roll's model (default: the upper roll's, ``[roll]`` or its table)."""
    if not contact.flattening:
        return {}
    rp = contact.rp
    ang = np.asarray(prof["angle"], dtype=float)
    lo, hi = (float(ang.min()), float(ang.max())) if len(ang) else (0.0, rp.bite_angle)
    t = np.linspace(lo, hi, 101)
    r = rp.surface_radius(t)
    X, Y = -r * np.sin(t), -r * np.cos(t)
    c = np.linalg.lstsq(np.c_[X, Y, np.ones_like(X)], X**2 + Y**2, rcond=None)[0]
    return {"roll_model": model or case.roll_gap().upper.model,
            "roll_flattening": flattening(rp, float(np.min(X)) + rp.centre[0]),
            "roll_equivalent_radius": float(np.sqrt(c[2] + (c[0] / 2) ** 2 + (c[1] / 2) ** 2)),
            "roll_updates": contact.roll_updates, "roll_last_move": contact.roll_last_move,
            "roll_shape_error": contact.roll_shape_error}


def flattening(rp, x_start: float) -> float:
    """max over [x_start, X_roll] of (rigid roll's height - flattened surface's height), m:
    the rigid roll of radius R touching the same lowest point (the gap at X_roll). For
    Hitchcock's circle R' it is about l^2 (1/R - 1/R') / 2, l the contact length."""
    x = np.linspace(x_start, rp.axis_x, 201)
    R = rp.radius
    rigid = rp.half_exit + R - np.sqrt(np.maximum(R**2 - (x - rp.axis_x) ** 2, 0.0))
    return float(np.max(rigid - rp.height(x)))
