"""GMRES preconditioned by the LDL^T factorisation of the matrix's lower triangle: the flow's
linear solver where the Jacobian is not symmetric (issue 34 session 7).

The flow's Newton matrix is symmetric but for a few boundary terms: Coulomb's friction
depends on the contact multiplier (the pressure), the one-sided inlet and outlet conditions
(3.2a-b) on the side of the velocity, the friction's tangent on the roll's frame. NGSolve's
sparse LDL^T (``sparsecholesky``, no pivoting) reads the lower triangle only: on a Coulomb
pass its solution missed the 1e-6 residual test by x30, and the steady solver fell back to
UMFPACK for every iteration (refactorisation and solve 24 ms on a 6.6k-DOF thermal finishing
pass, 2 threads). As GMRES's preconditioner the same factorisation takes 8-13 iterations to a
relative residual of 1e-10-1e-12: 11 ms, the solution 6e-11 from UMFPACK's. The test of
``nonlinear._accurate`` still decides: where GMRES does not reach it (``MAX_STEPS``), the next
direct solver is taken.
"""
from __future__ import annotations

from hotroll.fem.reproducible import one_thread

#: GMRES's relative residual (of the system, in the rows' weighted norm) where the caller
#: names none: the solution then 1e-10 from a direct solve's
TOL = 1e-10
#: GMRES's iterations before it gives up (the direct solvers after it then run)
MAX_STEPS = 60

#: the name ``linear_solvers`` lists it under
NAME = "sparsecholesky+gmres"


class PreconditionedGMRES:
    """``Update()`` refactorises the preconditioner for the matrix's new values (the same
    sparsity); ``solve(r, out, rtol, weights)``: out = A^{-1} r by GMRES on the free DOFs.

    GMRES is preconditioned from the right (it solves A P y = r, out = P y), so the residual it
    minimises and stops on is the system's own, r - A out, measured in the norm of the row
    ``weights`` (the flow's: its pressure rows times a viscosity, ``nonlinear._Workspace``):
    then its iterations, and where it stops, are the same at any roll speed or unit of time
    (a left-preconditioned GMRES minimised the 2-norm of a vector of velocities and pressures,
    whose stopping point moved with the units: issue 34 session 10).

    Where the matrix is symmetric (GMRES's last solve took one iteration: the viscoplastic
    and Tresca-free passes), the factorisation is applied directly and GMRES runs only if the
    residual of that is above ``rtol`` of r: GMRES's one iteration applies the factors twice
    (issue 34 session 8)."""

    iterative = True

    def __init__(self, mat, freedofs):
        import numpy as np

        self.mat = mat
        with one_thread():
            self.pre = mat.Inverse(freedofs, inverse="sparsecholesky")
        self.iterations = 0
        self.direct = False           # try the factors alone first (the last solve's hint)
        self._freedofs = freedofs
        self._free = np.array(list(freedofs), dtype=bool)
        self._res = None

    def Update(self) -> None:                      # noqa: N802 - NGSolve's inverse interface
        with one_thread():
            self.pre.Update()

    def _direct(self, r, out, rtol: float, w) -> bool:
        """out = the factors applied to r; True if A out = r to ``rtol`` (weighted rows)."""
        import numpy as np

        out.data = self.pre * r
        if self._res is None:
            self._res = r.CreateVector()
        self._res.data = self.mat * out - r
        res, rhs = w * self._res.FV().NumPy(), w * r.FV().NumPy()
        return bool(np.linalg.norm(res) <= rtol * np.linalg.norm(rhs))

    def solve(self, r, out, rtol: float = TOL, weights=None) -> None:
        """out = A^{-1} r to the relative residual ``rtol`` in the norm of the row ``weights``
        (a numpy array over all DOFs; default 1 on the free rows), in one thread
        (``one_thread``: the factors' solves are sequential only there)."""
        with one_thread():
            self._solve(r, out, rtol, weights)

    def _solve(self, r, out, rtol: float, weights) -> None:
        import numpy as np

        w = self._free.astype(float) if weights is None else np.where(self._free, weights, 0.0)
        started = False
        if self.direct:
            if self._direct(r, out, rtol, w):
                self.iterations = 0
                return
            started = True            # GMRES from there: out = P y with y = r
        self.iterations = gmres(self.mat, self.pre, self._freedofs, r, out, rtol, w,
                                MAX_STEPS, started)
        self.direct = self.iterations <= 1


