"""The one Newton (and Picard) of hotroll: the flow (3.6) and the heat equation both solve with
it. Picard (3.8) and Newton with a line search.

A system is what ``newton`` needs to know (``NonlinearSystem``): the unknown ``gf``, the form
whose ``Apply`` is the residual and whose linearisation is the Jacobian (``a_newton``, or a
separate ``a_jacobian``), the free DOFs, the direct solvers to try and the factorisations kept
between calls, the size of an update (the flow: the largest velocity update at a velocity node
over ``velocity_scale``, the report's ||U^i - U^{i+1}|| <= 1e-5 of (3.8c) made unit-free; the
heat: the largest temperature change over the largest temperature) and, optionally, a
``prepare(iteration)`` hook (the heat equation's SUPG parameter frozen at the iterate). The flow
is ``fem/forms.py: NonlinearProblem``, the heat ``fem/thermal_field.py: HeatSystem``.
Newton stops when the update is below ``tol``, or after ``max_it`` iterations.

Each Newton direction du solves J du = r to a relative residual eta, ||J du - r|| <= eta ||r||
in the residual's norm (``_Workspace.norm``; ``_accurate`` tests it): an inexact Newton method
(Dembo, Eisenstat & Steihaug 1982). The forcing term eta is the system's ``linear_rtol`` (the
flow's 1e-2, ``forms.NonlinearProblem``) or the last direction's size (its largest nodal
update over the velocity scale) where that is smaller, down to ``FORCING_FLOOR``: eta = O(|du|)
keeps Newton's local convergence superlinear (order about 1.6), and a direction small enough to
end the solve is solved again to its own size before it is accepted (a solve's first direction
is solved to linear_rtol), so the accepted last step is as accurate as before; where the
residual the solve reached is already below that size (a direct solver's: rounding), it is not
solved again (the same direction: UMFPACK's factors of the same matrix; issue 50 saved a
refactorisation per solve that way).
GMRES (``fem/krylov.py``) stops on the same residual in the same norm, so where it stops does
not depend on the roll speed or the units (the exact scalings hold). Measured on the ten
stands: the same Newton steps on every pass, GMRES's iterations about halved (issue 34 session
10, docs/validation/speed.md). A direct solver's solution is exact to rounding either way.
With ``reuse_steps`` (the large 3D meshes', ``solvers/spread_3d.REUSE_STEPS``) a direction is
first sought by GMRES on the new Jacobian preconditioned by the kept factors of an earlier one
(``krylov.gmres``, given up once its residual falls behind the geometric path to the forcing
term in that many iterations), the same accuracy test deciding; only where that fails are the
factors refactorised (the roughing pass: a refactorisation 12.7 s, a solve with the factors
0.65 s).
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable, Protocol

import numpy as np

from hotroll.fem.amg import make_inverse
from hotroll.fem.forms import NonlinearProblem
from hotroll.fem.krylov import apply_inverse, gmres
from hotroll.fem.reproducible import parallel


class NonlinearSystem(Protocol):
    """What ``newton`` and ``picard`` read (``NonlinearProblem`` is one)."""

    gf: object                      # the unknown (an NGSolve GridFunction)
    a_newton: object                # Apply = the residual; AssembleLinearization = Jacobian
    a_jacobian: object              # the Jacobian as a form of its own, or None
    inverses: dict                  # kept factorisations, by id of the form they factorise
    linear_solvers: tuple           # the direct solvers to try, in this order
    pressure_row_scale: float       # weight of the pressure rows in the residual's norm
    multiplier_tol: float           # a contact multiplier's own stopping test
    linear_rtol: float              # the largest forcing term (module docstring)

    @property
    def freedofs(self): ...
    @property
    def free_mask(self) -> np.ndarray: ...
    @property
    def velocity_scale(self) -> float: ...           # what an update is measured against
    def max_nodal_velocity(self, vec) -> float: ...  # the size of an update
    def max_multiplier(self, vec) -> float: ...
    def pressure_range(self) -> slice: ...

#: a callable (system, iteration, update, step length, residual before, after) called after
#: every Newton step, or None (studies of the iteration count: scripts/newton_trace.py)
TRACE = None

#: ``newton(full_step=True)``: below this update (x the velocity scale) a failed line search
#: takes the full step once (``newton``)
WATCHDOG_BELOW = 1e-2

#: Newton steps a contact multiplier may take after the velocity has converged (``newton``).
MULTIPLIER_EXTRA = 5

#: the smallest forcing term Newton asks for: the accuracy test every direction had to pass
#: before the inexact Newton (issue 34 session 10)
FORCING_FLOOR = 1e-6

#: GMRES's own stopping residual against the accuracy test's: its estimate of the residual
#: (the Hessenberg system's) is the true one up to rounding, a factor 10 is the margin
GMRES_MARGIN = 0.1


@dataclass
class SolveStats:
    iterations: int = 0
    converged: bool = False
    update: float = float("inf")     # last max |du| / velocity_scale
    residual: float = float("nan")   # last residual norm (free dofs)
    time_assembly: float = 0.0
    time_linear: float = 0.0
    multiplier_update: float = 0.0   # last max |d lambda| / velocity_scale (contact multiplier)
    factorisations: int = 0          # direct solvers' (re)factorisations
    reused: int = 0                  # directions solved on an earlier Jacobian's factors


class _Workspace:
    """Vectors and masks reused across iterations of one problem."""

    def __init__(self, problem: NonlinearProblem):
        self.r = problem.gf.vec.CreateVector()
        self.du = problem.gf.vec.CreateVector()
        self.backup = problem.gf.vec.CreateVector()
        self.check = problem.gf.vec.CreateVector()
        self.problem = problem
        #: the last direction's relative residual ||J du - r|| / ||r|| (``_accurate``; inf
        #: where it was not measured)
        self.achieved = float("inf")

    @property
    def free(self):
        """The free DOFs now (an active set of contact multipliers may change them)."""
        return self.problem.free_mask

    def norm(self, vec) -> float:
        """||r|| over the free DOFs, the pressure rows (int q div u: a velocity gradient) times
        ``problem.pressure_row_scale`` (a viscosity: then every row is a stress and the line
        search makes the same choices at any roll speed or unit of time)."""
        a = vec.FV().NumPy()
        w = self.problem.pressure_row_scale
        if w == 1.0:
            return float(np.linalg.norm(a[self.free]))
        pr = self.problem.pressure_range()
        rest = np.concatenate([a[: pr.start][self.free[: pr.start]],
                               a[pr.stop:][self.free[pr.stop:]]])
        return float(np.hypot(np.linalg.norm(rest), w * np.linalg.norm(a[pr][self.free[pr]])))

    def max_velocity(self, vec) -> float:
        return self.problem.max_nodal_velocity(vec)

    def weights(self) -> np.ndarray:
        """The rows' weights of ``norm`` (1, the pressure rows ``pressure_row_scale``), for
        GMRES's norm (``fem/krylov.py``)."""
        w = np.ones(len(self.r))
        scale = self.problem.pressure_row_scale
        if scale != 1.0:
            w[self.problem.pressure_range()] = scale
        return w


