"""A solved run becomes its summary and files: ``summary.json`` (means over the last window of
the history, leaving out unconverged steps; contact figures; checks and the exit code), the
profiles, fields and history (docs/reference/summary.md). Positions are written where the case
puts the roll axis (the steady solver works in the roll's frame).

It reads the run's ``Solution`` record (``model/solution.py``, filled by
``solvers/record.py``), never the FE or solver objects: results imports neither ``fem/`` nor
``solvers/`` (the ``results-no-fe`` contract, pyproject.toml)."""
from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from hotroll.config.case import Case
from hotroll.config.plausibility import solved_warnings
from hotroll.model import contact_figures as Q
from hotroll.model.solution import RollContact, Solution
from hotroll.results.engineering import mill_setup, negative_gap_warning, width_totals
from hotroll.results.gap_summary import (
    gap_figures,
    gap_force_balance,
    legacy_row,
    roll_units,
    shifted_history,
    upper_a_f,
)
from hotroll.results.neutral import decide
from hotroll.results.outcome import conservation_problem, contact_problem, exit_code, leak_to_slip
from hotroll.results.output import write_csv, write_json, write_npz
from hotroll.results.roll_figures import roll_figures
from hotroll.results.spread_summary import (
    formula_warning,
    spread_figures,
    unsettled,
    write_spread_files,
    zone_warning,
)
from hotroll.results.summary import Summary
from hotroll.results.units import UNITS

#: The history figures the summary averages over the last window.
AVERAGED = ("roll_force", "roll_torque", "roll_power", "forward_slip", "entry_velocity",
            "exit_velocity", "mass_flux_in", "mass_flux_out", "plastic_power", "friction_power",
            "penalty_power", "outlet_penalty_power", "horizontal_force", "neutral_angle", "tension_power",
            "contact_length", "a_f", "strain_rate_measure", "slip_measure")
#: The thermal figures of the history rows that the summary averages (with a [thermal] section).
THERMAL_AVERAGED = ("exit_temperature_mean", "exit_temperature_surface", "max_temperature",
                    "min_temperature", "plastic_heat", "friction_heat_to_strip", "heat_to_roll",
                    "heat_to_air", "advected_in", "advected_out", "conducted_in",
                    "heat_balance_error")


#: A contact ending less than this many contact mesh sizes before the gap ends at the gap: the
#: rigid-plastic strip's pressure falls from about 2k to 0 there, which the discrete contact
#: resolves over its last element (its end then lies a fraction of an element before the gap).
GAP_RESOLUTION = 0.5


def contact_end_kind(contact: RollContact, h: float, prof) -> str | None:
    """How the contact ends (exact contact, steady solver): ``"gap"`` (at the roll gap, within
    ``GAP_RESOLUTION`` elements), ``"separation"`` (the strip leaves the roll before the gap
    where the pressure falls to zero; unilateral), ``"recovery"`` (after the gap: an elastic
    strip follows the rising roll while its pressure falls, ``[contact] strip_youngs_modulus``),
    ``"wrap"`` (after the gap: the strip curls onto the roll and presses on it there; the full
    strip between two rolls), ``"bound"`` (the end reached its allowed range's end) or ``"held"`` (bilateral contact:
    held to the gap whatever the pressure); ``h`` the contact mesh size (m)."""
    if not len(prof["x"]):
        return None
    if not contact.unilateral:
        return "held"
    lo, hi = contact.end_bounds
    x_e, gap, R = contact.end_x, contact.rp.axis_x, contact.rp.radius
    if abs(x_e - gap) <= GAP_RESOLUTION * h:
        return "gap"
    if x_e <= lo + 1e-9 * R or (x_e > gap and x_e >= hi - 1e-9 * R):
        return "bound"
    if x_e < gap:
        return "separation"
    return "wrap" if contact.wraps else "recovery"


def separation_angle(rp, prof) -> float:
    """The roll angle from the gap (the surface's lowest point) to the contact's end, rad."""
    gap = float(rp.angle(np.array([rp.axis_x, rp.half_exit])))
    return float(prof["angle"][-1]) - gap


def exit_strain(case: Case, sol: Solution) -> dict:
    """Mean strain of the exit strip (the solver's, ``Solution.exit_strain``: steady strip, x
    in X_roll + [0.25, 0.75] D with D = max(l_c, 2 h1); report's scheme, the material past
    X_roll + 2h that was ahead of the bite at the start) beside the homogeneous strain
    entry + 2/sqrt3 ln(h0/h1) of plane-strain compression."""
    pa = case.pass_
    homog = case.plate.mean_entry_strain + 2.0 / math.sqrt(3.0) * math.log(
        pa.entry_thickness / pa.exit_thickness)
    return {"exit_strain": sol.exit_strain, "homogeneous_exit_strain": homog}


