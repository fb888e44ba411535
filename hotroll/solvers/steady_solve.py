"""The steady solve's loop (docs/theory.md 4b): Newton at the target m from the kinematic guess
or a neighbour's state, the couplings (a_f (3.15), the traced surfaces, the contact's end, the
fields, the roll) updated inside it until they settle, the continuation in m if the direct
solve fails, one history row per Newton solve and coupling update.

``SteadySolve`` is a mixin of the strips it drives: the half strip (``solvers/steady.py:
SteadyRun``) and the full strip between two rolls (``solvers/full_steady.py``). It reads the
strip only through ``solvers/discretisation.py: StripDiscretisation`` (a test checks it), so a
new discretisation (a 3D strip) implements those hooks and inherits this loop.
"""
from __future__ import annotations

import math
import time

from hotroll.fem.nonlinear import LinearSolveError, SolveStats, newton
from hotroll.model.solution import Solution
from hotroll.solvers.steady_settings import SteadyResult, WarmStart, continuation_path
from hotroll.solvers.threads import solver_threads

#: with the strip's compliance, the threshold (Newton update over U) of the couplings that
#: read the contact pressure (the contact's end, the roll): the pressure in its elastic zones
#: follows dp/ds = u.n / (c_e u.t), so an error of 1e-2 U in u.n moved p by about 200 MPa over
#: one element of a finishing pass and the contact's end wandered (unsettled after 30 rounds);
#: at 1e-3 U thin_strip's force is that at 1e-4 U to 1e-6 (at 1e-2 U: 7e-4 off). The others
#: update at ``couple_below``.
COUPLE_BELOW_ELASTIC = 1e-3


