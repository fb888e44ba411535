"""Taylor-Hood P2/P1 spaces (report (3.4), l = k - 1 for inf-sup stability)."""
from __future__ import annotations

import numpy as np

#: NGSolve's order-2 H1 edge shape function at the edge midpoint: the edge DOF of a P2 field is
#: the coefficient of this bubble, not a nodal value.
BUBBLE_MID = -0.125


def taylor_hood(mesh, dirichletx: str = "", dirichlety: str = "sym", order: int = 2,
                multiplier_on: str | None = None):
    """Velocity VectorH1(order) x pressure H1(order - 1), component-wise Dirichlet regions;
    with ``multiplier_on`` (a boundary region) a third factor: continuous P1 with DOFs at that
    boundary's vertices only (the contact pressure; stable with P2 velocities,
    ../shared/notes/exact-contact.md). It is the volume P1 space compressed to those DOFs, not a
    space defined on the boundary: an element-boundary integral (which sees the volume
    gradient, e.g. Coulomb's cap k of the strain rate) evaluates it too, as the P1 trace."""
    from ngsolve import H1, Compress, VectorH1

    V = VectorH1(mesh, order=order, dirichletx=dirichletx, dirichlety=dirichlety)
    Q = H1(mesh, order=order - 1)
    if multiplier_on is None:
        return V * Q
    full = H1(mesh, order=1)
    L = Compress(full, active_dofs=full.GetDofs(mesh.Boundaries(multiplier_on)))
    return V * Q * L


class P2Nodes:
    """The nodes of a P2 VectorH1 field (vertices, then edge midpoints) and the map between its
    coefficient vector and its nodal values."""

    def __init__(self, mesh, ndof_scalar: int):
        nv = mesh.nv
        ev = np.array([[v.nr for v in e.vertices] for e in mesh.edges], dtype=int).reshape(-1, 2)
        if nv + len(ev) != ndof_scalar:
            raise ValueError(f"not a P2 space: {ndof_scalar} DOFs per component, expected "
                             f"{nv} vertices + {len(ev)} edges")
        self.n, self.nv, self.ea, self.eb = ndof_scalar, nv, ev[:, 0], ev[:, 1]
        X = np.array([v.point for v in mesh.vertices])[:, :2]
        self.X0 = np.concatenate([X, 0.5 * (X[self.ea] + X[self.eb])])   # reference nodes

    def values(self, f: np.ndarray) -> np.ndarray:
        """Nodal values of both components, shape (2, vertices + edges)."""
        c = f[: 2 * self.n].reshape(2, self.n)
        mid = 0.5 * (c[:, self.ea] + c[:, self.eb]) + BUBBLE_MID * c[:, self.nv:]
        return np.concatenate([c[:, : self.nv], mid], axis=1)

    def coefficients(self, vals: np.ndarray) -> np.ndarray:
        """The coefficient vector with nodal values ``vals`` (shape (2, vertices + edges)):
        the inverse of ``values``."""
        vert, mid = vals[:, : self.nv], vals[:, self.nv:]
        bubble = (mid - 0.5 * (vert[:, self.ea] + vert[:, self.eb])) / BUBBLE_MID
        return np.concatenate([vert, bubble], axis=1).reshape(-1)
