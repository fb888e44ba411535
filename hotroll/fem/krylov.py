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

#: GMRES's relative residual (of the preconditioned system): two orders below what Newton's
#: direction needs, the direction then 1e-10 from a direct solve's
TOL = 1e-10
#: GMRES's iterations before it gives up (the direct solvers after it then run)
MAX_STEPS = 60

#: the name ``linear_solvers`` lists it under
NAME = "sparsecholesky+gmres"


class PreconditionedGMRES:
    """``Update()`` refactorises the preconditioner for the matrix's new values (the same
    sparsity); ``solve(r, out)``: out = A^{-1} r by GMRES on the free DOFs.

    Where the matrix is symmetric (GMRES's last solve took one iteration: the viscoplastic
    and Tresca-free passes), the factorisation is applied directly and GMRES runs only if the
    residual of that is above ``TOL`` of r: GMRES's one iteration applies the factors twice
    (issue 34 session 8)."""

    def __init__(self, mat, freedofs):
        import numpy as np

        self.mat = mat
        self.pre = mat.Inverse(freedofs, inverse="sparsecholesky")
        self.iterations = 0
        self.direct = False           # try the factors alone first (the last solve's hint)
        self._free = np.array(list(freedofs), dtype=bool)
        self._res = None

    def Update(self) -> None:                      # noqa: N802 - NGSolve's inverse interface
        self.pre.Update()

    def _direct(self, r, out) -> bool:
        """out = the factors applied to r; True if A out = r to TOL (free DOFs)."""
        import numpy as np

        out.data = self.pre * r
        if self._res is None:
            self._res = r.CreateVector()
        self._res.data = self.mat * out - r
        free = self._free
        res, rhs = self._res.FV().NumPy()[free], r.FV().NumPy()[free]
        return bool(np.linalg.norm(res) <= TOL * np.linalg.norm(rhs))

    def solve(self, r, out) -> None:
        from ngsolve.krylovspace import GMResSolver

        started = False
        if self.direct:
            if self._direct(r, out):
                self.iterations = 0
                return
            started = True            # GMRES from there
        solver = GMResSolver(mat=self.mat, pre=self.pre, tol=TOL, maxiter=MAX_STEPS,
                             printrates=False)
        try:
            if started:
                out.data = solver.Solve(rhs=r, sol=out, initialize=False)
            else:
                out.data = solver.Solve(rhs=r)
        except Exception:  # noqa: BLE001 - NGSolve raises plain exceptions (a singular
            # Hessenberg system on a broken state): no solution, the accuracy test fails
            out.FV().NumPy()[:] = float("nan")
        self.iterations = solver.iterations
        self.direct = self.iterations <= 1


def apply_inverse(inv, r, out) -> None:
    """out = inv^{-1} r for a direct solver's inverse or a ``PreconditionedGMRES``."""
    if isinstance(inv, PreconditionedGMRES):
        inv.solve(r, out)
    else:
        out.data = inv * r


def make_inverse(mat, freedofs, name: str):
    """The inverse of ``mat`` on ``freedofs`` by the solver ``name`` (an NGSolve direct
    solver's name or ``NAME``)."""
    if name == NAME:
        return PreconditionedGMRES(mat, freedofs)
    return mat.Inverse(freedofs, inverse=name)
