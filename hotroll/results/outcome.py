"""What a run's summary says happened, as the command line's exit code."""
from __future__ import annotations

import math

#: Exit codes of ``hotroll run``, ``example`` and ``sweep`` (README, "Exit codes"); 1 is left
#: to Python for an unexpected error, 2 is bad input (refused before any computation).
EXIT_CODES = {0: "converged", 2: "bad input", 3: "failed", 4: "diverged", 5: "not settled",
              6: "skids", 7: "not conserved", 8: "too large (memory estimate over the limit, "
              "workflows/estimate.py; refused before meshing)", 9: "disk full",
              10: "contact not resolved"}


def exit_code(summary: dict) -> int:
    """What a run's summary says happened, as an exit code (``EXIT_CODES``).

    0: converged (steady state reached, last nonlinear solve converged, the roll drives the
    strip); 3: failed, the run stopped with a reason (``failure``: a linear solve, a tangled
    mesh); 6: skids, no neutral point (the outlet penalty drives the strip, ``outlet_driven``);
    4: diverged, the last nonlinear solve did not converge or the figures are not finite;
    5: not settled, the end time, step or wall-time limit came first, or the steady solver's
    free-surface/a_f fixed point did not settle; 7: not conserved, a run that converged but
    whose mass flux or power balance is off by more than its tolerance (``not_conserved``,
    the reason in ``failure``; ``CONSERVATION_TOL`` below); 10: contact not resolved, a run
    that converged with its strip inside a roll past a contact's end or a contact's end held
    at the end of its range (``contact_unresolved``, ``contact_problem`` below); 5 also when
    the ``[spread]`` section's 3D pass did not settle (``spread_settled`` false)."""
    if summary.get("converged"):
        return 0
    if summary.get("not_conserved"):
        return 7
    if summary.get("contact_unresolved"):
        return 10
    status = summary.get("status")
    if status == "failed" and summary.get("failure"):
        return 3
    if summary.get("outlet_driven"):
        return 6
    if summary.get("spread_settled") is False:
        return 5
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


#: Conservation checks of a run that converged (docs/theory.md 4.2, 4.4): |Q_out - Q_in| / Q_in
#: and the power-balance defect over the roll power. The coarse runs of the tests stay below 1 %
#: (h = 0.02 m: measured 0.6 %, tests/solvers/test_rolling.py, test_steady.py); beyond twice that the
#: figures are not an answer, and the run says so (exit code 7). Seen (issue 18,
#: tests/config/test_case_properties.py): the contact penalty lets the strip leak through the roll,
#: at low roll speeds (the penalties of Table 1 are fixed numbers in units of K, not scaled with
#: the speed: 3 % of the flux at U = 0.05 m/s and m = 0.05, the forward slip 13 % low) and with
#: sticking friction (the estimated a_f at m = 0.8: 3-7 %, 2.6 % on a 5 times finer mesh).
#: Two more (issue 30): the leak |Q_out - Q_in| / Q_in against the forward slip it falsifies
#: (``leak_to_slip`` = leak / max(|forward slip|, 1 %): a leak of a fifth of the slip makes the
#: slip uncertain by a fifth; measured with exact contact on Example 1-type passes at h = 0.02 m:
#: 0.05-0.10, the traced free tops' discretisation, 6e-6 / 0.034 on M2; the penalty on a slow lab
#: pass: 0.2-0.5), and the penalties' share of the roll power (what the penalties do instead of
#: the physics; exact contact has none on the roll, the inlet/outlet ones are inactive unless the
#: strip skids).
CONSERVATION_TOL = {"mass_flux_error": 0.02, "power_balance_error": 0.02, "leak_to_slip": 0.2,
                    "spread_mass_flux_error": 0.02, "spread_power_balance_error": 0.02,
                    "penalty_share": 0.02}


