"""Is the case a pass a mill could roll, in the units it claims (issue 51, item 3)?

Checked before anything is meshed. Two kinds of findings, each a ``section.key: ...`` line
naming the figure, the range it left and the likely fix:

- **refusals** (a ``CaseError`` unless ``solver.force``): what is almost surely a unit slip (a
  roll surface speed above the fastest flat mills', lengths that only make sense in mm, a
  grade's hot-working data at a room temperature);
- **warnings** (the summary's ``warnings``, the console, the page): a pass outside its law's
  published fit ranges (temperature, strain, strain rate; "far" outside by FAR_*), a steel
  below its austenite range, and a nondimensional case (the report's Example 1, K = 1) named
  as such. A fit range is not a refusal: Misaka's 30-200 1/s would refuse every plate and
  roughing pass, and a schedule's strain builds up from pass to pass.

The bounds, with what they rest on ([S] read in a source, [E] our estimate;
docs/notes/issue51-ranges.md):
"""
from __future__ import annotations

import math

#: m/s: above it a flat pass is refused. The fastest flat mills found: aluminium foil mills
#: "in excess of 2,000 m/min" (33 m/s; Osborne, Materials World 2009 [S]); a steel tandem cold
#: mill at 1,300 m/min (21.7 m/s, SMS [S]). Wire rod blocks run at 115-140 m/s [S], not flat.
MAX_SURFACE_SPEED = 60.0
#: m: larger work-roll radii or thicknesses are taken for lengths written in mm. No published
#: maximum found; slabs 178-254 mm (AIST 2014 hot strip mill roundup [S]), work rolls of
#: lab and tandem mills 0.085-0.29 m [S]; the bounds are 4-8x those [E]
MAX_ROLL_RADIUS = 2.0
MAX_THICKNESS = 1.0
#: K: a grade's data (hot-working fits) at a lower plate temperature is taken for a
#: temperature written in degC as a number [E: the coldest hot-working fit, Al99.5, starts
#: at 250 degC = 523 K]
MIN_GRADE_TEMPERATURE = 500.0
#: Pa: a mean flow stress below it is not a metal's at hot-working rates (aluminium near its
#: solidus has some MPa) [E]: the case is nondimensional (or its law not in Pa)
NONDIMENSIONAL_STRESS = 1e5
#: how far outside a fit's range a pass is called "far" outside [E]: temperature by more
#: than this (K), strain rate by more than this factor, strain by more than this factor
FAR_TEMPERATURE = 100.0
FAR_RATE = 10.0
FAR_STRAIN = 2.0
#: K: a steel below it is no longer austenite (Ghosh and Olson's austenite from 800 degC, the
#: bound model/strip_elasticity.py takes [S]); a grade's hot-working fit then describes
#: another phase (ferritic rolling exists, so a warning) [E]
HOT_WORKING_FROM = {"steel": 800.0 + 273.15}


def _celsius(t: float) -> str:
    return f"{t:.6g} K ({t - 273.15:.6g} degC)"


def pass_estimates(case) -> dict:
    """The pass's strain and mean strain rate before the solve, by the homogeneous
    estimates: strain (2/sqrt 3) ln(h0/h1) added to the entry strain, mean rate that strain
    over the contact time L / U (L the projected contact length, U the roll's surface speed)."""
    p = case.pass_
    pass_strain = 2.0 / math.sqrt(3.0) * math.log(p.entry_thickness / p.exit_thickness)
    rate = pass_strain * p.roll_surface_speed / p.contact_length
    entry = case.plate.mean_entry_strain
    return {"strain": (entry, entry + pass_strain), "strain_rate": (rate, rate),
            "temperature": (case.plate.temperature, case.plate.temperature)}


