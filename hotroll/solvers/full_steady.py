"""Direct steady state on the full-thickness strip between two rolls (issue 52, stage 3).

``SteadyRun``'s solve (Newton, the couplings inside it, the continuation in m) on the full
strip (``fem/full_strip.py``) with the form of two contacts (``fem/gap_form.py``). Each roll's
side of the strip has what the half model's top has (its ``TopBoundary`` read in the roll's own
frame, its ``StripShape``, its traced free surfaces and its contact end): the couplings move
both sides in one update; a strain-dependent flow stress carries its strain field over the
whole strip; the temperature lives on one strip mesh over the whole thickness
(``solvers/thermal_coupling.py``); a flattening roll (``roll_models``) is the half model's
``FlatteningRoll`` on its own side, updated from its own contact's tractions in its own frame.
The strip's elasticity (a Winkler layer in each contact) and each contact's end past its gap
are the half model's, per side; a strip that curls onto a roll follows it past the gap
(``full_contact_end.py``). A sweep's neighbour on the same mesh starts a case warm
(``warm_start``/``_warm``: both shapes, the wrapping sides). Not yet here: a tandem speed
(refused by ``check_supported``).
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from hotroll.fem import quantities as Q
from hotroll.fem.free_surface import ContactEndSearch, StripShape, kinematic_update
from hotroll.fem.full_strip import SUFFIX, FullStripMap, build_full_mesh
from hotroll.fem.gap_form import GapForm
from hotroll.fem.top_boundary import TopBoundary
from hotroll.model.friction import FrictionLaw
from hotroll.model.geometry import RollPass
from hotroll.model.material import NortonHoff
from hotroll.model.roll_elastic import FlatteningRoll
from hotroll.solvers import couplings as C
from hotroll.solvers.full_contact_end import FullContactEndMixin
from hotroll.solvers.gap_measure import gap_measure, strip_force
from hotroll.solvers.problem import Problem
from hotroll.solvers.steady import SteadyRun, top_parts
from hotroll.solvers.steady_settings import FullWarmStart, SteadySettings, mesh_key

SIDES = (1, -1)
#: the Newton update (over U) below which the couplings move (``SteadySettings.couple_below``,
#: 1e-2 for the half strip), tightened by 10 every ``COUPLE_ROUNDS`` rounds without settling
#: down to ``COUPLE_BELOW``: the two sides' contact ends and surfaces read each other's flow,
#: and from a flow at 1e-2 or 1e-3 U the fast roll's end on Case R at r = 1.1 moved 1e-5-1e-4
#: m a round and never settled in 30 rounds. Newton iterations on Case R at r = 1.02 / 1.1 /
#: 1.15 (asymmetric_plate): at 1e-4 throughout 25 / 80 / 64; tightened every 6 rounds 13 / 64
#: / 40 (30); every 3 rounds 20 / 37 / 23 (30); every 4 rounds r = 1.1 did not settle
COUPLE_BELOW = 1e-4
COUPLE_ROUNDS = 3


def reference_roll(rolls: dict[int, RollPass]) -> RollPass:
    """The roll whose half strip both halves of the mesh are made from: the longer contact
    (then the larger radius, the faster): chosen by the rolls, not by their sides, so that
    swapping the rolls gives the mirrored mesh."""
    return max(rolls.values(), key=lambda r: (r.contact_length, r.radius, r.u_roll))


def check_supported(problem: Problem, settings: SteadySettings) -> None:
    """Refuse what the full strip does not carry yet, naming it."""
    missing = [name for name, on in (
        ("the half model's flattening roll (Problem.roll: the full strip takes each roll's "
         "model in roll_models)", problem.roll is not None),
        ("the constrained free surface (plate.free_surface)", settings.free_surface != "traced"),
        ("the penalty contact (contact.method)", settings.contact != "multiplier"),
    ) if on]
    if missing:
        raise ValueError("the full-thickness strip (asymmetric passes) does not yet support: "
                         + "; ".join(missing))


class FullSteadyRun(FullContactEndMixin, SteadyRun):
    """The steady full strip between the rolls ``rolls`` {+1: upper, -1: lower} (each a
    ``RollPass`` in its own frame, the same axis_x and half_exit), with ``frictions`` (reduced
    laws) and a_f per roll (``a_f``: a number or None for a law without it); ``roll_models``
    {side: (kind, RollElasticity, relaxation, tie m)} of the flattening rolls
    (``GapRolls.roll_models``)."""

    def __init__(self, problem: Problem, settings: SteadySettings, plate_length: float,
                 rolls: dict[int, RollPass], frictions: dict[int, FrictionLaw],
                 a_f: dict[int, float | None] | None = None, roll_models: dict | None = None):
        import ngsolve

        t0 = time.perf_counter()
        check_supported(problem, settings)
        rolls, self.flattening = dict(rolls), {}
        for s, (kind, elasticity, relaxation, tie) in (roll_models or {}).items():
            rolls[s], self.flattening[s] = FlatteningRoll.start(rolls[s], kind, elasticity,
                                                                relaxation, tie=tie)
        # each flattening roll's start (the rigid circle), which a cold start returns to
        self._flat_start = {s: (r.shape.theta.copy(), r.shape.w.copy(), r.shape.hoop.copy())
                            for s, r in self.flattening.items()}
        self.rolls, self.frictions = rolls, frictions
        self.a_f_given = a_f or {s: None for s in SIDES}
        ref = reference_roll(rolls)
        self.problem, self.s = replace(problem, rp=ref), settings
        self.upstream, self.downstream, margin, core = settings.mesh_zone(ref, problem.h)
        self.plate_length = plate_length
        spec = replace(problem.mesh, core_factor=core)
        self.mesh = build_full_mesh(ref, self.upstream, self.downstream, spec, margin)
        mat = problem.material
        self.strain, self.thermal, consistency = problem.field_setup(self.mesh)
        self.form = GapForm(self.mesh, rolls, NortonHoff(1.0, mat.m, mat.eps0), frictions,
                            problem.h, tensions=problem.reduced_tensions,
                            consistency=consistency,
                            rate_offset=self.thermal.rate_offset()
                            if self.thermal is not None else None,
                            strip_compliance=problem.strip_compliance,
                            strip_depth=None if problem.strip_elasticity is None else
                            {s: replace(problem, rp=r).strip_layer_depth
                             for s, r in rolls.items()})
        V = self.form.fes.components[0]
        self.disp = ngsolve.GridFunction(V)
        self.d = self.disp.vec.FV().NumPy()
        n = V.ndof // 2
        self.tops = {s: TopBoundary(self.mesh, n, side=s, suffix=SUFFIX[s]) for s in SIDES}
        self.top = self.tops[1]
        if self.thermal is not None:     # one strip mesh over the whole thickness
            self.thermal.attach(self.form, self.disp, self.tops[1], lower=self.tops[-1],
                                rp=ref, breaks=[r.x_touch for r in rolls.values()],
                                rolls=list(rolls.values()))
        self.arcs = {}
        for s, top in self.tops.items():
            self.arcs[s] = top.region == "arc"
            rows = np.nonzero(self.arcs[s])[0]
            top.set_midpoints(self.d, rows, ref.project(top.midpoint_positions(self.d, rows)))
        self.d_ref = self.d.copy()
        self.x_in = ref.x_touch - self.upstream
        self.map = FullStripMap(ref, rolls, self.mesh, n, self.d_ref, self.x_in)
        self.unilateral = settings.unilateral
        self.end_searches = {s: ContactEndSearch() for s in SIDES}
        self.wraps: set[int] = set()
        self.shapes = {s: StripShape.flat(rolls[s]) for s in SIDES}
        self._set_shape()
        self.mesh_key = mesh_key(self.mesh)
        self.mass_flux = None
        self._roll_start = None
        self.mesh_time = time.perf_counter() - t0
        self.record = True

    # --- what differs from the half strip ------------------------------------------------------
    @property
    def contact_start(self) -> float:
        return min(sh.x_c for sh in self.shapes.values())

    def measure(self, stats, index: int) -> dict:
        row = {"step": index, "time": math.nan, "m": self.form.m.Get()}
        row.update(gap_measure(self, self.problem.material.K))
        if self.thermal is not None:     # the heat flows after the solves, not every update
            row.update(self.thermal.measure(self.problem.rp.axis_x, self.problem.h,
                                            heat_flows=stats.iterations > 0))
        row.update({"iterations": stats.iterations, "residual": stats.residual,
                    "solver_converged": stats.converged})
        return row

    def solution_record(self, frame_shift: float = 0.0):
        """The full strip's ``Solution`` (``solvers/record_full.py``: two ``RollContact``s)."""
        from hotroll.solvers.record_full import solution_record

        return solution_record(self, frame_shift)

    def _couple_below(self, state: dict, given: float | None) -> float:
        """The settings' threshold, tightened by 10 every ``COUPLE_ROUNDS`` rounds to
        ``COUPLE_BELOW``."""
        start = self.s.couple_below if given is None else given
        return max(COUPLE_BELOW, start * 0.1 ** (state["rounds"] // COUPLE_ROUNDS))

    def _estimate_a_f(self) -> float:
        raise ValueError("the full strip takes a_f given per roll (friction.a_f), not (3.15)")

    def warm_start(self) -> FullWarmStart:
        """This run's solved state, to start a neighbouring case on the same mesh from."""
        return FullWarmStart(self.solution, {sd: sh.copy() for sd, sh in self.shapes.items()},
                             tuple(sorted(self.wraps)), self.form.m.Get(),
                             self.problem.rp.u_roll, self.mesh_key, self.s.free_surface)

    def _warm(self, warm, vec: np.ndarray, target: float) -> None:
        """Start from a neighbour's state (``SteadyRun._warm``): its two shapes and wrapping
        sides, its velocity scaled to this reference roll speed and its (reduced) pressure by
        the Norton-Hoff rate factor; the rolls rigid and the temperature the entry's, as a
        cold start has them."""
        if not isinstance(warm, FullWarmStart) or warm.mesh_key != self.mesh_key \
                or warm.solution.shape != vec.shape:
            raise ValueError("warm start: the neighbour was not a full strip on this mesh")
        if warm.free_surface != self.s.free_surface:
            raise ValueError(f"warm start: the neighbour has {warm.free_surface!r} free tops, "
                             f"this case {self.s.free_surface!r}")
        self._reset_couplings()
        ratio = self.problem.rp.u_roll / warm.u_roll
        nv = self.form.nonlinear.n_velocity_dofs()
        pr, lr = self.form.nonlinear.pressure_range(), self.form.nonlinear.multiplier_range()
        vec[:nv] = ratio * warm.solution[:nv]
        vec[pr] = ratio**target * warm.solution[pr]
        vec[lr] = ratio * warm.solution[lr]
        self.shapes = {sd: sh.copy() for sd, sh in warm.shapes.items()}
        self.wraps = set(warm.wraps)
        self._set_shape()
        self._update_strain()

    def _couplings(self, warm: bool = False) -> list:
        s, out = self.s, []
        if self.strain is not None:
            out.append(C.StrainTransport(self.strain, self.form.nonlinear.velocity, s.strain_rtol))
        if self.thermal is not None:
            out.append(C.Temperature(self.thermal, s.thermal_rtol))
        out.append(C.FreeSurface(self.update_surface, s.surface_tol * self.problem.h))
        for side, roll in self.flattening.items():
            flat = C.RollFlattening(roll, lambda side=side: self._roll_loads(side),
                                    self._set_shape, s.roll_tol * self.rolls[side].half_exit)
            flat.name = f"roll_{'upper' if side > 0 else 'lower'}"
            # the two rolls move in the same rounds: neither waits for the other
            flat.waits_not_on = (*C.RollFlattening.waits_not_on, "roll_upper", "roll_lower")
            out.append(flat)
        if self.unilateral:
            # each side's move in units of its own tolerance (``end_tolerance``)
            end = C.ContactEnd(self.move_contact_end, 1.0)
            # every round, not after the others have come within 10 tolerances (which guards
            # against a_f (3.15)'s swings, not estimated here): asymmetric_plate's fast roll
            # leaves 6.4 mm before the gap, and its end moved every other round (50 Newton
            # iterations, 20 rounds; every round: 30, 14); Case R at r = 1.02-1.15 the same
            # to +-10 %
            end.after_others = None
            out.append(end)
        return out

    def _fresh_searches(self) -> None:
        self.end_searches = {s: ContactEndSearch() for s in SIDES}

    def _roll_loads(self, side: int) -> tuple:
        """The contact tractions on the roll on ``side`` (its own frame: angles increasing,
        pressure and shear in Pa) and its roll force per unit width (N/m; Hitchcock's circle
        takes it), as the half model's ``SteadyRun._roll_loads``."""
        K = self.problem.material.K
        prof = self.side_profile(side, K)
        order = np.argsort(prof["angle"])
        force = None
        if self.flattening[side].kind == "hitchcock":
            force = -side * strip_force(self, side, K)[1]
        return (prof["angle"][order], -prof["normal_stress"][order],
                prof["shear_stress"][order], force)

    def _reset_couplings(self) -> None:
        """What a cold and a warm start share: each flattening roll back to its rigid start
        (and waiting again), a fresh contact-end search and tilt relaxation, the entry
        temperature until the first update (the half model's), each roll's a_f."""
        for s, roll in self.flattening.items():     # each flattening roll back to its start
            roll.shape.set(*self._flat_start[s])
        for c in getattr(self, "couplings", ()):    # ... and it waits again (cold)
            if isinstance(c, C.RollFlattening):
                c.after_others = C.RollFlattening.after_others
        self.end_searches = {s: ContactEndSearch() for s in SIDES}
        self._tilt = None
        if self.thermal is not None:
            self.thermal.reset(self.problem.temperature)
        for s in SIDES:
            a_f = self.a_f_given[s]
            if a_f is None and self.frictions[s].uses_a_f:
                raise ValueError(f"the full strip needs the {'upper' if s > 0 else 'lower'} "
                                 f"roll's a_f given (friction.a_f)")
            self.form.a_f_side[s].Set(1.0 if a_f is None else a_f)

    def _cold_start(self) -> None:
        self._reset_couplings()
        self.shapes = {s: StripShape.flat(self.rolls[s]) for s in SIDES}
        self.wraps = set()           # the sides whose contact follows its roll past the gap
        self._set_shape()
        self._predict_ends()
        self._kinematic_guess()
        self._update_strain()

    def _set_contact(self) -> None:
        chi = self.form.chi.vec.FV().NumPy()
        chi[:] = 0.0
        self._top_parts = {}
        for s, top in self.tops.items():
            top.set_contact_edges(self.arcs[s])
            chi[top.edge[top.edge_contact]] = 1.0
            xy = top.vertex_positions(self.d, top.verts[top.vertex_contact])
            self.form.x_split_side[s].Set(float(np.median(xy[:, 0])))
            self._top_parts[s] = top_parts(top)

    def _set_shape(self) -> None:
        self.d[:] = self.map.displacement(self.shapes)
        self._set_contact()
        self.mesh.SetDeformation(self.disp)
        if self.form.roll_tilt is not None:       # a flattened roll's frame at the new nodes
            self.form.set_roll_shape(self.tops[1].vertex_positions(self.d,
                                                                   np.arange(self.mesh.nv)))

    def update_surface(self) -> float:
        """Both sides' free surfaces traced along the flow (``SteadyRun.update_surface``, each
        in its roll's frame from its entry height at the inlet); the larger residual (m)."""
        vel = self.form.nonlinear.gf.vec.FV().NumPy()
        residual = 0.0
        old = {s: sh.x_c for s, sh in self.shapes.items()}
        for s, top in self.tops.items():
            xy = np.vstack([top.vertex_positions(self.d), top.midpoint_positions(self.d)])
            v = np.vstack([top.vertex_values(vel), top.midpoint_values(vel)])
            order = np.argsort(xy[:, 0], kind="stable")
            self.shapes[s], r = kinematic_update(self.rolls[s], self.shapes[s], xy[order],
                                                 v[order], self._top_parts[s][order], self.x_in,
                                                 self.map.x_bounds(s))
            residual = max(residual, r)
        self._relax_tilt(old)
        self._set_shape()
        return residual

    def _relax_tilt(self, old: dict[int, float]) -> None:
        """The contact starts' difference a = (x_c,upper - x_c,lower)/2 moved by a fraction
        omega of its traced update (their mean as traced): with equal rolls the traced update
        multiplies a by -4.7 per update on Example 1 (the strip tilting into the gap, a mode
        the half model's symmetry removes), which diverges from any start. omega starts at
        0.2 (-4.7 becomes -0.14), halves whenever the update changes sign (an oscillation)
        and grows by 1.5 (to 1) while it keeps its sign."""
        a_old = 0.5 * (old[1] - old[-1])
        step = 0.5 * (self.shapes[1].x_c - self.shapes[-1].x_c) - a_old
        omega, last = getattr(self, "_tilt", None) or (0.2, 0.0)
        if step * last < 0.0:
            omega *= 0.5
        elif step * last > 0.0:
            omega = min(1.0, 1.5 * omega)
        self._tilt = (omega, step)
        a = a_old + omega * step
        mean = 0.5 * (self.shapes[1].x_c + self.shapes[-1].x_c)
        for s in SIDES:
            shift_contact_start(self.shapes[s], self.rolls[s], mean + s * a, self.x_in)

    def _kinematic_guess(self) -> None:
        """Divergence-free flow between the two surfaces: stream function q zeta, zeta =
        (y - y_b)/H, so v_x = q/H, v_y = q (y_b' + zeta H')/H (H = y_t - y_b), tangent to both;
        q at 1 % forward slip on the slower roll."""
        from ngsolve import CF, IfPos, sqrt, x, y

        heights = {}
        for s, rp in self.rolls.items():
            cx, cy = rp.centre
            R = rp.radius
            root = sqrt(IfPos(R**2 - (x - cx) ** 2, R**2 - (x - cx) ** 2, 1e-300))
            on_arc = IfPos(x - rp.x_touch, IfPos(rp.axis_x - x, 1.0, 0.0), 0.0)
            H = on_arc * (cy - root) + (1.0 - on_arc) * IfPos(x - rp.axis_x, rp.half_exit,
                                                                rp.half_entry)
            heights[s] = (H, on_arc * (x - cx) / root)
        (Hu, dHu), (Hl, dHl) = heights[1], heights[-1]
        H, dH = Hu + Hl, dHu + dHl
        zeta = (y + Hl) / H
        q = 1.01 * min(r.u_roll for r in self.rolls.values()) * 2.0 * self.rolls[1].half_exit
        self.form.nonlinear.gf.vec[:] = 0.0
        self.form.nonlinear.gf.components[0].Set(CF((q / H, q * (-dHl + zeta * dH) / H)))
        self.form.nonlinear.fix_dirichlet()

    def head_x(self) -> float:
        return self.problem.rp.axis_x + self.downstream

    def side_profile(self, side: int, K: float, columns: dict | None = None) -> dict:
        """The contact profile of one roll (``quantities.contact_profile``, in its own frame:
        y up from the strip's mid-plane towards that roll); ``columns``: more vertex fields
        (the temperature's)."""
        return Q.contact_profile(_SideView(self.form, side, self.rolls[side]), self.tops[side],
                                 self.d, K, columns)


def shift_contact_start(shape: StripShape, rp: RollPass, x_c: float, x_up: float) -> None:
    """Move ``shape``'s contact start to ``x_c``, its entry curve carried along and blended
    from ``x_up`` to end on the roll (as ``kinematic_update`` places it)."""
    dx = x_c - shape.x_c
    if dx == 0.0:
        return
    ex, ey = shape.entry_x.copy(), shape.entry_y.copy()
    ex[1:] += dx
    w = np.clip((ex - x_up) / max(x_c - x_up, 1e-300), 0.0, 1.0)
    ey += w * (float(rp.height(x_c)) - ey[-1])
    shape.entry_x, shape.entry_y, shape.x_c = ex, ey, x_c


class _SideView:
    """The form as one roll's side sees it (its pass, law and a_f): what
    ``quantities.contact_profile`` reads."""

    def __init__(self, form: GapForm, side: int, rp: RollPass):
        self._form, self.rp = form, rp
        self.law = form.laws[side]
        self.a_f = form.a_f_side[side]
        self.friction = form.laws[side]

    def __getattr__(self, name):
        return getattr(self._form, name)
