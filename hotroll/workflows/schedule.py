"""Running a pass schedule (issue 17): pass after pass, each from the previous exit state.

The state handed on is the strip's thickness as the pass's solve leaves it (the outlet's
measured thickness, ``exit_thickness`` of its summary: a thick strip thins on past the gap, an
elastic one recovers; issue 51), its temperature and strain profiles through the half thickness
(``results/profiles.py``, measured at the steady strip's outlet) and, in a tandem mill, its
mass flux. A pass whose gap to set comes out negative (the mill stretch above the exit
thickness) is reported with what that means (``gauge.negative_gap_warning``: in the progress
lines and schedule.json ``warnings``). Between two passes the
temperature profile cools in air (``thermal/interpass.cool``: 1D conduction with convection
and radiation) and the strain is kept (``strain_retained`` of it). With
``mill.speeds = "mass_flow"`` each stand after the first gets the roll speed
U_k = Q / ((h_k/2) (1 + f_k)) that passes the first stand's flux Q, with its own forward slip
f_k: the previous stand's slip is the start, the stand's solve moves its speed until its
inlet passes Q (``solvers/couplings.TandemSpeed``, to a quarter of ``mass_flow_tolerance``);
where that does not settle, or for a stand set by its roll gap (whose gauge solves do not take
it), the stand is solved again, warm, until the fluxes agree.

Each pass is a ``hotroll run`` into ``DIR/NN_name/`` (its own summary, profiles, figures); a
finished pass whose case file is unchanged is not solved again (resume). Output:
``schedule.csv`` (one row per pass with its transport), ``schedule.json`` (the same with
units and the profiles handed on) and ``schedule.png``.
"""
from __future__ import annotations

import time
from functools import lru_cache
from pathlib import Path
from typing import Callable

import numpy as np

from hotroll.config.schedule import Schedule
from hotroll.config.spread import temperature_matters
from hotroll.model.interpass import cool, enthalpy_mean
from hotroll.model.interpass_section import cool_section
from hotroll.model.microstructure.softening import PassState
from hotroll.model.profile import ThicknessProfile
from hotroll.model.section import SectionProfile
from hotroll.model.thermal_properties import ThermalProperties
from hotroll.results.outcome import EXIT_CODES
from hotroll.results.output import write_csv, write_json
from hotroll.results.units import UNITS
from hotroll.workflows import microstructure as MS
from hotroll.workflows.gauge import negative_gap_warning
from hotroll.workflows.runner import finished_summary, run_case
from hotroll.workflows.schedule_rolls import curl_columns
from hotroll.workflows.strip_state import (  # noqa: F401 (the schedule's names)
    StripState,
    entry_state,
    exit_state,
    exit_thickness,
    set_exit_thickness,
)
from hotroll.workflows.sweep import Sweep
from hotroll.workflows.tandem import solve_tensions


def pass_case(sch: Schedule, k: int, state: StripState, omega: float | None = None,
              tensions: tuple[float, float] | None = None):
    """The k-th pass entering with ``state`` (uniform profiles are given as numbers);
    ``tensions``: its (back, front) tensions in Pa (None: the pass's own)."""
    T, e = state.temperature, state.strain
    return sch.pass_case(k, state.thickness, _enthalpy_mean(sch, T),
                         None if T.is_uniform else T, e.mean(),
                         None if e.is_uniform else e, omega, tensions, width=state.width,
                         temperature_section=_section_for(sch, k, state))


def _section_for(sch: Schedule, k: int, state: StripState):
    """The k-th pass's entry temperature over the cross-section (``spread.temperature_section``),
    or None: where the strip's edges cooled (a [spread] schedule's transport) and the pass's
    flow stress feels it (a thermal pass, a law that depends on the temperature). An edge
    zone's interior is mid-width's (its cut is plane strain)."""
    sec = state.section
    if (sec is None or sch.spread is None or sch.passes[k].isothermal
            or not temperature_matters(sch.material.flow_stress(), state.temperature.values[0])):
        return None
    if sch.spread.edge_zone is not None and state.width is not None:
        sec = sec.uniform_up_to(max(0.0, 1.0 - sch.spread.edge_zone / (0.5 * state.width)))
    return None if sec.is_uniform_across() else sec