def write_results(case: Case, sol: Solution, out: Path, wall: float,
                  extra: dict | None = None) -> Summary:
    """summary.json, contact.csv, top.csv, history.csv, fields.npz (thermal.npz,
    exit_profile.csv, fields.vtu where the run has them) of the solved run ``sol`` (its
    ``Solution`` record, ``solvers/record.py``) into ``out``; the typed summary."""
    # the half model's one roll, or an asymmetric pass's two (upper, lower: results/gap_summary)
    pd, hist, contact = sol.pass_data, sol.history, sol.contacts[0]
    two = len(sol.contacts) == 2
    prof = dict(contact.profile)
    exact = contact.exact     # exact contact: the raw multiplier needs no exit correction
    prof["normal_stress_corrected"] = (Q.exit_corrected(prof, pd.h)
                                      if case.solver.exit_pressure_correction and not exact
                                      else prof["normal_stress"])
    prof["normal_stress_smooth"] = Q.smoothed(prof, prof["normal_stress"])
    prof["shear_stress_smooth"] = Q.smoothed(prof, prof["shear_stress"])
    rp = contact.rp
    if rp.shape is not None:      # a flattened roll: its surface's offset from R there (m)
        prof["roll_offset"] = np.asarray(rp.shape.offset(prof["angle"]), dtype=float)
    # positions are written where the case puts the roll axis (``frame_shift``: the steady
    # solver works in the roll's frame)
    shift = sol.frame_shift
    write_csv(out / "contact.csv", {**prof, "x": prof["x"] + shift})
    top = sol.tops[0]
    write_csv(out / "top.csv", {**top, "x": top["x"] + shift})
    if two:       # the lower roll's contact and free surface, in its own frame (y mirrored)
        lower = dict(sol.contacts[1].profile)
        write_csv(out / "contact_lower.csv", {**lower, "x": lower["x"] + shift})
        write_csv(out / "top_lower.csv", {**sol.tops[1], "x": sol.tops[1]["x"] + shift})
        write_csv(out / "history.csv", shifted_history(hist, shift))
    else:
        write_csv(out / "history.csv", [{**r, **{k: r[k] + shift for k in ("neutral_x", "head_x")
                                                 if k in r}} for r in hist])
    fields = sol.fields.arrays()
    fields["points"] = fields["points"] + [shift, 0.0]
    write_npz(out / "fields.npz", **fields,
              contact_edges=np.concatenate(sol.fields.contact_edges) if two
              else sol.fields.contact_edges[0],
              roll_centre=np.array(rp.centre), roll_radius=rp.radius)
    if sol.thermal_strip is not None:         # the temperature's own (finer) strip mesh
        strip = dict(sol.thermal_strip)
        strip["points"] = strip["points"] + [shift, 0.0]
        write_npz(out / "thermal.npz", **strip)
    if case.output.vtk and sol.write_vtk is not None:    # a record built without FE has none
        sol.write_vtk(out / "fields.vtu", shift)
    if two:
        summary = summarise(case, replace(sol, history=[
            legacy_row(r, upper_a_f(case)) for r in hist]), prof, wall) | (extra or {})
        last = hist[-1]
        gap = case.roll_gap()
        summary.update(gap_figures(window_rows(sol), sol.contacts, gap.speed_ratio, shift))
        for entry, c, side in zip(summary["rolls"], sol.contacts, (gap.upper, gap.lower)):
            entry.update(roll_figures(case, c, c.profile, side.model))
            entry["contact_end_kind"] = (contact_end_kind(c, sol.pass_data.h, c.profile)
                                         if c.exact else None)
        summary.update(force_balance=gap_force_balance(last),
                       balance_error=last["vertical_balance_error"],
                       symmetry_stress_force_y=None, free_top_force_share=None,
                       neutral_angle_flux=None)
    else:
        summary = summarise(case, sol, prof, wall) | (extra or {})
    shift_positions(summary, shift)
    if sol.spread is not None:          # the 3D pass across the width ([spread])
        summary.update(spread_figures(case, sol.spread, summary["roll_force"]))
        said = [zone_warning(sol.spread),
                formula_warning(case.pass_.back_tension, case.pass_.front_tension)]
        if any(said):
            summary["warnings"] = [*(summary.get("warnings") or []), *filter(None, said)]
        write_spread_files(out, sol.spread, shift, case.output.vtk)
    summary["leak_to_slip"] = leak_to_slip(summary)
    overlaps = [c.overlap for c in sol.contacts if c.overlap is not None]
    summary["roll_overlap"] = max(overlaps) if overlaps else None
    # the 3D pass of a converged plane-strain pass: unsettled, the run is not an answer (its
    # conservation then not the reason)
    late = (unsettled(sol.spread, case.spread.max_rounds)
            if sol.spread is not None and summary["converged"] else None)
    if late:
        summary["converged"], summary["failure"] = False, late
    problem = conservation_problem(summary) if summary["converged"] else None
    summary["not_conserved"] = problem is not None
    if problem:
        summary["converged"], summary["failure"] = False, problem
    unresolved = contact_problem(summary) if summary["converged"] else None
    summary["contact_unresolved"] = unresolved is not None
    if unresolved:
        summary["converged"], summary["failure"] = False, unresolved
    if not case.friction.uses_a_f:
        summary["a_f"] = None            # the law has no a_f

    summary.update(sol.quantities)      # the means over the roll gap (the solver's)
    summary["mean_pressure"] = (summary["roll_force"] / summary["contact_length"]
                                if summary.get("contact_length") else None)
    if sol.spread is None:
        summary.update(width_totals(summary, case.pass_.width))
    else:
        summary["width"] = case.pass_.width
    summary.update(mill_setup(summary, case.pass_.exit_thickness, case.pass_.mill_modulus))
    summary["warnings"] = solved_warnings(case, _solved_state(case, summary),
                                          summary.get("warnings") or [])
    gap_warning = negative_gap_warning(summary.get("gap_setting"), summary.get("mill_stretch"))
    if gap_warning is not None:
        summary["warnings"] = [*(summary.get("warnings") or []), f"pass.mill_modulus: {gap_warning}"]
    summary["temperature"] = case.plate.temperature if uses_temperature(case) else None

    profile = sol.exit_profile
    summary["exit_profile"] = profile      # eta, temperature (K), strain (-) at the outlet
    if profile is not None:
        write_csv(out / "exit_profile.csv",
                  {k: np.asarray(v if v is not None else [math.nan] * len(profile["eta"]))
                   for k, v in profile.items()})

    summary["units"] = {k: u for k, u in UNITS.items() if k in summary}
    if two:
        present = {k for entry in summary["rolls"] for k in entry}
        summary["units"].update({k: u for k, u in roll_units().items()
                                 if k.split(".", 1)[1] in present})

    summary["exit_code"] = exit_code(summary)
    typed = Summary.from_dict(summary)      # every key declared once, with its unit
    write_json(out / "summary.json", typed.to_dict())
    return typed


