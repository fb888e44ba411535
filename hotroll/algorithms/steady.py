"""Direct steady state: the Eulerian rolling problem on the fixed steady strip (issue 3).

The strip is the steady shape the report's scheme converges to: flat at the entry thickness up
to the first touching point, the roll arc, flat at the roll gap after it. On it the same form
(3.6) is solved once, with the same Norton-Hoff law, friction law, penalties (Table 1) and a_f
rule (3.15) as the transient scheme; the arc is the contact Gamma_C, the flat tops are free
(v.n = 0 is what makes them streamlines of a steady flow).

Robustness: Newton with a line search along a continuation in m (1 -> the target, the report's
own m = 1 start made a path); a_f by (3.15) is updated between the continuation stages and
iterated to its fixed point at the target m. The volume integral of (3.15) is taken over a
plate of the case's length: the steady window plus the rigid upstream rest at the entry
velocity, so the steady and transient a_f are the same rule on the same plate.

Where the converged contact stress turns tensile the strip would leave the roll; that stretch is
reported (``contact_loss``), not hidden.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..discretisation.mesh import build_steady_mesh, top_height
from ..discretisation.rolling_form import PenaltyTable, RollingForm
from ..physics.friction import ViscoplasticFriction
from ..physics.friction_estimate import estimate_a_f
from ..physics.material import NortonHoff
from ..post import quantities as Q
from ..process.contact import TopBoundary
from ..process.free_surface import StripShape, top_height_function, trace_top
from .nonlinear import SolveStats, newton
from .transient import RollingModel, TransientState


@dataclass
class SteadySettings:
    tol: float = 1e-5
    max_it: int = 30                 # Newton iterations per continuation stage
    a_f: float | None = None         # None: (3.15), iterated to its fixed point
    a_f_max: float = 1e6
    a_f_start: float = 1.0
    a_f_rtol: float = 1e-2           # fixed point of the a_f rule reached at this change
    upstream: float | None = None    # flat entry length before the touching point (None: auto)
    downstream: float | None = None  # flat exit length after the roll gap (None: auto)
    contact_tol: float = 1e-5
    m_path: tuple[float, ...] = ()   # intermediate m of the continuation (() : automatic)
    stage_tol: float = 1e-2          # Newton tolerance on the intermediate stages
    fine_margin: float = 0.25        # fine mesh this many contact lengths (+4h) around the arc
    free_surface: bool = True        # free tops as streamlines (False: the flat tops fixed)
    surface_tol: float = 1e-2        # shape converged when no top node moves more than this x h
    max_outer: int = 12              # a_f / free-surface updates at the target m
    relax: float = 0.5               # under-relaxation of the free-surface update


def default_lengths(rp) -> tuple[float, float]:
    """Upstream and downstream lengths: one contact length and two full thicknesses at least,
    so that the strip is rigid at both cut faces (checked in the tests by doubling them)."""
    lc = rp.contact_length
    return max(lc, 4.0 * rp.half_entry), max(lc, 4.0 * rp.half_exit)


def continuation_path(m: float) -> list[float]:
    """Continuation 1 -> m: geometric steps of at most a factor 2 in m."""
    n = max(1, math.ceil(math.log(1.0 / m) / math.log(2.0)))
    return [float(v) for v in np.geomspace(1.0, m, n + 1)[1:]] if m < 1.0 else [m]


@dataclass
class SteadyResult:
    stats: list = field(default_factory=list)   # SolveStats per solve
    rows: list = field(default_factory=list)    # measured figures after each solve
    surface_moves: list = field(default_factory=list)   # largest top-node move per update, m
    a_f_history: list = field(default_factory=list)
    wall_time: float = 0.0
    mesh_time: float = 0.0

    @property
    def iterations(self) -> int:
        return sum(s.iterations for s in self.stats)

    @property
    def converged(self) -> bool:
        return bool(self.stats) and self.stats[-1].converged


class SteadyRun:
    """The steady strip, its form and the continuation Newton solve."""

    def __init__(self, model: RollingModel, settings: SteadySettings, plate_length: float):
        import ngsolve

        t0 = time.perf_counter()
        self.model, self.s = model, settings
        rp, mat = model.rp, model.material
        up, down = default_lengths(rp)
        self.upstream = settings.upstream or up
        self.downstream = settings.downstream or down
        self.plate_length = plate_length
        self.mesh = build_steady_mesh(rp, self.upstream, self.downstream, model.mesh,
                                      margin=settings.fine_margin * rp.contact_length
                                      + 4 * model.h)
        reduced = NortonHoff(1.0, mat.m, mat.eps0)
        friction = ViscoplasticFriction(1.0, mat.m, model.v_reg)
        self.form = RollingForm(self.mesh, rp, reduced, friction, PenaltyTable(model.h))
        V = self.form.fes.components[0]
        self.disp = ngsolve.GridFunction(V)
        self.d = self.disp.vec.FV().NumPy()
        self.top = TopBoundary(self.mesh, V.ndof // 2)
        # the arc is the contact; projection puts the P2 midpoints exactly on the roll
        self.top.detect(rp, self.d, settings.contact_tol, project_contact=True)
        self.top.write_indicator(self.form.chi.vec.FV().NumPy())
        self.mesh.SetDeformation(self.disp)
        self.d_ref = self.d.copy()
        self.shape = StripShape(self.mesh, V.ndof // 2)
        self.contact_start = rp.x_touch
        self.mesh_time = time.perf_counter() - t0
        self.record = True    # measure after every solve (history.csv); off in benchmarks

    # --- the interface the runner shares with TransientRun -------------------------------------
    window = 1           # summary scalars: the last (converged) row

    def run(self, progress=None, warm: np.ndarray | None = None,
            warm_a_f: float | None = None) -> TransientState:
        """Solve, record one history row per Newton solve (its m, a_f and figures)."""
        self.result = self.solve(warm, warm_a_f, progress)
        last = self.result.stats[-1]
        self.state = TransientState(step=len(self.result.stats) - 1, time=math.nan,
                                    history=self.result.rows,
                                    status="steady" if last.converged else "failed")
        return self.state

    @property
    def last_stats(self) -> SolveStats:
        return self.result.stats[-1]

    def measure(self, stats: SolveStats, index: int) -> dict:
        row = {"step": index, "time": math.nan, "m": self.form.m.Get()}
        row.update(Q.measure(self.form, self.top, self.d, self.model.material.K, self.model.h,
                             self.head_x()))
        row.update({"iterations": stats.iterations, "residual": stats.residual,
                    "solver_converged": stats.converged})
        return row

    def head_x(self) -> float:
        return self.model.rp.axis_x + self.downstream

    @property
    def dofs(self) -> int:
        return self.form.fes.ndof

    # --- a_f rule on the plate of the case's length --------------------------------------------
    def _estimate_a_f(self) -> float:
        if self.s.a_f is not None:
            return self.s.a_f
        rp, m = self.model.rp, self.model.material.m
        prof = Q.contact_profile(self.form, self.top, self.d, 1.0)
        vol, back = Q.a_f_inputs(self.form)
        v_in = Q.face_flow(self.form, "in")["velocity"]
        rest = max(self.plate_length - (self.upstream + rp.contact_length), 0.0)
        vol += rest * rp.half_entry * abs(v_in) ** (m + 1.0)
        lam = abs(prof["v_slip"][0]) / rp.u_roll if len(prof["v_slip"]) else 0.0
        return estimate_a_f(vol, self.model.h, lam, back, rp.u_roll, m, a_f_max=self.s.a_f_max)

    # --- the solve ------------------------------------------------------------------------------
    def solve(self, warm: np.ndarray | None = None, warm_a_f: float | None = None,
              progress=None) -> SteadyResult:
        """Continuation Newton from m = 1 (cold) or from ``warm`` (a neighbour's solution)."""
        from ngsolve import TaskManager

        f, s, res = self.form, self.s, SteadyResult(mesh_time=self.mesh_time)

        def newton_solve(tol):
            st = newton(f.problem, tol, s.max_it)
            res.stats.append(st)
            if self.record:
                res.rows.append(self.measure(st, len(res.stats) - 1))
                if progress:
                    progress(res.rows[-1])
            return st

        target = self.model.material.m
        t0 = time.perf_counter()
        vec = f.problem.gf.vec.FV().NumPy()
        with TaskManager():
            if warm is not None and warm.shape == vec.shape:
                vec[:] = warm
                f.a_f.Set(s.a_f if s.a_f is not None else (warm_a_f or s.a_f_start))
                path = [target]
            else:
                self._initial_guess()
                f.a_f.Set(s.a_f if s.a_f is not None else s.a_f_start)
                path = [1.0] + (list(s.m_path) or continuation_path(target))
            for i, m in enumerate(path):
                f.m.Set(m)
                final = i == len(path) - 1
                tol = s.stage_tol
                for _ in range(s.max_outer if final else 1):
                    newton_solve(tol)
                    change = self._update_coupled(res)
                    if final and change <= 1.0 and tol == s.tol:
                        break
                    # loose solves while a_f and the surface still move, the last ones to tol
                    tol = s.tol if change <= 10.0 else s.stage_tol
            # the fields must belong to the final a_f, shape and contact set: solve once more
            newton_solve(s.tol)
        res.wall_time = time.perf_counter() - t0 + self.mesh_time
        return res

    def _update_coupled(self, res: SteadyResult) -> float:
        """Update a_f (3.15) and the free surface; return the change in units of tolerance."""
        s, f, change = self.s, self.form, 0.0
        if s.a_f is None:
            a_old, a_new = f.a_f.Get(), self._estimate_a_f()
            res.a_f_history.append(a_new)
            f.a_f.Set(a_new)
            change = abs(a_new - a_old) / (s.a_f_rtol * a_new)
        if s.free_surface:
            contact = self.top.edge_contact.copy()
            moved = self.update_surface()
            res.surface_moves.append(moved)
            change = max(change, moved / (s.surface_tol * self.model.h))
            if not np.array_equal(contact, self.top.edge_contact):
                change = max(change, 2.0)   # a contact edge came or went: not converged yet
        return change

    def update_surface(self) -> float:
        """Re-trace the free tops as streamlines, move the mesh, re-detect the contact (3.9).

        Returns the largest vertical move of a top node (m).
        """
        rp = self.model.rp
        tp = Q.top_profile(self.form, self.top, self.d)
        # the strip is flat and rigid more than the default entry length ahead of the bite;
        # tracing from there keeps the result independent of a longer entry
        y_new = tp["y"].copy()
        k = tp["x"] >= rp.x_touch - default_lengths(rp)[0]
        y_new[~k] = rp.half_entry
        y_new[k], start = trace_top(rp, tp["x"][k], tp["v1"][k], tp["v2"][k], rp.half_entry,
                                    rp.axis_x)
        self.contact_start = start
        y_new = tp["y"] + self.s.relax * (y_new - tp["y"])
        moved = float(np.max(np.abs(y_new - tp["y"])))
        height = top_height_function(tp["x"], y_new)
        self.d[:] = self.shape.scale(self.d_ref, lambda x: top_height(rp, x), height)
        self.top.detect(rp, self.d, self.s.contact_tol, project_contact=True)
        self.top.write_indicator(self.form.chi.vec.FV().NumPy())
        self.mesh.SetDeformation(self.disp)
        return moved

    def _initial_guess(self) -> None:
        """u = (U_roll, 0), p = 0: no one-sided penalty is active at the start."""
        from ngsolve import CF

        self.form.problem.gf.vec[:] = 0.0
        self.form.problem.gf.components[0].Set(CF((self.model.rp.u_roll, 0.0)))

    @property
    def solution(self) -> np.ndarray:
        return self.form.problem.gf.vec.FV().NumPy().copy()
