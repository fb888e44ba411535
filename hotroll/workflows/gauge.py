"""A pass given by its roll gap: the exit thickness found with the force (issue 32).

The stand springs open under the roll force: with the no-load gap S set on the stand and the
mill modulus M (N/m, the whole width's force per metre of opening), the strip leaves at the
gaugemeter thickness (Weber 1973)

    h1 = S + F(h1) / M,

F(h1) the whole width's roll force of the pass rolled to h1 (one FE solve each). The residual
g(h) = h - S - F(h)/M rises strictly with h (F falls as the draft falls), is -F(S)/M < 0 at
h = S and h0 - S > 0 at the entry thickness h0: one root in (S, h0). It is found by Newton
steps whose slope is the slab law's g' = 1 + F / (2 (h0 - h) M) (F ~ sqrt(h0 - h), Sims'
contact length) until two solves bracket the root, then by secant steps through the last
two solves (the Illinois step of the bracket where the secant leaves it), to
|g| <= ``GAUGE_RTOL`` S. Each solve starts from the last (``workflows/sweep``).
"""
from __future__ import annotations

from pathlib import Path
from typing import Callable

from hotroll.config.case import Case
from hotroll.results.outcome import exit_code
from hotroll.results.output import write_json, write_text
from hotroll.results.summary import Summary
from hotroll.results.units import UNITS
from hotroll.workflows.sweep import Sweep

#: |h1 - S - F/M| at which the exit thickness is accepted, relative to the gap S.
GAUGE_RTOL = 1e-4
#: FE solves before the search gives up (not settled, exit code 5).
GAUGE_MAX_SOLVES = 12
#: The largest trial exit thickness, as the share of the way from the gap to the entry.
_TOP = 0.98


def run_gap_case(case: Case, out: Path, run_case: Callable[..., Summary], *,
                 progress: Callable[[dict], None] | None = None, sweep=None) -> Summary:
    """Run a case with ``[pass] roll_gap``: the pass rolled to h1 = S + F(h1)/M by
    ``run_case`` (``workflows/runner.run_case``: each trial a plain pass), written to ``out``
    as a pass is (the last trial's fields), its summary with ``roll_gap``,
    ``gauge_thickness`` and ``gauge_solves``; ``out/case.toml`` is the case as given.
    ``sweep``: the ``Sweep`` the trials start from (default: a new one, each from the last)."""
    pa = case.pass_
    S, M, h0 = pa.roll_gap, pa.mill_modulus, pa.entry_thickness
    tol = GAUGE_RTOL * S
    sweep = sweep if sweep is not None else Sweep(similar=True, history=False)
    solves: list[tuple[float, float, dict]] = []        # (h, g(h), summary)

    def solve(h: float) -> float:
        trial = case.with_overrides(**{"pass.exit_thickness": h, "pass.roll_gap": None})
        s = run_case(trial, out, resume=False, progress=progress, sweep=sweep)
        if s.get("exit_code") != 0:
            raise _Stop(s)
        g = h - S - s["roll_force_total"] / M
        solves.append((h, g, s))
        return g

    def slab_step(h: float, g: float, force: float) -> float:
        slope = 1.0 + force / (2.0 * max(h0 - h, 1e-300) * M)
        return min(max(h - g / slope, S), S + _TOP * (h0 - S))

    try:
        h = min(max(pa.exit_thickness, S), S + _TOP * (h0 - S))
        g = solve(h)
        lo = hi = None                                   # (h, g) with g < 0, g > 0
        last_side = 0
        while abs(g) > tol and len(solves) < GAUGE_MAX_SOLVES:
            side = -1 if g < 0 else 1
            if side < 0:
                lo = (h, g)
            else:
                hi = (h, g)
            if lo is None or hi is None:
                h_next = slab_step(h, g, solves[-1][2]["roll_force_total"])
                if h_next == h:          # pinned at the top of the range: the root is above
                    break
            else:
                (h1, g1), (h2, g2) = solves[-2][:2], solves[-1][:2]
                h_next = h2 - g2 * (h2 - h1) / (g2 - g1)      # secant of the last two
                if not lo[0] < h_next < hi[0]:                # outside: Illinois in the bracket
                    if side == last_side:
                        if side < 0:
                            hi = (hi[0], 0.5 * hi[1])
                        else:
                            lo = (lo[0], 0.5 * lo[1])
                    (ha, ga), (hb, gb) = lo, hi
                    h_next = ha - ga * (hb - ha) / (gb - ga)
            last_side = side
            h = h_next
            g = solve(h)
    except _Stop as stop:
        return _finish(case, out, stop.summary, h, len(solves) + 1, None)
    h, g, last = solves[-1]
    failure = None
    if abs(g) > tol:
        failure = (f"the exit thickness did not settle: h1 - S - F/M = {g:.3g} m after "
                   f"{len(solves)} solves (tolerance {tol:.3g} m; at most {GAUGE_MAX_SOLVES}, "
                   f"trial exit thicknesses up to {_TOP:g} of the way from the gap to the "
                   f"entry)")
    return _finish(case, out, last, h, len(solves), failure)


class _Stop(Exception):
    def __init__(self, summary):
        self.summary = summary


def _finish(case: Case, out: Path, last, h1: float, n_solves: int,
            failure: str | None) -> Summary:
    """The last solve's summary with the gap's figures, summary.json and case.toml rewritten
    (case.toml as given: a schedule's resume compares it)."""
    d = dict(last)
    d["roll_gap"], d["gauge_solves"] = case.pass_.roll_gap, n_solves
    d["gauge_thickness"] = h1
    d["units"] = {k: u for k, u in UNITS.items() if k in d}       # as write_results does
    if failure is not None:
        d.update(converged=False, status="unsettled", failure=failure)
        d["exit_code"] = exit_code(d)
    typed = Summary.from_dict(d)
    write_json(Path(out) / "summary.json", typed.to_dict())
    write_text(Path(out) / "case.toml", case.to_toml())
    return typed