def outside(validity, figures: dict) -> list[tuple[str, tuple, tuple, bool]]:
    """(variable, the pass's (low, high), the fit's (low, high), far) for each variable of
    ``figures`` outside the law's published range; far per FAR_*."""
    out = []
    for key in ("temperature", "strain", "strain_rate"):
        fit, got = getattr(validity, key), figures.get(key)
        if fit is None or got is None:
            continue
        lo, hi = fit
        g_lo, g_hi = got
        if key == "strain":     # below its range a law holds the flow stress at its floor
            g_lo = max(g_lo, lo)
        if g_lo >= lo and g_hi <= hi:
            continue
        if key == "temperature":
            far = g_lo < lo - FAR_TEMPERATURE or g_hi > hi + FAR_TEMPERATURE
        else:
            factor = FAR_RATE if key == "strain_rate" else FAR_STRAIN
            far = (lo > 0 and g_lo < lo / factor) or g_hi > hi * factor
        out.append((key, (g_lo, g_hi), (lo, hi), far))
    return out


_WHERE = {"temperature": "plate.temperature", "strain": "pass.exit_thickness",
          "strain_rate": "pass.roll_angular_velocity"}
_UNIT = {"temperature": "K", "strain": "-", "strain_rate": "1/s"}


def range_lines(name: str, found, when: str) -> list[str]:
    """``found`` (``outside``) as lines: the figure, the fit's range, what to do."""
    lines = []
    for key, got, fit, far in found:
        u = _UNIT[key]
        shown = (f"{got[0]:.4g}" if got[0] == got[1] else f"{got[0]:.4g} to {got[1]:.4g}")
        where = _WHERE[key]
        if key == "strain" and got[0] > fit[1]:     # the strain it enters with is already out
            where = "plate.entry_strain"
        lines.append(f"{where}: the {when} {key.replace('_', ' ')} {shown} {u} is "
                     f"{'far ' if far else ''}outside {name}'s fit range {fit[0]:.4g} to "
                     f"{fit[1]:.4g} {u}: the flow stress there is extrapolated")
    return lines


def _law_name(case) -> str:
    m = case.material
    return f"grade {m.grade}" if m.grade is not None else f"the {m.law} law"


def refusals(case) -> list[str]:
    """The findings that stop a run unless ``solver.force`` (module docstring). A
    nondimensional case (its flow stress below ``NONDIMENSIONAL_STRESS``) has units of its
    own: its speeds and lengths are not checked against mills'."""
    p, out = case.pass_, []
    stress = _mean_stress(case)
    dimensional = stress is None or stress >= NONDIMENSIONAL_STRESS
    speed = p.roll_surface_speed if dimensional else 0.0
    mm = " (the lengths look like mm: write \"500 mm\" or 0.5)"
    if speed > MAX_SURFACE_SPEED:
        out.append(f"pass.roll_angular_velocity: the roll's surface speed R omega = {speed:.4g} "
                   f"m/s is above {MAX_SURFACE_SPEED:g} m/s, faster than any flat mill"
                   f"{mm if p.roll_radius > MAX_ROLL_RADIUS else ''}; give omega in rad/s "
                   f"(\"60 rpm\" is read too)")
    if dimensional and p.roll_radius > MAX_ROLL_RADIUS:
        out.append(f"pass.roll_radius: {p.roll_radius:g} m is above {MAX_ROLL_RADIUS:g} m, no "
                   f"work roll is that large{mm}")
    if dimensional and p.per_roll:           # a roll's own table (the upper's speed is above)
        out += _own_roll_refusals(p)
    if dimensional and p.entry_thickness > MAX_THICKNESS:
        out.append(f"pass.entry_thickness: {p.entry_thickness:g} m is above "
                   f"{MAX_THICKNESS:g} m, no slab is that thick{mm}")
    if case.material.grade is not None and case.plate.temperature < MIN_GRADE_TEMPERATURE:
        t = case.plate.temperature
        out.append(f"plate.temperature: {_celsius(t)} is below {MIN_GRADE_TEMPERATURE:g} K, "
                   f"where grade {case.material.grade}'s hot-working data do not reach (cold "
                   f"rolling needs a law of its own); if you meant {t:g} degC, write "
                   f"\"{t:g} degC\"")
    return out