def uses_temperature(case: Case) -> bool:
    """Whether anything of the run depends on the plate temperature: a ``[thermal]`` section,
    or a flow-stress law whose K or m changes with it (not Norton-Hoff's K, m): the summary
    gives the temperature only then (an isothermal K = 1 case has none to show)."""
    if case.thermal is not None:
        return True
    law, T = case.material.flow_stress(), case.plate.temperature
    strain = case.plate.mean_entry_strain
    try:
        return any(float(f(T)) != float(f(1.05 * T)) for f in (
            law.rate_exponent, lambda t: law.consistency(max(strain, 0.1), t)))
    except (ValueError, ArithmeticError):      # outside the law's temperatures: it depends
        return True


def shift_positions(summary: dict, shift: float) -> None:
    """Move the summary's x positions by ``shift`` (the roll's frame to the case's)."""
    if not shift:
        return
    for key in ("neutral_point", "roll_centre", "contact_start", "contact_end"):
        if summary.get(key) is not None:
            summary[key] = [summary[key][0] + shift, summary[key][1]]
    if summary.get("sticking_zone_x") is not None:
        summary["sticking_zone_x"] = [x + shift for x in summary["sticking_zone_x"]]
    summary["contact_loss"] = [[a + shift, b + shift] for a, b in summary["contact_loss"]]


def _nanmean(values) -> float:
    """The mean of the finite values; NaN if there is none (the transient scheme's advected
    flows, which a Lagrangian plate does not have)."""
    vals = np.asarray(values, dtype=float)
    vals = vals[np.isfinite(vals)]
    return float(vals.mean()) if len(vals) else math.nan


#: the share of the contact length from its start over which ``entry_pressure`` is averaged
ENTRY_SHARE = 0.05