def _enthalpy_mean(sch: Schedule, T: ThicknessProfile) -> float:
    """The profile's mean temperature by its heat content (K)."""
    if T.is_uniform:
        return T.values[0]
    return _profile_enthalpy_mean(sch.material.thermal_properties(), T)


@lru_cache(maxsize=64)
def _profile_enthalpy_mean(props: ThermalProperties, T: ThicknessProfile) -> float:
    """``enthalpy_mean`` of a profile (both frozen: the same profile's mean is asked for two to
    four times a pass, by its case, its row and the next pass's, each a 40-step bisection)."""
    return enthalpy_mean(props, np.asarray(T.values), T.weights())


def transport(sch: Schedule, k: int, state: StripState, exit_velocity: float,
              deformed: PassState | None = None):
    """The state after the k-th pass's transport, its row (duration, heat lost) and the
    softening; with the pass's ``deformed`` state (a microstructure model) the retained
    strain and the grain size from the kinetics (``workflows/microstructure.py``)."""
    tr = sch.passes[k].transport
    th = sch.thermal
    duration = tr.duration if tr.duration is not None else tr.distance / exit_velocity
    T = state.temperature
    surface = th.law("surface", htc_air=tr.htc_air, emissivity=tr.emissivity)
    props = sch.material.thermal_properties()
    section = None
    if sch.spread is not None and state.width is not None:
        # across the width too: the edges cool from the side (model/interpass_section.py)
        res = cool_section(state.section or SectionProfile.across(T), 0.5 * state.thickness,
                           0.5 * state.width, duration, props, surface,
                           th.ambient_temperature, record=deformed is not None)
        section = res.section
        T_new = section.mid_width()
        section_mean = res.mean
        # J per m^2 of the quarter's cooled surface (the top's half width and the edge's half
        # thickness), as the 1D model's per m^2 of its top
        heat_lost = res.heat_lost / (0.5 * state.width + 0.5 * state.thickness)
        surface_T = float(T_new.values[-1])
    else:
        res = cool(np.asarray(T.eta), np.asarray(T.values), 0.5 * state.thickness, duration,
                   props, None, None, th.ambient_temperature, surface=surface,
                   record=deformed is not None)
        eta = res.y / res.y[-1]
        T_new = ThicknessProfile(tuple(eta), tuple(res.temperature))
        heat_lost, surface_T = res.heat_lost, res.surface
    soft = None
    if deformed is None:
        new = StripState(state.thickness, T_new, state.strain.scaled(tr.strain_retained),
                         width=state.width, section=section)
    else:     # the kinetics at mid-width (its column's history with the section)
        soft = MS.after_transport(sch, deformed, res, f"pass[{k + 1}].transport")
        new = StripState(state.thickness, T_new, *MS.handed_on(soft), width=state.width,
                         section=section)
    row = {"transport_duration": duration, "transport_heat_lost": heat_lost,
           "transport_balance_error": res.balance_error,
           # the next pass's entry mean (mid-width's, with the section: its plate temperature)
           "next_entry_temperature_mean": (res.mean if section is None
                                           else _enthalpy_mean(sch, T_new)),
           "next_entry_temperature_surface": surface_T,
           "next_entry_strain_mean": new.strain.mean()}
    if section is not None:
        row["next_entry_temperature_edge"] = section.edge_mean()
        row["next_entry_temperature_section_mean"] = section_mean
    if soft is not None:
        row.update(MS.transport_columns(soft))
    return new, row, soft