def warnings(case) -> list[str]:
    """The findings a run reports and goes on (module docstring): a pass outside its fit's
    ranges (estimated), a steel below its austenite range, a nondimensional case."""
    out = []
    validity = case.material.flow_stress().validity
    law = _law_name(case)
    found = outside(validity, pass_estimates(case))
    out += range_lines(law, found, "estimated")
    missing = [k.replace("_", " ") for k in ("temperature", "strain", "strain_rate")
               if getattr(validity, k) is None]
    if missing and case.material.grade is not None:
        out.append(f"material.grade: {case.material.grade}'s fit ranges of {', '.join(missing)} "
                   f"are not known (not in the source it was read from): the pass is not "
                   f"checked against them")
    t = case.plate.temperature
    family = _family(case.material.grade) if case.material.grade is not None else None
    low = HOT_WORKING_FROM.get(family)
    if low is not None and t < low:
        out.append(f"plate.temperature: {_celsius(t)} is below {_celsius(low)}, where "
                   f"{family} is no longer austenite (Ghosh and Olson); if you meant {t:g} "
                   f"degC, write \"{t:g} degC\"")
    stress = _mean_stress(case)
    if stress is not None and stress < NONDIMENSIONAL_STRESS:
        out.append(f"material: the flow stress at the pass's estimated state is {stress:.3g} "
                   f"Pa, below any metal's hot flow stress ({NONDIMENSIONAL_STRESS:g} Pa): a "
                   f"nondimensional case (as the report's Example 1, K = 1); its forces and "
                   f"powers are in the case's own units")
    return out


def _family(grade: str) -> str | None:
    from hotroll.model.grades import get_grade

    return get_grade(grade).family


def _mean_stress(case) -> float | None:
    """The flow stress at the estimated mean state (middle strain, mean rate, plate
    temperature), Pa; None where the law cannot say."""
    import numpy as np

    e = pass_estimates(case)
    try:
        with np.errstate(all="ignore"):      # a law far from its data overflows: not finite
            s = float(case.material.flow_stress().sigma(sum(e["strain"]) / 2,
                                                        e["strain_rate"][0],
                                                        case.plate.temperature))
    except (ValueError, TypeError, ArithmeticError):
        return None
    return s if math.isfinite(s) else None


def solved_warnings(case, figures: dict, before: list[str]) -> list[str]:
    """``before`` (the case's warnings) with the estimated fit-range lines replaced by the
    solved pass's own figures (``figures``: variable -> (low, high), e.g. the FE's mean strain
    rate), far or not: a run reports what it computed, the range and the law."""
    found = outside(case.material.flow_stress().validity, figures)
    kept = [w for w in before if " the estimated " not in w]
    return kept + range_lines(_law_name(case), found, "solved")


def _own_roll_refusals(p) -> list[str]:
    """An asymmetric pass's lower roll faster than any mill, or a roll's own radius larger
    than any work roll, naming the key that set it."""
    out, lower = [], p.two_rolls().lower
    if lower.surface_speed > MAX_SURFACE_SPEED:
        own = p.lower.speed_key if p.lower is not None else None
        key = (f"lower.{own}" if own else "speed_ratio" if p.speed_ratio is not None
               else "roll_angular_velocity")
        out.append(f"pass.{key}: the lower roll's surface speed R omega = "
                   f"{lower.surface_speed:.4g} m/s is above {MAX_SURFACE_SPEED:g} m/s, faster "
                   f"than any flat mill")
    for name in ("upper", "lower"):
        own = getattr(p, name)
        if own is not None and own.roll_radius is not None and own.roll_radius > MAX_ROLL_RADIUS:
            out.append(f"pass.{name}.roll_radius: {own.roll_radius:g} m is above "
                       f"{MAX_ROLL_RADIUS:g} m, no work roll is that large (the lengths look "
                       f"like mm: write \"500 mm\" or 0.5)")
    return out