def entry_pressure(prof: dict) -> float | None:
    """The contact pressure's entry value (Pa): its mean over the first ``ENTRY_SHARE`` of the
    contact's length along the arc. The corner's own nodal value is not a limit: a rate-
    dependent strip's stress is singular at the entry corner, about r^-m (the flow turns
    there, its strain rate ~ 1/r), so the first vertex's pressure grows as h^-m under
    refinement (measured, docs/validation/contact.md); its mean over a fixed length
    converges."""
    x, y = np.asarray(prof["x"], dtype=float), np.asarray(prof["y"], dtype=float)
    if len(x) < 2:
        return None
    p = -np.asarray(prof["normal_stress"], dtype=float)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    L = ENTRY_SHARE * s[-1]
    t = np.linspace(0.0, L, 401)
    return float(np.trapezoid(np.interp(t, s, p), t) / L)


def window_rows(sol: Solution) -> list[dict]:
    """The history rows the summary's means take: the last ``window`` rows but those whose
    nonlinear solve did not converge (max_iterations reached: not a solution; their figures
    stay in history.csv), or all of the window if none converged."""
    window = sol.history[-sol.window:]
    return [r for r in window if r.get("solver_converged", True)] or window


def summarise(case: Case, sol: Solution, prof: dict, wall: float) -> dict:
    """The summary.json dictionary: last-window means and run figures."""
    contact, pd, last = sol.contacts[0], sol.pass_data, sol.history[-1]
    rp, state, stats = contact.rp, sol, sol.solve_stats
    window = state.history[-sol.window:]
    solved = window_rows(sol)
    steady_solver = case.solver.method == "steady"
    mean = {k: float(np.nanmean([r[k] for r in solved])) if any(
        math.isfinite(r[k]) for r in solved) else math.nan for k in AVERAGED}
    outlet_driven = mean["outlet_penalty_power"] < -0.05 * mean["plastic_power"]
    # the neutral story, decided once (results/neutral.py; docs/theory.md 1e): the split of the
    # slip's signs (``Q.neutral_index``), none where it is noise in a sticking zone or the
    # strip skids. The flux angle (the strip's mean speed = the roll's horizontal speed) is
    # given beside it: it needs no slip sign, and it is not the neutral point
    neutral = decide(prof, rp, pd.h, mean["neutral_angle"], bool(outlet_driven))
    ang_flux = Q.flux_neutral_angle(rp, mean["mass_flux_in"])
    cx, cy = rp.centre
    steady = state.status == "steady"
    exact = contact.exact
    # exact contact: every tensile node of the raw multiplier (bilateral), and the stretch of the
    # arc the strip has left (unilateral); penalties: stretches of 2h of the corrected stress
    loss = Q.contact_loss(prof, prof["normal_stress_corrected"], 0.0 if exact else 2.0 * pd.h)
    unilateral = contact.unilateral
    end_kind = contact_end_kind(contact, pd.h, prof) if steady_solver and exact else None
    contact_figures = {
        "contact_method": contact.method,
        "unilateral": unilateral,
        "contact_end_kind": end_kind,
        "separation_angle": separation_angle(rp, prof) if end_kind == "separation" else None,
        "contact_end_pressure": float(-prof["normal_stress"][-1])
        if steady_solver and exact and len(prof["x"]) else None,
        "contact_start_angle": float(prof["angle"][0]) if len(prof["angle"]) else None,
        "contact_end_angle": float(prof["angle"][-1]) if len(prof["angle"]) else None,
        "min_contact_pressure": float(-np.max(prof["normal_stress"]))
        if len(prof["normal_stress"]) else None,
        "entry_pressure": entry_pressure(prof),
    }
    sn_raw, sn_cor = prof["normal_stress"], prof["normal_stress_corrected"]
    seg = np.hypot(np.diff(prof["x"]), np.diff(prof["y"])) if len(prof["x"]) > 1 else []
    trap = (lambda f: float(np.sum(0.5 * (f[1:] + f[:-1]) * seg))) if len(seg) else (lambda f: 0.0)
    iters = [r["iterations"] for r in state.history]
    return {
        "case_name": case.name, "method": case.solver.method, "status": state.status,
        "failure": state.failure or None,
        "converged": bool(steady and last["solver_converged"] and not outlet_driven),
        "steady_state": steady, "outlet_driven": bool(outlet_driven),
        # docs/theory.md 1e: the one neutral story (results/neutral.py)
        **neutral.to_summary(), "neutral_angle_flux": ang_flux,
        **{k: mean[k] for k in ("roll_force", "roll_torque", "roll_power", "forward_slip",
                                "entry_velocity", "exit_velocity", "mass_flux_in",
                                "mass_flux_out", "plastic_power", "friction_power",
                                "penalty_power", "outlet_penalty_power", "horizontal_force",
                                "tension_power", "a_f", "contact_length")},
        "force_balance": {part: [last.get(f"{part}_force_x", 0.0), last[f"{part}_force_y"]]
                          for part in ("roll", "free_top", "face", "tension", "symmetry")},
        "symmetry_stress_force_y": last["symmetry_stress_force_y"],
        "balance_error": last["balance_error"],
        "free_top_force_share": last["free_top_force_share"],
        "power_balance_error": last["power_balance_error"],
        "penalty_share": last["penalty_share"],
        "mass_flux_error": abs(mean["mass_flux_out"] - mean["mass_flux_in"])
        / abs(mean["mass_flux_in"]) if math.isfinite(mean["mass_flux_out"]) else math.nan,
        "exit_correction_normal_force_change": (trap(sn_cor) - trap(sn_raw)) / trap(sn_raw)
        if trap(sn_raw) else 0.0,
        "contact_loss": loss, "contact_loss_detected": bool(loss), **contact_figures,
        "exit_thickness": last.get("exit_thickness_measured", math.nan),
        # exact contact: what the pressure still moved in the last Newton step (Pa; sticking
        # zones, fem/nonlinear.py)
        "pressure_last_update": contact.pressure_last_update
        if steady_solver and exact else None,
        "steps": 0 if steady_solver else last["step"] + 1,
        "time": None if steady_solver else last["time"],
        "dt": None if steady_solver else stats["dt"],
        "newton_solves": stats["newton_solves"] if steady_solver else None,
        "coupling_updates": stats["coupling_updates"] if steady_solver else None,
        "fixed_point_settled": stats["fixed_point_settled"] if steady_solver else None,
        "free_surface": case.plate.free_surface,
        "surface_residual_h": stats["surface_residual_h"] if steady_solver else None,
        "nonlinear_iterations": int(np.sum(iters)),
        "iterations_per_step": None if steady_solver else (
            float(np.mean(iters[1:])) if len(iters) > 1 else float(iters[0])),
        "dofs": sol.dofs, "h_contact": pd.h, "wall_time_s": wall,
        "roll_centre": [cx, cy], "roll_radius": rp.radius, "roll_surface_speed": rp.u_roll,
        "contact_start": [float(prof["x"][0]), float(prof["y"][0])] if len(prof["x"]) else None,
        "contact_end": [float(prof["x"][-1]), float(prof["y"][-1])] if len(prof["x"]) else None,
        "K": pd.K, "m": pd.m,
        "nonlinear": sol.nonlinear,
        **exit_strain(case, sol),
        "friction_law": case.friction.law, "friction_mu": case.friction.mu,
        "friction_factor": case.friction.factor,
        "back_tension": case.pass_.back_tension, "front_tension": case.pass_.front_tension,
        "averaged_over_steps": len(solved),
        "unconverged_steps_in_window": len(window) - len(solved),
        "thermal": case.thermal is not None,
        **{k: _nanmean([r[k] for r in solved]) for k in THERMAL_AVERAGED
           if case.thermal is not None},
        **({"thermal_dofs": last["thermal_dofs"], "thermal_layer": last["thermal_layer"]}
           if case.thermal is not None else {}),
        **({"exit_temperature_surface_lower": _nanmean(
            [r["exit_temperature_surface_lower"] for r in solved])}
           if case.thermal is not None and "exit_temperature_surface_lower" in last else {}),
        **roll_figures(case, contact, prof),
    }


def _solved_state(case, summary: dict) -> dict:
    """The pass's state as solved, for the fit ranges: strain from the entry's to the exit's
    mean, the mean strain rate in the gap, the temperature from the coldest to the hottest of
    the plate's and the outlet's means (K); a figure the run did not compute is left out."""
    def num(key):
        v = summary.get(key)
        return float(v) if isinstance(v, (int, float)) and math.isfinite(v) else None

    out = {}
    strain = num("exit_strain")
    if strain is not None:
        out["strain"] = (case.plate.mean_entry_strain, strain)
    rate = num("mean_strain_rate")
    if rate is not None:
        out["strain_rate"] = (rate, rate)
    temps = [t for t in (case.plate.temperature, num("outlet_temperature_mean")) if t]
    out["temperature"] = (min(temps), max(temps))
    return out

