"""A schedule pass's own rolls (issue 52): an asymmetric pass is written as a case writes it,
per pass (``speed_ratio``, ``[pass.upper]``/``[pass.lower]`` after its ``[[pass]]``, its own
``[pass.friction]`` with ``upper``/``lower`` tables), and solved on the full-thickness strip.
``pass_rolls`` gives the case's [pass] keys; ``asymmetric_problems`` refuses, before any
computation and naming ``pass[k]`` and the key, what that strip does not carry yet
(``config/full_strip.asymmetric_refusal``, in the schedule's terms) and what a schedule asks of
a pass that the full strip cannot give: a tandem's stand speed or tension from the mass flux
(the full strip takes its rolls' speeds as given, and its flux is the whole thickness's, the
half model's the half's) and an isothermal pass's streamline histories for the
microstructure."""
from __future__ import annotations

from hotroll.config.full_strip import asymmetric_refusal
from hotroll.config.roll_sides import SIDES


def pass_rolls(p) -> dict:
    """The case's [pass] keys of the schedule pass ``p``'s own rolls (those it gives)."""
    d = {} if p.speed_ratio is None else {"speed_ratio": p.speed_ratio}
    for name in SIDES.values():
        own = getattr(p, name)
        if own is not None:
            d[name] = own.model_dump(exclude_none=True)
    return d


def asymmetric_problems(sch, k: int, case) -> list[str]:
    """The problems of the k-th pass (from 0) of the schedule ``sch``, as the case ``case``,
    when its rolls differ (none for a symmetric pass), each naming ``pass[k+1]`` and its key."""
    gap = case.roll_gap()
    if gap.symmetric:
        return []
    p, where = sch.passes[k], f"pass[{k + 1}]"
    what = f"{where} (asymmetric: the rolls differ in {', '.join(gap.differences())})"
    out = []
    if sch.mill.speeds == "mass_flow":
        out.append(f'mill.speeds: "mass_flow" cannot set {what}: the full-thickness strip does '
                   f'not search a stand speed for a mass flux (it takes both rolls\' speeds as '
                   f'given); allowed with an asymmetric pass: "given"')
    if sch.mill.tensions == "from_speeds":
        out.append(f'mill.tensions: "from_speeds" cannot take {what}: the full-thickness '
                   f'strip\'s flux is not comparable with its neighbours\' and no tension is '
                   f'searched for it; allowed with an asymmetric pass: "given"')
    if sch.microstructure.kinetics is not None and case.thermal is None:
        out.append(f"{where}.isothermal: {what} with microstructure.kinetics needs its "
                   f"streamlines' histories, which only a pass with its temperature writes; "
                   f"set isothermal = false, got true")
    refusal = asymmetric_refusal(case)
    for line in refusal.problems if refusal is not None else []:
        line = _in_schedule(line, where, what, p)
        out += [line] if line not in out else []
    return out


def _in_schedule(line: str, where: str, what: str, p) -> str:
    """A line of ``asymmetric_refusal`` in the schedule's keys."""
    key, _, why = line.partition(": ")
    if key.startswith("pass."):
        return f"{where}.{key[len('pass.'):]}: {why}"
    if key.startswith("friction") and p.friction is not None:
        return f"{where}.{key}: {why} ({what})"
    return f"{key}: {why} ({what})"
