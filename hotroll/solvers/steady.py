"""Direct steady state: the Eulerian rolling problem on the steady strip (docs/theory.md 4b, 4d).

The strip is flat at the entry thickness far upstream, follows the roll arc from the contact
start to the gap, and leaves it at the gap. On it the same form (3.6) is solved, with the same
Norton-Hoff law, friction law, penalties (Table 1) and a_f rule (3.15) as the transient scheme.

Free-surface models (``SteadySettings.free_surface``): ``"constrained"`` keeps the flat tops of
the geometric strip with the report's (3.2d) on them; ``"traced"`` makes the tops
traction-free and moves them (and the contact start) until they are streamlines of the flow,
by the kinematic update of ``fem/free_surface.py`` on a mesh mapped onto the shape.

Solve: Newton with a line search at the target m, started from a divergence-free slab flow
through the strip (the kinematic guess) with a_f (3.15) evaluated on it. Once the Newton update
is small, a_f and the free tops are updated inside the iteration until both settle; the fields
returned belong to the final a_f and shape. If the direct solve fails, it is redone along a
continuation in m from 1 (steps of at most a factor 2). The volume integral of (3.15) is taken
over a plate of the case's length: the steady window plus the rigid upstream rest at the entry
velocity, so the steady and transient a_f are the same rule on the same plate.

Where the converged contact stress turns tensile the strip would leave the roll; that stretch is
reported (``contact_loss``), not hidden.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from hotroll.fem import quantities as Q
from hotroll.fem.free_surface import ContactEndSearch, StripMap, StripShape, kinematic_update
from hotroll.fem.mesh import build_steady_mesh
from hotroll.fem.nonlinear import LinearSolveError, SolveStats, newton
from hotroll.fem.rolling_form import PenaltyTable, RollingForm
from hotroll.fem.top_boundary import TopBoundary
from hotroll.model.friction_estimate import estimate_a_f
from hotroll.model.material import NortonHoff
from hotroll.solvers import couplings as C
from hotroll.solvers.contact_end import ContactEndMixin
from hotroll.solvers.problem import Problem, Solution
from hotroll.solvers.record import solution_record
from hotroll.solvers.steady_settings import (
    SteadyResult,
    SteadySettings,
    WarmStart,
    continuation_path,
    default_lengths,
    mesh_key,
)
from hotroll.solvers.threads import solver_threads

#: with the strip's compliance, the threshold (Newton update over U) of the couplings that
#: read the contact pressure (the contact's end, the roll): the pressure in its elastic zones
#: follows dp/ds = u.n / (c_e u.t), so an error of 1e-2 U in u.n moved p by about 200 MPa over
#: one element of a finishing pass and the contact's end wandered (unsettled after 30 rounds);
#: at 1e-3 U thin_strip's force is that at 1e-4 U to 1e-6 (at 1e-2 U: 7e-4 off). The others
#: update at ``couple_below``.
COUPLE_BELOW_ELASTIC = 1e-3


def top_parts(top: TopBoundary) -> np.ndarray:
    """Part of every top P2 node (vertices, then edge midpoints, as ``Q.top_nodes``): 0 free
    entry top (before the first contact vertex), 1 contact, 2 free exit top (after it: the flat
    exit and a stretch of the arc the strip has left)."""
    xv = top.X0[top.verts, 0]
    x_first = xv[top.vertex_contact].min()
    verts = np.where(top.vertex_contact, 1, np.where(xv < x_first, 0, 2))
    mids = np.where(top.edge_contact, 1, np.where(top.M0[:, 0] < x_first, 0, 2))
    return np.concatenate([verts, mids])


class SteadyRun(ContactEndMixin):
    """The steady strip, its form and the coupled Newton solve."""

    def __init__(self, problem: Problem, settings: SteadySettings, plate_length: float):
        import ngsolve

        t0 = time.perf_counter()
        if settings.free_surface not in ("traced", "constrained"):
            raise ValueError(f"plate.free_surface must be 'traced' or 'constrained', got "
                             f"{settings.free_surface!r}")
        self.problem, self.s = problem, settings
        rp, mat = problem.rp, problem.material
        self.upstream, self.downstream, margin, core = settings.mesh_zone(rp, problem.h)
        self.plate_length = plate_length
        spec = replace(problem.mesh, core_factor=core)
        self.mesh = build_steady_mesh(rp, self.upstream, self.downstream, spec, margin=margin)
        reduced = NortonHoff(1.0, mat.m, mat.eps0)
        self.strain, self.thermal, consistency = problem.field_setup(self.mesh)
        self.form = RollingForm(self.mesh, rp, reduced, problem.friction, PenaltyTable(problem.h),
                                free_surface=settings.free_surface,
                                tensions=problem.reduced_tensions, consistency=consistency,
                                rate_offset=self.thermal.rate_offset()
                                if self.thermal is not None else None,
                                contact=settings.contact, contact_regions="arc",
                                strip_compliance=problem.strip_compliance,
                                strip_depth=problem.strip_layer_depth)
        V = self.form.fes.components[0]
        self.disp = ngsolve.GridFunction(V)
        self.d = self.disp.vec.FV().NumPy()
        self.top = TopBoundary(self.mesh, V.ndof // 2)
        if self.thermal is not None:     # the temperature's own strip mesh (solvers/thermal_coupling.py)
            self.thermal.attach(self.form, self.disp, self.top)
        # reference shape: the arc's P2 midpoints on the roll (nothing else moves: the flat
        # tops stay flat even where they pass within the contact tolerance of the roll)
        self.arc = self.top.region == "arc"
        rows = np.nonzero(self.arc)[0]
        self.top.set_midpoints(self.d, rows, rp.project(self.top.midpoint_positions(self.d, rows)))
        self.d_ref = self.d.copy()
        self.map = StripMap(rp, self.mesh, V.ndof // 2, self.d_ref, rp.x_touch - self.upstream)
        #: unilateral contact (exact contact with traced tops): the contact's end x_e is a
        #: shape unknown, where the pressure falls to zero or the gap (docs/theory.md 1e)
        self.unilateral = (self.form.exact and settings.unilateral
                           and settings.free_surface == "traced")
        self.end_search = ContactEndSearch()
        self.shape = StripShape.flat(rp)
        self._set_shape()
        self._top_part = self._top_parts()
        self.mesh_key = mesh_key(self.mesh)
        #: (target inlet flux m^2/s half model, tolerance): a tandem stand whose speed the
        #: solve finds (``TandemSpeed``), or None: the case's speed
        self.mass_flux: tuple[float, float] | None = None
        self._roll_start = None       # a flattening roll's surface at the solve's start
        self.mesh_time = time.perf_counter() - t0
        self.record = True    # measure after every solve (history.csv); off in benchmarks

    # --- the Solver interface (solvers/problem.py), shared with TransientRun ---------------------
    time_stepping = False
    window = 1           # summary scalars: the last (converged) row

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

    def solution_record(self, frame_shift: float = 0.0) -> Solution:
        """The solved pass as data, all that the results read (``solvers/record.py``)."""
        return solution_record(self, frame_shift)

    @property
    def last_stats(self) -> SolveStats:
        return self.result.stats[-1]

    @property
    def contact_start(self) -> float:
        return self.shape.x_c

    def measure(self, stats: SolveStats, index: int) -> dict:
        row = {"step": index, "time": math.nan, "m": self.form.m.Get()}
        row.update(Q.measure(self.form, self.top, self.d, self.problem.material.K, self.problem.h,
                             self.head_x()))
        if self.thermal is not None:     # the heat flows after the solves, not every update
            row.update(self.thermal.measure(self.problem.rp.axis_x, self.problem.h,
                                            heat_flows=stats.iterations > 0))
        row.update({"iterations": stats.iterations, "residual": stats.residual,
                    "solver_converged": stats.converged})
        return row

    def head_x(self) -> float:
        return self.problem.rp.axis_x + self.downstream

    @property
    def dofs(self) -> int:
        return self.form.fes.ndof

    # --- a_f rule on the plate of the case's length --------------------------------------------
    def _estimate_a_f(self) -> float:
        if self.s.a_f is not None:
            return self.s.a_f
        rp, m = self.problem.rp, self.problem.material.m
        prof = Q.contact_profile(self.form, self.top, self.d, 1.0)
        vol, back = Q.a_f_inputs(self.form)
        v_in = Q.face_flow(self.form, "in")["velocity"]
        rest = max(self.plate_length - (self.upstream + rp.contact_length), 0.0)
        vol += rest * rp.half_entry * abs(v_in) ** (m + 1.0)
        lam = abs(prof["v_slip"][0]) / rp.u_roll if len(prof["v_slip"]) else 0.0
        return estimate_a_f(vol, self.problem.h, lam, back, rp.u_roll, m, a_f_max=self.s.a_f_max)

    # --- the solve ------------------------------------------------------------------------------
    def warm_start(self) -> WarmStart:
        """This run's solved state, to start a neighbouring case from."""
        return WarmStart(self.solution, self.shape.copy(), self.form.a_f.Get(),
                         self.form.m.Get(), self.problem.rp.u_roll, self.mesh_key,
                         self.s.free_surface)

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
        self.end_search = ContactEndSearch()     # the contact end's search afresh each solve

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

    def _warm(self, warm: WarmStart, vec: np.ndarray, target: float) -> None:
        """Start from a neighbour's state: its shape and a_f, its velocity scaled to this roll
        speed and its (reduced) pressure by the Norton-Hoff rate factor (U/U_warm)^m; or from
        a similar pass on another mesh (``transfer.SimilarPass``)."""
        if hasattr(warm, "apply"):
            warm.apply(self, vec)
            a_f = self._estimate_a_f() if self.s.a_f is None else None
        else:
            if warm.mesh_key != self.mesh_key or warm.solution.shape != vec.shape:
                raise ValueError("warm start: the neighbour was solved on another mesh")
            if warm.free_surface != self.s.free_surface:
                raise ValueError(f"warm start: the neighbour has {warm.free_surface!r} free "
                                 f"tops, this case {self.s.free_surface!r}")
            ratio = self.problem.rp.u_roll / warm.u_roll
            nv = self.form.nonlinear.n_velocity_dofs()
            pr, lr = self.form.nonlinear.pressure_range(), self.form.nonlinear.multiplier_range()
            vec[:nv] = ratio * warm.solution[:nv]
            vec[pr] = ratio**target * warm.solution[pr]
            vec[lr] = ratio * warm.solution[lr]     # the multiplier is scaled to a velocity
            # a flattening roll starts rigid, not from the neighbour's surface, as a cold solve
            # does: on a heavily flattened pass (R'/R = 1.3) the two starts stopped 3.4 % apart,
            # the rigid one at a false stop of the roll / free-top iteration 4 % below the
            # pass's solution (docs/validation/speed.md, issue 34 session 4: open)
            self.shape = warm.shape.copy()
            self._set_shape()
            a_f = warm.a_f
        self.form.a_f.Set(self.s.a_f if self.s.a_f is not None else a_f)
        self._update_strain()
        # one Newton step of the heat equation, as in every coupling round after it: a full
        # solve here (3-4 steps, 96 ms a pass) gave the ten stands the same Newton iterations
        # per pass (issue 34 session 7); a fresh step, not on the factors a sweep's kept run
        # holds from its previous case (from the session's review)
        self._update_thermal(newton_steps=1, fresh=True)

    def _cold_start(self) -> None:
        """Reference strip shape, kinematic velocity guess and a_f (3.15) from it."""
        roll = self.problem.roll
        if roll is not None and self._roll_start is not None:   # a warm start's roll undone
            roll.shape.set(*self._roll_start)
        for c in getattr(self, "couplings", ()):      # ... and its roll waits again (cold)
            if isinstance(c, C.RollFlattening):
                c.after_others = C.RollFlattening.after_others
        self.shape = StripShape.flat(self.problem.rp)
        self.end_search = ContactEndSearch()
        self._set_shape()
        self._predict_end()
        self._kinematic_guess()
        self._update_strain()
        self.form.a_f.Set(self.s.a_f if self.s.a_f is not None else self._estimate_a_f())
        if self.thermal is not None:
            # the entry temperature everywhere until the first coupling update: its temperature
            # is that of a flow converged to couple_below, not of the slab guess (whose plastic
            # heat is the guess's): fewer Newton iterations on five of six passes measured
            # (docs/studies/thermal_cost.md)
            self.thermal.reset(self.problem.temperature)

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

    def _couplings(self, warm: bool = False) -> list[C.Coupling]:
        """The run's couplings in their update order (``solvers/couplings.py``): the strain, the
        temperature, a_f (3.15), the traced free tops and the contact's end, the flattening
        roll (from the first round when ``warm``: started from a solved similar pass and its
        roll), the tandem speed."""
        s, out = self.s, []
        if self.strain is not None:
            out.append(C.StrainTransport(self.strain, self.form.nonlinear.velocity, s.strain_rtol))
        if self.thermal is not None:
            out.append(C.Temperature(self.thermal, s.thermal_rtol))
        if s.a_f is None:
            out.append(C.AfEstimate(self.form.a_f, self._estimate_a_f, s.a_f_rtol))
        if s.free_surface == "traced":
            out.append(C.FreeSurface(self.update_surface, s.surface_tol * self.problem.h))
        if self.unilateral:
            tol = (C.ContactEnd.TOLERANCE_ELASTIC if self.form.compliance
                   else C.ContactEnd.TOLERANCE)
            out.append(C.ContactEnd(self.move_contact_end, tol * s.surface_tol * self.problem.h))
        if self.problem.roll is not None:
            out.append(C.RollFlattening(self.problem.roll, self._roll_loads, self._set_shape,
                                        s.roll_tol * self.problem.rp.half_exit,
                                        wait=not warm))
        if self.mass_flux is not None:
            out.append(C.TandemSpeed(lambda: Q.face_flow(self.form, "in")["flux"],
                                     self.mass_flux[0], lambda: self.problem.rp.omega,
                                     self.set_roll_speed, self.mass_flux[1]))
        return out

    def set_roll_speed(self, omega: float) -> None:
        """The same pass at the roll speed ``omega`` (rad/s): the form's speed Parameters
        (``RollingForm.set_roll_speed``), the problem's RollPass and friction law, and the
        current solution scaled to it as a neighbour's start is (velocity x U ratio, reduced
        pressure x ratio^m)."""
        pb = self.problem
        rp = replace(pb.rp, omega=float(omega))
        ratio = rp.u_roll / pb.rp.u_roll
        v_reg = (pb.friction.v_reg if pb.v_reg_per_speed is None
                 else pb.v_reg_per_speed * rp.u_roll)
        nl = self.form.nonlinear
        vec = nl.gf.vec.FV().NumPy()
        vec[:nl.n_velocity_dofs()] *= ratio
        vec[nl.pressure_range()] *= ratio**pb.material.m
        self.form.set_roll_speed(rp, v_reg)      # keeps the multiplier's pressure ...
        vec[nl.multiplier_range()] *= ratio**pb.material.m     # ... then scales it
        self.problem = replace(pb, rp=rp, friction=replace(pb.friction, v_reg=v_reg))
        if pb.roll is not None:
            pb.roll.rp = rp

    def _roll_loads(self) -> tuple:
        """The contact tractions on the roll (angles increasing; pressure and shear, Pa) and
        the roll force per unit width (N/m) of the form."""
        K = self.problem.material.K
        prof = Q.contact_profile(self.form, self.top, self.d, K)
        order = np.argsort(prof["angle"])
        # the form's roll force: Hitchcock's circle takes it; the elastic disc takes the
        # tractions alone (11 ms a roll update saved on the ten-stand schedule's passes)
        force = (-Q.force_balance(self.form, K)["roll_force_y"]
                 if self.problem.roll.kind == "hitchcock" else None)
        return (prof["angle"][order], -prof["normal_stress"][order],
                prof["shear_stress"][order], force)

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

    def _set_contact(self) -> None:
        """The contact edges: the arc's chain (mapped from x_c to x_e); the friction indicator
        and the top's parts follow."""
        self.top.set_contact_edges(self.arc)
        self.top.write_indicator(self.form.chi.vec.FV().NumPy())
        self._top_part = self._top_parts()
        # the entry's and the exit's one-sided conditions split inside the contact
        xy = self.top.vertex_positions(self.d, self.top.verts[self.top.vertex_contact])
        self.form.x_split.Set(float(np.median(xy[:, 0])))

    def _update_strain(self) -> float:
        """Transport the strain along the current flow; its largest relative change (0 when
        the flow stress does not depend on the strain)."""
        if self.strain is None:
            return 0.0
        return self.strain.transport(self.form.nonlinear.velocity)

    def _update_thermal(self, newton_steps: int = 30, fresh: bool = False) -> float:
        """The steady temperature of the current flow (``solvers/thermal_coupling.py``; in the fixed
        point one Newton step per update); its largest change over the largest temperature
        (0 for an isothermal run)."""
        if self.thermal is None:
            return 0.0
        return self.thermal.update_steady(max_iter=newton_steps, fresh=fresh)

    def _top_parts(self) -> np.ndarray:
        return top_parts(self.top)

    def update_surface(self) -> float:
        """Trace the free tops along the flow, move the contact start, remap the mesh.

        Returns the largest distance (m) between a traced top and the current one."""
        top, rp = self.top, self.problem.rp
        vel = self.form.nonlinear.gf.vec.FV().NumPy()
        xy = np.vstack([top.vertex_positions(self.d), top.midpoint_positions(self.d)])
        v = np.vstack([top.vertex_values(vel), top.midpoint_values(vel)])
        order = np.argsort(xy[:, 0], kind="stable")
        x_up = rp.x_touch - default_lengths(rp)[0]
        self.shape, residual = kinematic_update(rp, self.shape, xy[order], v[order],
                                                self._top_part[order], x_up,
                                                self.map.x_bounds())
        self._set_shape()
        return residual

    def _set_shape(self) -> None:
        """Map the mesh onto ``self.shape``; the contact is the arc's chain of edges."""
        self.d[:] = self.map.displacement(self.shape)
        self._set_contact()
        self.mesh.SetDeformation(self.disp)
        if self.form.roll_tilt is not None:       # a flattened roll's frame at the new nodes
            self.form.set_roll_shape(self.top.vertex_positions(self.d, np.arange(self.mesh.nv)))

    def _kinematic_guess(self) -> None:
        """Divergence-free slab flow through the strip: v_x = q / H(x), v_y = v_x y H'(x) / H(x)
        with H the top height (flat, arc, flat) and q the flux at 1 % forward slip; tangent
        to the top and to the symmetry line. Pressure 0."""
        from ngsolve import CF, IfPos, sqrt, x, y

        rp = self.problem.rp
        cx, cy = rp.centre
        root = sqrt(IfPos(rp.radius**2 - (x - cx) ** 2, rp.radius**2 - (x - cx) ** 2, 1e-300))
        on_arc = IfPos(x - rp.x_touch, IfPos(rp.axis_x - x, 1.0, 0.0), 0.0)
        H = on_arc * (cy - root) + (1.0 - on_arc) * IfPos(x - rp.axis_x, rp.half_exit,
                                                            rp.half_entry)
        dH = on_arc * (x - cx) / root
        # the flux at 1 % forward slip: at zero slip the exit would move at exactly U, on the
        # kink of the outlet's one-sided condition (3.2b), whose side would then be decided by
        # rounding (different at another roll speed: the scaling test caught it)
        q = 1.01 * rp.u_roll * rp.half_exit
        self.form.nonlinear.gf.vec[:] = 0.0
        self.form.nonlinear.gf.components[0].Set(CF((q / H, q * y * dH / H**2)))
        self.form.nonlinear.fix_dirichlet()     # v_y = 0 on the symmetry line exactly

    @property
    def solution(self) -> np.ndarray:
        return self.form.nonlinear.gf.vec.FV().NumPy().copy()