def leak_to_slip(summary: dict) -> float:
    """The mass-flux error over the forward slip (at least 1 %)."""
    leak, slip = summary.get("mass_flux_error"), summary.get("forward_slip")
    if leak is None or slip is None or not (math.isfinite(leak) and math.isfinite(slip)):
        return math.nan
    return abs(leak) / max(abs(slip), 0.01)


def conservation_problem(summary: dict) -> str | None:
    """Why a run's figures break conservation (each check over its tolerance), or None."""
    bad = [f"{key} = {abs(summary[key]):.3g} above {tol:g}" for key, tol in CONSERVATION_TOL.items()
           if summary.get(key) is not None and math.isfinite(summary[key])
           and abs(summary[key]) > tol]
    if not bad:
        return None
    if summary.get("contact_method", "penalty") == "penalty":
        why = ("the contact penalty lets the strip through the roll (penalty share "
               f"{summary.get('penalty_share', math.nan):.3g}, roll surface speed "
               f"{summary.get('roll_surface_speed', math.nan):.3g} m/s): most at low roll speeds "
               "and with sticking friction; exact contact (contact.method = \"multiplier\") or a "
               "finer mesh.h_contact")
    else:
        why = ("exact contact holds the roll; the flux crosses the traced free tops (their "
               "discretisation): a finer mesh.h_contact tightens it")
    return "not conserved: " + ", ".join(bad) + "; " + why


#: How deep the strip's free surface may lie inside a roll past a contact's end, in contact
#: elements (``roll_overlap`` over ``h_contact``): the traced surfaces settle to 1e-3 h and the
#: full strip's contact end follows a strip that curls onto its roll once it lies 1e-2 h
#: inside (solvers/full_contact_end.py). Seen before that (issue 52): the bundled
#: asymmetric_plate's strip 0.26 mm (0.13 h) inside its slower roll past the gap, exit code 0.
OVERLAP_LIMIT_H = 0.02


def contact_problem(summary: dict) -> str | None:
    """Why a converged run's contact is not an answer (exit code 10), or None: the strip's
    free surface inside a roll past a contact's end (``roll_overlap`` over
    ``OVERLAP_LIMIT_H`` elements), or a contact's end held at the end of its allowed range
    (``contact_end_kind`` ``bound``: where the strip leaves the roll is not resolved; the
    end's pressure, ``contact_end_pressure``, says which way it would move)."""
    why = []
    over, h = summary.get("roll_overlap"), summary.get("h_contact")
    if over is not None and h and over > OVERLAP_LIMIT_H * h:
        why.append(f"the strip's free surface lies {over * 1e6:.3g} um ({over / h:.3g} "
                   f"elements) inside a roll past its contact's end (limit "
                   f"{OVERLAP_LIMIT_H:g} elements)")
    rolls = summary.get("rolls") or [{"side": None, "contact_end_kind":
                                      summary.get("contact_end_kind"),
                                      "contact_end_pressure": summary.get("contact_end_pressure")}]
    for r in rolls:
        if r.get("contact_end_kind") != "bound":
            continue
        p = r.get("contact_end_pressure")
        who = f"the {r['side']} roll's" if r.get("side") else "the roll's"
        if p is not None and p < 0.0:
            why.append(f"{who} contact end is held at the end of its allowed "
                       f"range with a tensile contact stress there ({p / 1e6:.3g} MPa): the "
                       f"strip would leave the roll before it")
        else:
            why.append(f"{who} contact end is held at the end of its allowed "
                       f"range (half a contact length before the gap, or past it: a quarter "
                       f"for an elastic strip, half for one that curls onto the roll, at most "
                       f"a quarter of the exit length solver.steady_exit_length) with the "
                       f"strip still pressing on the roll: it would follow the roll further "
                       f"than the model does (asymmetric: a smaller speed or radius ratio, or "
                       f"less friction, curls it less)")
    if not why:
        return None
    return "contact not resolved: " + "; ".join(why)