class LinearSolveError(RuntimeError):
    """No direct solver produced an accurate solution of the (Picard or Newton) system."""


def _linear_step(form, problem, ws, stats, residual_ready: bool = False,
                 jacobian=None, chord: bool = False, rtol: float | None = None) -> None:
    """Assemble the (Picard or Newton) matrix at gf and compute du = J^{-1} r.

    ``r`` is evaluated by ``form`` unless the caller left the residual at gf in ``ws.r``. The
    matrix is ``form``'s linearisation at gf, or ``jacobian`` (a form linear in the trial
    functions, coefficients at gf) assembled as it stands. ``chord``: the kept factorisation of
    the same form as it is, nothing assembled (Newton-chord), where there is one. ``rtol``:
    the direction's relative residual, the forcing term (default the system's ``linear_rtol``).
    """
    t0 = time.perf_counter()
    ws.achieved = float("inf")
    if not residual_ready:
        with parallel():
            form.Apply(problem.gf.vec, ws.r)
    kept = problem.inverses.get(id(jacobian if jacobian is not None else form))
    rtol = problem.linear_rtol if rtol is None else rtol
    if chord and kept is not None:
        apply_inverse(kept, ws.r, ws.du, GMRES_MARGIN * rtol, ws.weights())
        stats.time_linear += time.perf_counter() - t0
        return
    with parallel():
        if jacobian is None:
            form.AssembleLinearization(problem.gf.vec)
            jacobian = form
        else:
            jacobian.Assemble()
    t1 = time.perf_counter()
    rnorm = max(ws.norm(ws.r), 1e-300)
    cached = problem.inverses.get(id(jacobian))
    reuse = getattr(problem, "reuse_steps", 0)
    if (cached is not None and reuse > 0 and not getattr(cached, "iterative", False)
            and _reuse_and_solve(cached, jacobian, problem, ws, rnorm, rtol, reuse)):
        stats.reused += 1
    elif not (cached is not None and _update_and_solve(cached, jacobian, ws, rnorm, rtol,
                                                       stats)):
        for name in problem.linear_solvers:
            try:
                stats.factorisations += 1
                inv = make_inverse(jacobian.mat, problem.freedofs, name,
                                   getattr(problem, "layout", None))
            except Exception:  # noqa: BLE001 - NGSolve raises plain exceptions (zero pivot, no MKL)
                continue
            if _accurate(inv, jacobian, ws, rnorm, rtol):
                problem.inverses[id(jacobian)] = inv
                break
        else:
            raise LinearSolveError(f"no direct solver in {problem.linear_solvers} solved the system "
                                   f"to {rtol:g} relative residual")
    stats.time_assembly += t1 - t0
    stats.time_linear += time.perf_counter() - t1


