"""The steady-state test and the summary windows of the transient run, report Section 3.4.

Steady state (the report judges it by eye from Fig. 3; the histories oscillate with the period
of the contact projection): a window is a whole number (>= 6) of projection periods, at least
the time the roll surface needs to travel 3 h (the summary averages over whole periods covering
3 h). The run is steady when, for the roll force, torque, strain-rate measure, forward slip and
neutral angle, the means over the last two windows differ by at most ``steady_tol`` (relative;
10 x bite angle for the angle) or by at most twice their standard error (batch means over the
projection periods: the drift is below the noise), at least one contact transit time l_c/|U|
after the start, with the head past the exit section.
"""
from __future__ import annotations

import math

import numpy as np

STEADY_KEYS = ("roll_force", "roll_torque", "strain_rate_measure", "forward_slip",
               "neutral_angle")


def steady_reached(history: list, window: int, period: int, tol: float,
                   bite_angle: float) -> bool:
    """Steady-state test of the module docstring on the last 2 ``window`` rows of ``history``
    (docs/theory.md, section 3.4). ``window`` is a multiple of ``period``."""
    if len(history) < 2 * window or not math.isfinite(history[-1]["forward_slip"]):
        return False
    period = max(1, period)
    for key in STEADY_KEYS:
        rows = np.array([r[key] for r in history[-2 * window:]], dtype=float)
        last, prev = np.split(rows.reshape(-1, period).mean(axis=1), 2)   # batch means
        a, b = last.mean(), prev.mean()
        scale = {"neutral_angle": 10.0 * bite_angle, "forward_slip": 1.0 + abs(a)}.get(key, abs(a))
        noise = 2.0 * math.sqrt((last.var(ddof=1) + prev.var(ddof=1)) / len(last))
        if not (math.isfinite(a) and math.isfinite(b) and abs(a - b) <= max(tol * scale, noise)):
            return False
    return True


def summary_windows(h: float, u_roll: float, dt: float, project_every: int) -> tuple[int, int]:
    """(summary window, steady window) in steps: whole projection periods covering the time the
    roll surface needs to travel 3 h; the steady test's window at least 6 periods."""
    period = max(1, project_every)
    periods = math.ceil(3.0 * h / (u_roll * dt) / period)
    return period * periods, period * max(6, periods)


def transit_time(rp, carried: bool) -> float:
    """The earliest time a run may be steady: one contact transit l_c / U; with a field carried
    by the material (strain, temperature), material that entered the bite after the start
    must have left the gap, at the entry speed (~ U h1/h0, with 20 % margin)."""
    transit = rp.contact_length / rp.u_roll
    if carried:
        transit *= 1.2 * rp.half_entry / rp.half_exit
    return transit


def default_end_time(rp) -> float:
    """Time for the roll surface to travel three contact lengths (the run stops when steady)."""
    return 3.0 * rp.contact_length / rp.u_roll
