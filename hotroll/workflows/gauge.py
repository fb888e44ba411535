"""A pass given by its roll gap: the exit thickness found with the force (issue 32).

The stand springs open under the roll force: with the no-load gap S set on the stand and the
mill modulus M (N/m, the whole width's force per metre of opening), the strip leaves at the
gaugemeter thickness (Weber 1973)

    h1 = S + F(h1) / M,

F(h1) the whole width's roll force of the pass rolled to h1 (one FE solve each). The residual
g(h) = h - S - F(h)/M rises strictly with h (F falls as the draft falls) and is -F(S)/M < 0 at
h = S. It is found by Newton steps whose slope is the slab law's g' = 1 + F / (2 (h0 - h) M)
(F ~ sqrt(h0 - h), Sims' contact length) until two solves bracket the root, then by secant
steps through the last two solves (the Illinois step of the bracket where the secant leaves
it), to |g| <= ``GAUGE_RTOL`` h (the exit thickness: a gap of 1 um is found as well as one of
1 mm). Each solve starts from the last (``workflows/sweep``).

An impossible gap (issue 51): at the entry thickness g(h0) = h0 - S - F(h0)/M, positive only
where the force of a vanishing draft vanishes; an elastic roll flattens under any load, and a
gap just below the entry on a soft stand leaves the stretch above the opening at every trial
up to ``_TOP`` of the way from the gap to the entry. The pass then ends with that reason,
status "failed" (exit code 3, ``results/outcome.py``); so does a trial the search chose that
cannot be set up or solved (a draft too small for the mesh, a roll flattened more than the
draft), and a trial that did not converge keeps its own exit code with the trial named.
"""
from __future__ import annotations

from pathlib import Path
from typing import Callable

from hotroll.config.case import Case, CaseError
from hotroll.results.engineering import negative_gap_warning  # noqa: F401 (re-exported)
from hotroll.results.outcome import EXIT_CODES, exit_code
from hotroll.results.output import write_json, write_text
from hotroll.results.summary import Summary
from hotroll.results.units import UNITS
from hotroll.workflows.sweep import Sweep

#: |h1 - S - F/M| at which the exit thickness is accepted, relative to the exit thickness.
GAUGE_RTOL = 1e-4
#: FE solves before the search gives up (not settled, exit code 5).
GAUGE_MAX_SOLVES = 12
#: The largest trial exit thickness, as the share of the way from the gap to the entry.
_TOP = 0.98
#: The smallest trial exit thickness, a share of the entry thickness (a gap at or below zero:
#: a preloaded stand, should a case ever give one).
_BOTTOM = 0.02


def run_gap_case(case: Case, out: Path, run_case: Callable[..., Summary], *,
                 progress: Callable[[dict], None] | None = None, sweep=None) -> Summary:
    """Run a case with ``[pass] roll_gap``: the pass rolled to h1 = S + F(h1)/M by
    ``run_case`` (``workflows/runner.run_case``: each trial a plain pass), written to ``out``
    as a pass is (the last trial's fields), its summary with ``roll_gap``,
    ``gauge_thickness`` and ``gauge_solves``; ``out/case.toml`` is the case as given.
    ``sweep``: the ``Sweep`` the trials start from (default: a new one, each from the last).
    An impossible gap, or a trial that cannot be solved, ends the pass with the reason in
    ``failure`` (module docstring)."""
    pa = case.pass_
    S, M, h0 = pa.roll_gap, pa.mill_modulus, pa.entry_thickness
    bottom, top = max(S, _BOTTOM * h0), S + _TOP * (h0 - S)
    sweep = sweep if sweep is not None else Sweep(similar=True, history=False)
    solves: list[tuple[float, float, dict]] = []        # (h, g(h), summary)

    def tol(h: float) -> float:
        return GAUGE_RTOL * h

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
        return min(max(h - g / slope, bottom), top)

    h = min(max(pa.exit_thickness, bottom), top)
    try:
        g = solve(h)
        lo = hi = None                                   # (h, g) with g < 0, g > 0
        last_side = 0
        while abs(g) > tol(h) and len(solves) < GAUGE_MAX_SOLVES:
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
        s = stop.summary
        code = s.get("exit_code")
        why = (f"{_trial(h, h0, len(solves) + 1)} ended with exit code {code} "
               f"({EXIT_CODES.get(code, '?')}"
               + (f": {s['failure']}" if s.get("failure") else "") + ")"
               + _no_root_yet(S, M, solves))
        return _finish(case, out, s, h, len(solves) + 1, why, s.get("status"))
    except (CaseError, ValueError) as e:
        if not solves:               # the case's own first guess: as a plain run would
            raise
        text = "; ".join(e.problems) if isinstance(e, CaseError) else f"{type(e).__name__}: {e}"
        why = (f"{_trial(h, h0, len(solves) + 1)} could not be "
               f"{'set up' if isinstance(e, CaseError) else 'solved'} ({text})"
               + _no_root_yet(S, M, solves))
        h_last, _, last = solves[-1]
        return _finish(case, out, last, h_last, len(solves), why, "failed")
    h, g, last = solves[-1]
    if g < -tol(h) and h >= top:
        return _finish(case, out, last, h, len(solves), _impossible(S, M, h0, h, last),
                       "failed")
    failure = None
    if abs(g) > tol(h):
        failure = (f"the exit thickness did not settle: h1 - S - F/M = {g:.3g} m after "
                   f"{len(solves)} solves (tolerance {tol(h):.3g} m; at most "
                   f"{GAUGE_MAX_SOLVES}, trial exit thicknesses up to {_TOP:g} of the way from "
                   f"the gap to the entry)")
    return _finish(case, out, last, h, len(solves), failure, "unsettled")


