"""What a run's summary says happened, as the command line's exit code."""
from __future__ import annotations

import math


#: Exit codes of ``hotroll run``, ``example`` and ``sweep`` (README, "Exit codes"); 1 is left
#: to Python for an unexpected error, 2 is bad input (refused before any computation).
EXIT_CODES = {0: "converged", 2: "bad input", 3: "failed", 4: "diverged", 5: "not settled",
              6: "skids", 7: "not conserved", 8: "too large (memory estimate over the limit, "
              "app/estimate.py; refused before meshing)", 9: "disk full"}


def exit_code(summary: dict) -> int:
    """What a run's summary says happened, as an exit code (``EXIT_CODES``).

    0: converged (steady state reached, last nonlinear solve converged, the roll drives the
    strip); 3: failed, the run stopped with a reason (``failure``: a linear solve, a tangled
    mesh); 6: skids, no neutral point (the outlet penalty drives the strip, ``outlet_driven``);
    4: diverged, the last nonlinear solve did not converge or the figures are not finite;
    5: not settled, the end time, step or wall-time limit came first, or the steady solver's
    free-surface/a_f fixed point did not settle; 7: not conserved, a run that converged but
    whose mass flux or power balance is off by more than its tolerance (``not_conserved``,
    the reason in ``failure``; ``runner.CONSERVATION_TOL``)."""
    if summary.get("converged"):
        return 0
    if summary.get("not_conserved"):
        return 7
    status = summary.get("status")
    if status == "failed" and summary.get("failure"):
        return 3
    if summary.get("outlet_driven"):
        return 6
    if status in ("failed", "steady") or not all(
            _finite(summary.get(k)) for k in ("roll_force", "roll_torque")):
        return 4
    return 5


def _finite(value) -> bool:
    """A finite real number (None, text and NaN are not)."""
    try:
        return math.isfinite(float(value))
    except (TypeError, ValueError):
        return False
