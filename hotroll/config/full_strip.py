"""What the full-thickness strip (``solvers/full_steady.py``, issue 52) does not carry yet: the
refusal of an asymmetric case asking for it (``asymmetric_refusal``), made before any
computation by ``workflows/build.build_model``, ``hotroll run`` and a schedule's checks
(``config/schedule.py``: each line then in that pass's terms)."""
from __future__ import annotations

from hotroll.config.case import Case, CaseError
from hotroll.config.roll_sides import SIDES


def asymmetric_refusal(case: Case) -> CaseError | None:
    """The refusal of an asymmetric pass (``RollGap.symmetric`` false) that asks for what the
    full-thickness strip (``solvers/full_steady.py``) does not carry yet, each line naming its
    key; None for a symmetric pass or one the full strip solves. Made before any computation
    (``build_model``, ``hotroll run``)."""
    gap = case.roll_gap()
    if gap.symmetric:
        return None
    lines = []
    if case.solver.method != "steady":
        lines.append(f'solver.method: an asymmetric pass needs "steady" (the report\'s scheme '
                     f'has the half model only), got "{case.solver.method}"')
    if case.plate.free_surface != "traced":
        lines.append('plate.free_surface: the full-thickness strip traces both free surfaces '
                     f'(allowed: "traced"), got "{case.plate.free_surface}"')
    if case.contact.resolved(case.solver.method) != "multiplier":
        lines.append('contact.method: the full-thickness strip has the exact contact only '
                     f'(allowed: "multiplier" or "auto"), got "{case.contact.method}"')
    if case.pass_.roll_gap is not None:
        lines.append("pass.roll_gap: the gap's search (gaugemeter) runs the half model only; "
                     "give pass.exit_thickness")
    for name, section in friction_sections(case):
        line = (f'{name}.a_f: the full-thickness strip needs each roll\'s a_f given '
                f'(m^-m, > 0), not "estimate" ((3.15) is the half model\'s)')
        if section.uses_a_f and section.a_f_rule is None and line not in lines:
            lines.append(line)     # once for a [friction] both rolls share
    if not lines:
        return None
    u, lo = gap.upper, gap.lower
    return CaseError(lines, case.name, (
        f"asymmetric pass for the full-thickness strip (the rolls differ in "
        f"{', '.join(gap.differences())}; upper: R = {1e3 * u.radius:g} mm, U = "
        f"{u.surface_speed:.6g} m/s; lower: R = {1e3 * lo.radius:g} mm, U = "
        f"{lo.surface_speed:.6g} m/s; speed ratio {gap.speed_ratio:.6g})"))


def friction_sections(case: Case) -> list:
    """(key, friction section) of each roll: ``[friction.upper]``/``[friction.lower]`` where
    given (they hold [friction]'s keys they do not change), else ``[friction]``."""
    out = []
    for name in SIDES.values():
        own = getattr(case.friction, name)
        out.append((f"friction.{name}", own) if own is not None else ("friction", case.friction))
    return out