def _accurate(inv, form, ws, rnorm: float, rtol: float) -> bool:
    """du = inv r, accepted if ``_reached``."""
    apply_inverse(inv, ws.r, ws.du, GMRES_MARGIN * rtol, ws.weights())
    return _reached(form, ws, rnorm, rtol)


def _reached(form, ws, rnorm: float, rtol: float) -> bool:
    """||A du - r|| <= rtol ||r|| (``ws.norm``, the free DOFs); the ratio kept in
    ``ws.achieved``."""
    ws.check.data = form.mat * ws.du - ws.r
    res = ws.norm(ws.check)
    ws.achieved = res / rnorm
    return res <= rtol * rnorm


def _reuse_and_solve(inv, form, problem, ws, rnorm: float, rtol: float, steps: int) -> bool:
    """du from GMRES on the new matrix preconditioned by a direct solver's kept factors of an
    earlier one, at most ``steps`` iterations; True if it reached ``rtol`` (``_reached``),
    else the factors are refactorised by the caller."""
    w = np.where(ws.free, ws.weights(), 0.0)
    gmres(form.mat, inv, problem.freedofs, ws.r, ws.du, GMRES_MARGIN * rtol, w, steps,
          on_track=True)
    return _reached(form, ws, rnorm, rtol)


def _update_and_solve(inv, form, ws, rnorm: float, rtol: float, stats) -> bool:
    """Refactorise a kept inverse for the matrix's new values; False if that fails."""
    try:
        stats.factorisations += 1
        inv.Update()
    except Exception:  # noqa: BLE001
        return False
    return _accurate(inv, form, ws, rnorm, rtol)