class _OffTrack(Exception):
    """GMRES's residual fell too slowly to reach its target within its iterations."""


def gmres(mat, pre, freedofs, r, out, rtol: float, w, maxiter: int,
          started: bool = False, on_track: bool = False) -> int:
    """out = pre y with y from GMRES on mat pre y = r (right preconditioning), stopped on
    ||r - mat out|| <= rtol ||r|| in the norm of the row weights ``w`` (zero off the free
    rows) or after ``maxiter`` iterations; ``started``: from y = r, else from 0. ``on_track``:
    also given up after k >= 2 iterations whose residual is above the geometric path to the
    target in ``maxiter`` iterations, ||r_k|| > ||r|| rtol^(k / maxiter). Returns NGSolve's
    count of the iterations (the start's residual counted as one); out is NaN where GMRES
    broke down or gave up (the caller's accuracy test fails)."""
    import numpy as np
    from ngsolve.krylovspace import GMResSolver

    w2 = w * w

    def inner(x, y):
        return float(np.dot(w2 * x.FV().NumPy(), y.FV().NumPy()))

    # stopped on ||r - A out|| <= rtol ||r|| (an absolute bound: from the factors' solution
    # GMRES's first residual is not r's, and a relative one would be relative to it)
    size = float(np.sqrt(inner(r, r)))

    def track(iterations: int, residual: float) -> None:
        k = iterations - 1                  # NGSolve counts the start's residual as one
        if k >= 2 and residual > size * rtol ** (k / maxiter):
            raise _OffTrack

    solver = GMResSolver(mat=mat @ pre, freedofs=freedofs, innerproduct=inner,
                         tol=0.0, atol=rtol * size, maxiter=maxiter, printrates=False,
                         callback=track if on_track else None)
    y = r.CreateVector()
    try:
        if started:
            y.data = r
        else:
            y[:] = 0.0
        solver.Solve(rhs=r, sol=y, initialize=False)
        out.data = pre * y
    except Exception:  # noqa: BLE001 - NGSolve raises plain exceptions (a singular
        # Hessenberg system on a broken state), or off track: no solution, the accuracy
        # test fails
        out.FV().NumPy()[:] = float("nan")
    return solver.iterations


def apply_inverse(inv, r, out, rtol: float = TOL, weights=None) -> None:
    """out = inv^{-1} r for a direct solver's inverse or an iterative one (a
    ``PreconditionedGMRES``, ``amg.BlockAMG``: to the relative residual ``rtol`` in the norm
    of the row ``weights``)."""
    if getattr(inv, "iterative", False):
        inv.solve(r, out, rtol, weights)
    else:
        out.data = inv * r


def make_inverse(mat, freedofs, name: str):
    """The inverse of ``mat`` on ``freedofs`` by the solver ``name`` (an NGSolve direct
    solver's name or ``NAME``; the AMG solver is ``amg.make_inverse``'s)."""
    if name == NAME:
        return PreconditionedGMRES(mat, freedofs)
    return mat.Inverse(freedofs, inverse=name)


def numpy_operator(apply, like, inverse=None, update=None):
    """``apply`` (numpy -> numpy over all DOFs, vectors like ``like``) as an NGSolve matrix
    (``op * x`` in vector expressions); ``inverse(freedofs, name)`` its ``Inverse``,
    ``update()`` its ``Update`` (a kept factorisation's, ``fem/nonlinear.py``), where given."""
    from ngsolve import BaseMatrix

    class Operator(BaseMatrix):
        def IsComplex(self):                           # noqa: N802
            return False

        def Height(self):                              # noqa: N802
            return len(like)

        def Width(self):                               # noqa: N802
            return len(like)

        def CreateRowVector(self):                     # noqa: N802
            return like.CreateVector()

        def CreateColVector(self):                     # noqa: N802
            return like.CreateVector()

        def Mult(self, x, y):                          # noqa: N802
            y.FV().NumPy()[:] = apply(x.FV().NumPy())

        def Inverse(self, freedofs=None, inverse: str = ""):   # noqa: N802
            if inverse_of is None:
                raise NotImplementedError("no inverse of this operator")
            return inverse_of(freedofs, inverse)

        def Update(self):                              # noqa: N802
            if update is None:
                raise NotImplementedError("no Update of this operator")
            update()

    inverse_of = inverse
    return Operator()

