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
from hotroll.fem.nonlinear import SolveStats
from hotroll.fem.penalties import PenaltyTable
from hotroll.fem.rolling_form import RollingForm
from hotroll.fem.top_boundary import TopBoundary
from hotroll.model.friction_estimate import estimate_a_f
from hotroll.model.material import NortonHoff
from hotroll.solvers import couplings as C
from hotroll.solvers.contact_end import ContactEndMixin
from hotroll.solvers.problem import Problem, Solution
from hotroll.solvers.record import solution_record
from hotroll.solvers.steady_settings import (
    SteadySettings,
    WarmStart,
    default_lengths,
    mesh_key,
)
from hotroll.solvers.steady_solve import COUPLE_BELOW_ELASTIC, SteadySolve  # noqa: F401


def top_parts(top: TopBoundary) -> np.ndarray:
    """Part of every top P2 node (vertices, then edge midpoints, as ``Q.top_nodes``): 0 free
    entry top (before the first contact vertex), 1 contact, 2 free exit top (after it: the flat
    exit and a stretch of the arc the strip has left)."""
    xv = top.X0[top.verts, 0]
    x_first = xv[top.vertex_contact].min()
    verts = np.where(top.vertex_contact, 1, np.where(xv < x_first, 0, 2))
    mids = np.where(top.edge_contact, 1, np.where(top.M0[:, 0] < x_first, 0, 2))
    return np.concatenate([verts, mids])


class SteadyRun(ContactEndMixin, SteadySolve):
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

    def solution_record(self, frame_shift: float = 0.0) -> Solution:
        """The solved pass as data, all that the results read (``solvers/record.py``)."""
        return solution_record(self, frame_shift)

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

    def _fresh_searches(self) -> None:
        """The contact end's search afresh (each solve)."""
        self.end_search = ContactEndSearch()

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