def picard(problem: NonlinearSystem, tol: float = 1e-5, max_it: int = 20) -> SolveStats:
    """Picard iteration (3.8b): J(U^i) U^{i+1} = b(U^i), coefficients frozen at U^i."""
    ws, stats = _Workspace(problem), SolveStats()
    scale = problem.velocity_scale
    for it in range(1, max_it + 1):
        # each step is one parallel region: the task manager while no other
        # process wants the cores (fem/reproducible.parallel), sampled each step
        with parallel():
            problem.gf_w.vec.data = problem.gf.vec
            _linear_step(problem.a_picard, problem, ws, stats,      # Newton's forcing term
                         rtol=min(problem.linear_rtol, max(stats.update, FORCING_FLOOR)))
            stats.residual = ws.norm(ws.r)
            problem.gf.vec.data -= ws.du
            stats.iterations = it
            stats.update = ws.max_velocity(ws.du) / scale
            if stats.update <= tol:
                stats.converged = True
                break
    return stats


def newton(
    problem: NonlinearSystem,
    tol: float = 1e-5,
    max_it: int = 20,
    min_step: float = 1.0 / 64,
    couple: Callable[[float], bool] | None = None,
    couple_below: float | Callable[[], float] = 1e-3,
    full_step: bool = False,
    chord: bool = False,
    last_residual: bool = True,
) -> SolveStats:
    """Newton's method on the residual form with a backtracking line search on ||r||
    (``min_step = 1``: no search, the full step).

    ``couple`` (optional) updates data the form depends on (a_f, the free surface) once the
    velocity update is below ``couple_below`` (a number, or a callable giving it now; it is
    given that update, over the velocity scale); it returns True while that data still moves,
    and the iteration only stops when it returns False and the update is below ``tol``.
    ``chord``: the Jacobian's kept factors instead of new ones (Newton-chord). ``full_step``:
    the steady solver's final solve (a direction below ``tol`` is taken whole; a search that
    fails below ``WATCHDOG_BELOW`` takes the full step once). ``last_residual=False`` (no
    line search and no ``couple`` only: neither the coupling nor the multiplier's test runs
    then): the residual after the ``max_it``-th step is not evaluated (its
    ``stats.residual`` is NaN): the heat equation's one step per coupling update, whose
    residual nobody reads, saved an evaluation as costly as the step's assembly. The system's
    ``prepare(iteration)``, where it has one, runs first in every iteration and returns True
    when it changed the form (its residual is then evaluated again).
    """
    ws, stats = _Workspace(problem), SolveStats()
    form = problem.a_newton
    prepare = getattr(problem, "prepare", None)
    residual_ready, extra, watched = False, 0, False
    for it in range(1, max_it + 1):
        # each step is one parallel region: the task manager while no other
        # process wants the cores (fem/reproducible.parallel), sampled each step
        with parallel():
            if prepare is not None and prepare(it):
                residual_ready = False
            scale = problem.velocity_scale
            # the forcing term (module docstring): linear_rtol, or the last direction's size
            rtol = min(problem.linear_rtol, max(stats.update, FORCING_FLOOR))
            _linear_step(form, problem, ws, stats, residual_ready, problem.a_jacobian, chord, rtol)
            # the Newton direction, not the damped step: a step cut by the line search is small
            # without the iterate being converged
            stats.update = ws.max_velocity(ws.du) / scale
            if (stats.update <= tol and rtol > max(stats.update, FORCING_FLOOR)
                    and ws.achieved > max(stats.update, FORCING_FLOOR)):
                # a direction small enough to end the solve, solved loosely (a solve's first:
                # the last update is not known yet): solved again to its own size before it is
                # trusted (from the session's review: a 3e-6 U start stopped 2e-6 U off), unless
                # it already reached that (a direct solver's solution: its rounding)
                rtol = max(stats.update, FORCING_FLOOR)
                _linear_step(form, problem, ws, stats, True, problem.a_jacobian, chord, rtol)
                stats.update = ws.max_velocity(ws.du) / scale
            r0 = ws.norm(ws.r)
            ws.backup.data = problem.gf.vec
            # full_step: once the direction is below the tolerance, its full step is taken without
            # the line search. There the residual's norm is at its floor (the near-rigid zones,
            # whose viscosity is eps0^(m-1): a velocity change of 1e-7 U moves it), and the test
            # r1 < r0 refused full steps of 1e-7 U for up to five iterations on the finishing pass
            alpha, search = 1.0, not (full_step and stats.update <= tol)
            if (not last_residual and it == max_it and couple is None
                    and (min_step >= 1.0 or not search)):
                problem.gf.vec.data = ws.backup - ws.du
                stats.iterations, stats.residual = it, float("nan")
                stats.converged = stats.update <= tol
                if TRACE is not None:
                    TRACE(problem, it, stats.update, alpha, r0, float("nan"))
                break
            while True:
                problem.gf.vec.data = ws.backup - alpha * ws.du
                with parallel():
                    form.Apply(problem.gf.vec, ws.r)
                r1 = ws.norm(ws.r)
                if (not search or r1 <= (1.0 - 1e-4 * alpha) * r0 or alpha <= min_step
                        or r0 == 0.0):
                    break
                alpha *= 0.5
            # full_step: a search that found no decrease down to min_step on a small update takes
            # the full step instead, once (not twice running): near the regularised friction's kink
            # the residual's norm rises on the way to the solution, and the cut steps stalled for
            # 10-20 iterations on thin passes where the full steps converged in 2-3 (speed.md)
            watched = (full_step and search and alpha <= min_step and r0 > 0.0
                       and r1 > (1.0 - 1e-4 * alpha) * r0 and stats.update <= WATCHDOG_BELOW
                       and not watched)
            if watched:
                alpha = 1.0
                problem.gf.vec.data = ws.backup - ws.du
                with parallel():
                    form.Apply(problem.gf.vec, ws.r)
                r1 = ws.norm(ws.r)
            stats.iterations = it
            stats.residual = r1
            if TRACE is not None:
                TRACE(problem, it, stats.update, alpha, r0, r1)
            residual_ready = True
            below = couple_below() if callable(couple_below) else couple_below
            if couple is not None and stats.update <= below:
                if couple(stats.update):
                    residual_ready = False   # the form changed: its residual must be re-evaluated
                    continue
            # a contact multiplier's own test (its DOFs are not velocity nodes). In a sticking zone
            # the regularised friction is a tangential stiffness of a_f v_reg^(m-1) (10^7 times the
            # viscosity on Example 1): the pressure at the neutral node then moves by percents for
            # velocity changes of 1e-7 U, without settling. Once the velocity has converged the
            # multiplier gets MULTIPLIER_EXTRA more steps; what it still moves is reported
            # (``multiplier_update``), not hidden.
            stats.multiplier_update = problem.max_multiplier(ws.du) / scale
            settled = stats.multiplier_update <= problem.multiplier_tol
            if stats.update <= tol and not settled and (alpha == 1.0 or not full_step):
                extra += 1
                settled = extra > MULTIPLIER_EXTRA
            if stats.update <= tol and settled and (alpha == 1.0 or not full_step):
                # full_step: a full Newton step below the tolerance, in Newton's quadratic range the
                # residual after it is of the order of the step squared (the steady solver's final
                # solve, whose forces are reported; each time step of the report's scheme keeps the
                # plain test: it would otherwise spend steps at max_it on its non-smooth contact)
                stats.converged = True
                break
    return stats


def solve(problem: NonlinearProblem, method: str, tol: float, max_it: int) -> SolveStats:
    """Dispatch to ``picard`` or ``newton``."""
    if method == "picard":
        return picard(problem, tol, max_it)
    if method == "newton":
        return newton(problem, tol, max_it)
    raise ValueError(f"solver.nonlinear must be 'newton' or 'picard', got {method!r}")
