"""GMRES preconditioned by smoothed-aggregation AMG: the 3D strip's linear solver without a
factorisation of the whole Jacobian, for meshes whose factors do not fit (issue 53).

The Newton matrix is [[A, B^T], [B, C]]: A the velocity block (the Norton-Hoff tangent, the
friction's, the penalties'), B the pressure's and the contact multiplier's rows, C theirs
(the multiplier's regularisation, the elastic layer's terms). The preconditioner is block
upper-triangular: y_s = S^-1 r_s, y_u = A~^-1 (r_u - B^T y_s), with
- A~^-1 one V-cycle of smoothed aggregation (pyamg) on A's symmetric part, the velocity
  node-blocked (3 x 3) and the rigid-body modes its near-null space;
- S = C - B diag(A)^-1 B^T (the SIMPLE approximation of the Schur complement: a sparse
  matrix of the pressure's and the multiplier's size), factorised by SuperLU.
GMRES (``krylov.gmres``, right-preconditioned, stopped on the system's own residual in the
Newton norm's row weights) on it. Measured on the roughing pass's first 3D Jacobian (113k
unknowns): 170 iterations to 1e-6, about 27 s, against a 12.7 s UMFPACK refactorisation and
3.47 GB (docs/notes/issue53-iterative/README.md): slower, without the factors' memory.
Deterministic (scipy, pyamg, SuperLU and BLAS held to one thread): the same bits at any thread
count.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hotroll.fem import krylov
from hotroll.fem.reproducible import one_thread


def _sequential():
    """NGSolve and BLAS on this thread alone (``one_thread``; threadpoolctl: numpy's inner
    products on other threads' BLAS ran 2500x slower on a loaded machine)."""
    from contextlib import ExitStack

    from threadpoolctl import threadpool_limits

    stack = ExitStack()
    stack.enter_context(one_thread())
    stack.enter_context(threadpool_limits(limits=1))
    return stack

#: the name ``Spread3D(linear_solver=...)`` takes
NAME = "amg+gmres"
#: GMRES's iterations before it gives up (the direct solvers after it then run)
MAX_STEPS = 400


@dataclass(frozen=True)
class VelocityLayout:
    """Where the velocity sits in the unknowns: the first ``n_velocity`` DOFs, its three
    components one after the other (``n_velocity / 3`` each), every component's first
    ``len(points)`` DOFs its values at the mesh vertices ``points`` (NGSolve's VectorH1:
    vertex DOFs first, then the hierarchical edge and face ones, which a linear field has 0)."""

    n_velocity: int
    points: np.ndarray

    def rigid_modes(self) -> np.ndarray:
        """The six rigid-body motions (columns; three translations, three rotations about the
        vertices' centroid)."""
        n1, nv = self.n_velocity // 3, len(self.points)
        X = self.points - self.points.mean(axis=0)
        modes = np.zeros((self.n_velocity, 6))
        for c in range(3):
            modes[c * n1: c * n1 + nv, c] = 1.0
        for col, (a, b) in enumerate(((0, 1), (0, 2), (1, 2)), start=3):
            modes[a * n1: a * n1 + nv, col] = X[:, b]
            modes[b * n1: b * n1 + nv, col] = -X[:, a]
        return modes


def _scipy(mat):
    """An NGSolve sparse matrix as scipy CSR."""
    import scipy.sparse as sp

    rows, cols, vals = mat.COO()
    n = mat.height
    return sp.csr_matrix((np.asarray(vals), (np.asarray(rows), np.asarray(cols))), shape=(n, n))


class BlockAMG:
    """``Update()`` rebuilds the preconditioner from the matrix's new values;
    ``solve(r, out, rtol, weights)``: out = A^{-1} r by GMRES on the free DOFs (module
    docstring). The same interface as ``krylov.PreconditionedGMRES``."""

    iterative = True

    def __init__(self, mat, freedofs, layout: VelocityLayout):
        self.mat, self._freedofs, self.layout = mat, freedofs, layout
        self._free = np.array(list(freedofs), dtype=bool)
        n, nu = mat.height, layout.n_velocity
        # the node-blocked order of the velocity: position 3 i + c holds component c's DOF i
        self._perm = np.arange(nu).reshape(3, nu // 3).T.reshape(-1)
        where = np.empty(nu, dtype=int)
        where[self._perm] = np.arange(nu)
        idx = np.arange(n)
        self._iu = idx[:nu][self._free[:nu]]
        self._is = idx[nu:][self._free[nu:]]
        self._at = where[self._iu]          # the free velocity's places in the blocked order
        self._modes = (layout.rigid_modes() * self._free[:nu, None])[self._perm]
        self.iterations = 0
        self.Update()

    def Update(self) -> None:                      # noqa: N802 - NGSolve's inverse interface
        import pyamg
        import scipy.sparse as sp
        import scipy.sparse.linalg as sla

        with _sequential():
            J = _scipy(self.mat)
            nu = self.layout.n_velocity
            fixed = ~self._free[:nu]
            keep = sp.diags((~fixed).astype(float))
            A = (keep @ J[:nu, :nu] @ keep + sp.diags(fixed.astype(float))).tocsr()
            A = A[self._perm][:, self._perm]
            sym = sp.bsr_matrix(0.5 * (A + A.T), blocksize=(3, 3))
            # the prolongation's Jacobi weight from a local bound of the spectral radius:
            # pyamg's default estimates it from a random start (np.random), which moved a
            # pass's last bits from run to run
            self._amg = pyamg.smoothed_aggregation_solver(
                sym, B=self._modes, strength="symmetric",
                smooth=("jacobi", {"weighting": "local"}), max_coarse=500)
            self._cycle = self._amg.aspreconditioner(cycle="V")
            iu, is_ = self._iu, self._is
            self._bt = J[iu][:, is_].tocsr()
            rows = J[is_]
            schur = (rows[:, is_]
                     - rows[:, iu] @ sp.diags(1.0 / J.diagonal()[iu]) @ self._bt)
            self._schur = sla.splu(schur.tocsc())

    def _apply(self, x: np.ndarray) -> np.ndarray:
        """The block-triangular preconditioner on a vector over all DOFs (0 off the free)."""
        out = np.zeros_like(x)
        ys = self._schur.solve(x[self._is])
        z = np.zeros(self.layout.n_velocity)
        z[self._at] = x[self._iu] - self._bt @ ys
        out[self._iu] = (self._cycle @ z)[self._at]
        out[self._is] = ys
        return out

    def solve(self, r, out, rtol: float, weights=None) -> None:
        """out = A^{-1} r to the relative residual ``rtol`` in the norm of the row ``weights``
        (default 1 on the free rows). Where GMRES stops short of it (``MAX_STEPS``) out is its
        last iterate, NaN after a breakdown: Newton's accuracy test refuses either."""
        w = self._free.astype(float) if weights is None else np.where(self._free, weights, 0.0)
        pre = krylov.numpy_operator(self._apply, r)
        with _sequential():
            self.iterations = krylov.gmres(self.mat, pre, self._freedofs, r, out, rtol, w,
                                           MAX_STEPS)


def make_inverse(mat, freedofs, name: str, layout: VelocityLayout | None = None):
    """``krylov.make_inverse``, and for ``NAME`` a ``BlockAMG`` (it needs the velocity's
    ``layout``: a 3D strip's)."""
    if name != NAME:
        return krylov.make_inverse(mat, freedofs, name)
    if layout is None:
        raise ValueError(f"{NAME} needs the velocity's layout (a 3D strip's)")
    return BlockAMG(mat, freedofs, layout)