class SteadySolve:
    """The loop of the steady solve over a strip (``StripDiscretisation``)."""

    def run(self, progress=None, warm: WarmStart | None = None) -> Solution:
        """Solve, record one history row per Newton solve (its m, a_f and figures)."""
        self.result = self.solve(warm, progress)
        r = self.result
        status = ("steady" if r.converged else
                  "unsettled" if r.stats[-1].converged else "failed")
        if not r.rows:     # benchmarks switch recording off: keep one row for the summary
            r.rows.append(self.measure(r.stats[-1], 0))
        self.state = Solution(step=len(r.rows) - 1, time=math.nan, history=r.rows,
                                    status=status,
                                    failure=r.failure if status == "failed" else "")
        return self.state

    @property
    def last_stats(self) -> SolveStats:
        return self.result.stats[-1]

    def solve(self, warm: WarmStart | None = None, progress=None) -> SteadyResult:
        """Newton at the target m from the kinematic guess (cold) or from ``warm`` (a neighbour's
        solution on the same mesh), with a_f (3.15) and the free surface updated inside the
        iteration."""
        s, res = self.s, SteadyResult(mesh_time=self.mesh_time)
        # built for this solve: a run kept by a sweep gets each case's settings (a_f given or
        # estimated, the free-surface model) before it solves
        # a similar pass's start carries its roll (``transfer.SimilarPass``); a neighbour's on
        # the same mesh (a sweep's ``WarmStart``) starts from a fresh roll
        self.couplings = self._couplings(warm=hasattr(warm, "apply"))
        self._fresh_searches()     # the contact end's search afresh each solve

        def record(st, coupling: dict | None = None):
            """One history row (a Newton solve, or a coupling update: ``coupling``) and its
            progress report: Newton iterations and coupling updates, not time steps."""
            if self.record:
                res.rows.append(self.measure(st, len(res.rows)))
            if progress:
                progress(self._progress(st, coupling, res))

        target = self.problem.material.m
        t0 = time.perf_counter()
        roll = self.problem.roll
        self._roll_start = ((roll.shape.theta, roll.shape.w, roll.shape.hoop)
                            if roll is not None else None)
        vec = self.form.nonlinear.gf.vec.FV().NumPy()
        with solver_threads():
            if warm is not None:
                self._warm(warm, vec, target)
                try:
                    self._follow([target], res, record, s.couple_below_warm)
                except LinearSolveError:
                    res.stats.append(SolveStats())
                # a neighbour too far off (or a broken state), or a fixed point that did not
                # settle from it: start again from cold (a study's Example 1 pass warm-started
                # from another reduction swung a_f (3.15) by 2x for 30 updates; cold: 8)
                res.warm_failed = not (res.stats[-1].converged and res.settled)
            if warm is None or res.warm_failed:
                self._cold_start()
                path = list(s.m_path) or [target]
                self._follow_or_fail(path, res, record)
                if not res.stats[-1].converged and len(path) == 1 and target < 1.0:
                    # the direct solve failed: afresh along a continuation in m
                    res.fallback = True
                    self._cold_start()
                    self._follow_or_fail([1.0] + continuation_path(target), res, record)
        res.wall_time = time.perf_counter() - t0 + self.mesh_time
        return res

    def _follow_or_fail(self, path: list[float], res: SteadyResult, record) -> None:
        """``_follow``; a linear solve that fails ends the path as an unconverged solve, its
        reason in ``res.failure`` (the run's ``failure`` if nothing converges after it: m = 0.02
        at 15 m/s with Tresca's factor 1 raised LinearSolveError out of the runner, issue 18)."""
        try:
            self._follow(path, res, record)
        except LinearSolveError as e:
            res.stats.append(SolveStats())
            res.failure = f"m = {self.form.m.Get():.4g}: {e}"

    def _follow(self, path: list[float], res: SteadyResult, record,
                couple_below: float | None = None) -> None:
        """Loose Newton solves at the intermediate m of ``path``, then the coupled Newton at the
        last: a_f and the surface updated inside it until they settle (or ``max_outer``), from
        the first Newton update below ``couple_below`` (default: the settings')."""
        f, s = self.form, self.s
        for m in path[:-1]:
            f.m.Set(m)
            st = newton(f.nonlinear, s.stage_tol, s.max_it)
            res.stats.append(st)
            self._update_coupled(res)
            record(st)
        f.m.Set(path[-1])
        state = {"settled": False, "updates": 0, "rounds": 0}

        def couple(update: float) -> bool:
            """One a_f / surface update; False once settled (or at the cap): freeze."""
            if state["settled"] or state["updates"] >= s.max_outer:
                return False
            # a round on a flow not yet tight enough for the pressure's readers (the strip's
            # compliance: COUPLE_BELOW_ELASTIC) is a Newton step with the others' updates, not
            # one of the max_outer rounds
            if not (self.form.compliance and update > COUPLE_BELOW_ELASTIC):
                state["updates"] += 1
            change = self._update_coupled(res, update)
            state["settled"] = change <= 1.0
            state["rounds"] += 1
            if f.friction_dual is not None:      # the form's data moved (fem/primal_dual.py)
                f.friction_dual.restart()
            record(SolveStats(iterations=0, converged=False),
                   {"round": state["rounds"], "newton_update": update, "change": change,
                    "changes": dict(self.last_changes), "settled": state["settled"]})
            return True

        coupled = any(c.in_fixed_point for c in self.couplings)
        st = newton(f.nonlinear, s.tol, s.max_it + 3 * s.max_outer,
                    couple=couple if coupled else None,
                    couple_below=lambda: self._couple_below(state, couple_below),
                    full_step=True)
        res.stats.append(st)
        res.settled = state["settled"] or not coupled
        record(st)

    def _couple_below(self, state: dict, given: float | None) -> float:
        """The Newton update (over U) below which the couplings move now: ``given`` or the
        settings' (``state``: the fixed point's rounds so far, for a solver that tightens it)."""
        return self.s.couple_below if given is None else given

    def _update_coupled(self, res: SteadyResult, update: float = 0.0) -> float:
        """One update of every coupling on a flow whose last Newton update was ``update`` (over
        U); the largest change in units of its tolerance. A coupling with ``after_others``
        waits (its change counts as infinite) until the others before it have changed by at
        most that many tolerances; one that reads the contact pressure (``reads_pressure``)
        waits, with the strip's compliance, for a flow converged to ``COUPLE_BELOW_ELASTIC``."""
        changes: dict[str, float] = {}
        tight = self.form.compliance and update > COUPLE_BELOW_ELASTIC
        for c in self.couplings:
            wait = getattr(c, "after_others", None)
            before = [v for k, v in changes.items() if k not in c.waits_not_on]
            if (wait is not None and max(before, default=0.0) > wait) or (
                    tight and c.reads_pressure):
                changes[c.name] = math.inf
                continue
            changes[c.name] = c.update(res)
        self.last_changes = changes      # each coupling's change, for the progress report
        return max(changes.values(), default=0.0)

    def _progress(self, st: SolveStats, coupling: dict | None, res: SteadyResult) -> dict:
        """The progress report of one history row: a Newton solve (its iterations, residual
        and last update; the roll force of the solution) or a coupling update (the Newton
        update it came at, each coupling's change in units of its tolerance), in ``message``
        and as figures. A steady solve has no time steps: no ``step`` or ``time``."""
        if coupling is None:
            n, m = len(res.stats), self.form.m.Get()
            info = {"stage": "newton", "newton_solve": n, "newton_iterations": st.iterations,
                    "newton_residual": st.residual, "newton_update": st.update,
                    "newton_converged": st.converged, "rate_exponent": m}
            force = res.rows[-1].get("roll_force") if self.record and res.rows else None
            info["message"] = (
                f"Newton solve {n} at m = {m:.4g}: "
                f"{'converged' if st.converged else 'NOT converged'} after {st.iterations} "
                f"iterations, residual norm {st.residual:.3g}, last update {st.update:.3g} of "
                f"the roll speed" + (f"; roll force {force:.6g} N/m" if force is not None
                                     and math.isfinite(force) else ""))
            return info
        parts = ", ".join(f"{k} {v:.3g}" if math.isfinite(v) else f"{k} waiting"
                          for k, v in coupling["changes"].items())
        return {"stage": "coupling", "coupling_update": coupling["round"],
                "newton_update": coupling["newton_update"],
                "coupling_change": coupling["change"], "coupling_settled": coupling["settled"],
                "message": (f"coupling update {coupling['round']} at a Newton update of "
                            f"{coupling['newton_update']:.3g} of the roll speed: changes in "
                            f"units of their tolerances: {parts or 'none'}; "
                            + ("settled" if coupling["settled"] else "not settled"))}