def _reuse(case, out: Path) -> dict | None:
    """A finished, converged pass's summary when its case file is the same (resume); a thermal
    pass's with its exit profile (an isothermal pass may have none)."""
    summary = finished_summary(case, out)
    if summary and summary.get("exit_code") == 0 and (summary.get("exit_profile")
                                                       or case.thermal is None):
        return summary
    return None


def _last_speed(pdir: Path) -> float | None:
    """The roll angular velocity of the pass last run in ``pdir`` (its case.toml), or None."""
    import tomllib

    try:
        return float(tomllib.loads((pdir / "case.toml").read_text())["pass"]
                     ["roll_angular_velocity"])
    except (OSError, KeyError, ValueError, tomllib.TOMLDecodeError):
        return None


def run_schedule(sch: Schedule, out: Path, *, resume: bool = True,
                 progress: Callable[[str], None] | None = None,
                 figure: bool = True) -> list[dict]:
    """Roll the schedule into ``out``; returns the table's rows (module docstring).
    ``figure``: schedule.png (each pass's own figures follow its [output] figures)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    say = progress or (lambda msg: None)
    t_start = time.perf_counter()
    # each pass starts from the last one solved; history.csv keeps the final state only
    sweep = Sweep(similar=sch.mill.start_from_previous, history=False)

    def roll(tensions=None, quiet: bool = False) -> tuple[list[dict], list[dict]]:
        rows, profiles = _roll(sch, out, resume, sweep, (lambda m: None) if quiet else say,
                               tensions)
        _write(sch, out, rows, profiles, time.perf_counter() - t_start, extra)
        return rows, profiles

    extra: dict = {}
    if sch.mill.tensions == "from_speeds":
        rows, profiles, info = solve_tensions(sch, roll, _previous_tensions(out) if resume
                                              else None, say)
        extra.update(info)
    else:
        rows, profiles = roll()
    extra.pop("warnings", None)
    warnings = [f"{r['name']}: {w}" for r in rows
                if (w := negative_gap_warning(r.get("gap_setting"), r.get("mill_stretch")))]
    if warnings:
        extra["warnings"] = warnings
    _write(sch, out, rows, profiles, time.perf_counter() - t_start, extra)
    if figure:
        from hotroll.results.figures.microstructure import plot_microstructure
        from hotroll.results.schedule_plot import plot_schedule  # matplotlib only when drawing

        plot_schedule(rows, out / "schedule.png", width=sch.strip.width)
        plot_microstructure(profiles, out / "microstructure.png")
    return rows


def _previous_tensions(out: Path) -> list[float] | None:
    """The interstand tensions a finished run of this schedule settled on (schedule.json)."""
    import json

    try:
        return [float(t) for t in json.loads((out / "schedule.json").read_text())
                ["interstand_tensions"]]
    except (OSError, KeyError, TypeError, ValueError):
        return None


def _roll(sch: Schedule, out: Path, resume: bool, sweep: Sweep, say, tensions=None):
    """One pass after the other from the entry strip; ``tensions``: the interstand tensions
    (Pa, one fewer than the passes; None: each pass's own). (rows, profiles)."""
    state, rows, profiles = entry_state(sch), [], []
    flux = None                                    # the tandem's mass flux (half strip)
    for k, p in enumerate(sch.passes):
        t0 = time.perf_counter()
        omega = None
        if sch.mill.speeds == "mass_flow" and k > 0:
            f_guess = rows[-1]["forward_slip"]
            h1 = p.exit_thickness if p.exit_thickness is not None else (
                p.roll_gap + rows[-1].get("mill_stretch", 0.0))     # a guess: the flux decides
            omega = flux / (0.5 * h1 * (1.0 + f_guess)) / p.roll_radius
            if resume:          # the speed a finished run of this pass settled on
                omega = _last_speed(out / f"{k + 1:02d}_{sch.pass_name(k)}") or omega
        pulls = None
        if tensions is not None:
            pulls = (tensions[k - 1] if k > 0 else p.back_tension,
                     tensions[k] if k < len(sch.passes) - 1 else p.front_tension)
        solves, iterations, tries = 0, 0, 0
        while True:
            tries += 1
            case = pass_case(sch, k, state, omega, pulls)
            pdir = out / case.name
            summary = _reuse(case, pdir) if resume else None
            if summary is None:
                # a tandem stand's speed is found inside its solve (TandemSpeed), to a quarter
                # of the tolerance; the loop solves again only where that did not settle
                target = (None if flux is None or sch.mill.speeds != "mass_flow"
                          or case.solver.method != "steady"
                          else (flux, 0.25 * sch.mill.mass_flow_tolerance))
                summary = run_case(case, pdir, resume=False, sweep=sweep, mass_flux=target)
                solves += int(summary.get("gauge_solves", 1))
                iterations += int(summary.get("nonlinear_iterations") or 0)
                if target is not None:         # the speed the solve settled on
                    omega = _last_speed(pdir) or omega
                    case = pass_case(sch, k, state, omega, pulls)
            if summary.get("exit_code") != 0:
                raise ScheduleError(k, case.name, summary, rows)
            if flux is None or sch.mill.speeds != "mass_flow":
                break
            miss = summary["mass_flux_in"] / flux - 1.0
            if abs(miss) <= sch.mill.mass_flow_tolerance or tries >= 6:
                break
            omega = case.pass_.roll_angular_velocity / (1.0 + miss)
        if flux is None:
            flux = summary["mass_flux_out"]
        entry_T = _enthalpy_mean(sch, state.temperature)
        entry_e = state.strain.mean()
        ps = None
        if sch.microstructure.kinetics is not None:
            ps = MS.deformed(sch, state.strain, state.grain, summary, k)
        state = exit_state(sch, case, summary, state.grain, state)
        row = _pass_row(sch, k, case, summary, entry_T, entry_e, solves, iterations,
                        time.perf_counter() - t0)
        row["outlet_temperature_mean"] = _enthalpy_mean(sch, state.temperature)
        row["exit_strain_mean"] = state.strain.mean()
        profiles.append({"pass": row["name"], "exit": state.to_dict()})
        soft = None
        if ps is not None:
            row.update(MS.pass_columns(ps))
        if p.transport is not None:
            state, trow, soft = transport(sch, k, state, summary["exit_velocity"], ps)
            row.update(trow)
            profiles[-1]["after_transport"] = state.to_dict()
        if ps is not None:
            record = MS.profile_dict(ps, soft)
            profiles[-1]["microstructure"] = record
            MS.write_table(pdir / "microstructure.csv", record)
        rows.append(row)
        say(_line(row))
        warning = negative_gap_warning(row.get("gap_setting"), row.get("mill_stretch"))
        if warning:
            say(f"{row['name']}: WARNING: {warning}")
    return rows, profiles


class ScheduleError(RuntimeError):
    """A pass that did not converge: the schedule stops there (the passes before are kept)."""

    def __init__(self, k: int, name: str, summary: dict, rows: list[dict] | None = None):
        self.k, self.name, self.summary, self.rows = k, name, summary, rows or []
        code = summary.get("exit_code")
        why = f": {summary['failure']}" if summary.get("failure") else ""
        super().__init__(f"pass {k + 1} ({name}) ended with exit code {code}: "
                         f"{EXIT_CODES.get(code, '?')} (status {summary.get('status')}{why}); "
                         f"the schedule stops there, the passes before it are written")


def _pass_row(sch, k, case, s, entry_T, entry_e, solves, iterations, wall) -> dict:
    pa = case.pass_
    h1 = exit_thickness(case, s)
    row = {"pass": k + 1, "name": sch.pass_name(k), "case": case.name,
           "entry_thickness": pa.entry_thickness, "exit_thickness": h1,
           "reduction": 1.0 - h1 / pa.entry_thickness,
           "roll_radius": pa.roll_radius, "roll_surface_speed": pa.roll_surface_speed,
           "roll_angular_velocity": pa.roll_angular_velocity,
           "back_tension": pa.back_tension, "front_tension": pa.front_tension,
           "roll_force": s["roll_force"], "roll_torque": s["roll_torque"],
           "roll_power": s["roll_power"], "forward_slip": s["forward_slip"],
           "entry_velocity": s["entry_velocity"], "exit_velocity": s["exit_velocity"],
           "mass_flux": s["mass_flux_in"], "mass_flux_out": s["mass_flux_out"],
           "mean_flow_stress": s.get("mean_flow_stress"),
           "entry_temperature_mean": entry_T,
           "exit_temperature_mean": s.get("exit_temperature_mean"),
           "exit_temperature_surface": s.get("exit_temperature_surface"),
           "entry_strain_mean": entry_e,
           "exit_strain_mean": None,          # the profile handed on (run_schedule)
           "homogeneous_exit_strain": s["homogeneous_exit_strain"],
           "newton_iterations": iterations, "fe_solves": solves, "wall_time": wall}
    # the roll's flattening and the stand's stretch, where the schedule asks for them
    row.update({key: s[key] for key in ("roll_flattening", "roll_equivalent_radius",
                                        "roll_gap", "gauge_thickness", "mill_stretch",
                                        "gap_setting")
                if key in s})
    row.update(curl_columns(s))
    if "spread" in s:                     # the pass's 3D pass ([spread])
        row.update({"entry_width": s["width"], "exit_width": s["exit_width"],
                    "spread": s["spread"]})
    if sch.strip.width is not None:
        row.update({"roll_force_total": s.get("roll_force_total"),
                    "roll_torque_total": s.get("roll_torque_total"),
                    "mill_power_total": s.get("mill_power_total")})
    return row


def _line(r: dict) -> str:
    text = (f"{r['name']}: {1e3 * r['entry_thickness']:.2f} -> {1e3 * r['exit_thickness']:.2f}"
            f" mm, {r['roll_surface_speed']:.3g} m/s, force {1e-6 * r['roll_force']:.3f} MN/m,"
            f" torque {1e-3 * r['roll_torque']:.2f} kN m/m, exit "
            + (f"{r['exit_temperature_mean']:.1f} K" if r.get('exit_temperature_mean')
               is not None else "isothermal")
            + f", strain {r['exit_strain_mean']:.3f}, "
            f"{r['fe_solves']} FE solve(s), {r['wall_time']:.1f} s")
    if "speed_ratio" in r:
        text += (f"; asymmetric (speed ratio {r['speed_ratio']:.4g}): exit curvature "
                 f"{r['exit_curvature']:.4g} 1/m, angle {r['exit_angle']:.4g} rad, torques "
                 f"{1e-3 * r['upper_roll_torque']:.2f} / {1e-3 * r['lower_roll_torque']:.2f} "
                 f"kN m/m (upper / lower)")
    if "transport_duration" in r:
        text += (f"; transport {r['transport_duration']:.2f} s -> "
                 f"{r['next_entry_temperature_mean']:.1f} K")
    return text


def _write(sch, out: Path, rows: list[dict], profiles: list[dict], wall: float,
           extra: dict | None = None) -> None:
    keys = list(dict.fromkeys(k for r in rows for k in r))
    write_csv(out / "schedule.csv", [{k: r.get(k) for k in keys} for r in rows])
    extra = extra or {}
    write_json(out / "schedule.json", {
        "name": sch.name, "passes": rows, "profiles": profiles, "wall_time": wall,
        "fe_solves": extra.get("fe_solves", sum(r["fe_solves"] for r in rows)), **extra,
        "units": {k: u for k, u in UNITS.items() if k in keys or k in extra}})