def _trial(h: float, h0: float, n: int) -> str:
    return (f"pass.roll_gap: the gap search's trial {n}, exit thickness {1e3 * h:.4g} mm "
            f"({100.0 * (1.0 - h / h0):.3g} % reduction),")


def _no_root_yet(S: float, M: float, solves: list) -> str:
    """Where every solve before left the stretch above the opening: the root is above the
    thickest of them, at a smaller draft, or nowhere."""
    if not solves or any(g >= 0 for _, g, _ in solves):
        return ""
    h, _, s = max(solves, key=lambda x: x[0])
    return (f"; every trial that solved left the mill stretch above the opening (at h = "
            f"{1e3 * h:.4g} mm: F/M = {1e3 * s['roll_force_total'] / M:.4g} mm > h - S = "
            f"{1e3 * (h - S):.4g} mm), so the exit thickness lies above {1e3 * h:.4g} mm, at a "
            f"smaller draft, or nowhere where the force does not vanish with the draft (an "
            f"elastic roll): a smaller gap, a stiffer mill, or a finer mesh.h_contact")


def _impossible(S: float, M: float, h0: float, h: float, s: dict) -> str:
    stretch = s["roll_force_total"] / M
    return (f"pass.roll_gap: impossible roll gap: no exit thickness between the gap and the "
            f"entry satisfies h1 = S + F/M; at the largest trial, h = {1e3 * h:.4g} mm "
            f"({100.0 * (1.0 - h / h0):.3g} % reduction, {_TOP:g} of the way from the gap to "
            f"the entry), the mill stretch F/M = {1e3 * stretch:.4g} mm still exceeds the "
            f"opening h - S = {1e3 * (h - S):.4g} mm: with a gap of S = {1e3 * S:.4g} mm on a "
            f"stand of modulus M = {M:.4g} N/m the force of even the smallest draft opens the "
            f"stand by more than the gap leaves to roll (the gap too close to the entry "
            f"thickness {1e3 * h0:.4g} mm for this stand, or the stand too soft): set a smaller "
            f"gap, or give the pass by its exit_thickness")


class _Stop(Exception):
    def __init__(self, summary):
        self.summary = summary


def _finish(case: Case, out: Path, last, h1: float, n_solves: int,
            failure: str | None, status: str | None = None) -> Summary:
    """The last solve's summary with the gap's figures, summary.json and case.toml rewritten
    (case.toml as given: a schedule's resume compares it); with a ``failure`` the run is not
    converged, its ``status`` that given and its exit code from both."""
    d = dict(last)
    d["roll_gap"], d["gauge_solves"] = case.pass_.roll_gap, n_solves
    d["gauge_thickness"] = h1
    d["units"] = {k: u for k, u in UNITS.items() if k in d}       # as write_results does
    if failure is not None:
        d.update(converged=False, failure=failure)
        if status is not None:
            d["status"] = status
        d["exit_code"] = exit_code(d)
    typed = Summary.from_dict(d)
    write_json(Path(out) / "summary.json", typed.to_dict())
    write_text(Path(out) / "case.toml", case.to_toml())
    return typed
