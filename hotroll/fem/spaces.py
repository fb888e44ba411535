"""Taylor-Hood P2/P1 spaces (report (3.4), l = k - 1 for inf-sup stability)."""
from __future__ import annotations

from operator import mul

import numpy as np

from hotroll.fem.reproducible import fe_space

#: NGSolve's order-2 H1 edge shape function at the edge midpoint: the edge DOF of a P2 field is
#: the coefficient of this bubble, not a nodal value.
BUBBLE_MID = -0.125


def taylor_hood(mesh, dirichletx: str = "", dirichlety: str = "sym", order: int = 2,
                multiplier_on: str | None = None, dirichletz: str | None = None):
    """Velocity VectorH1(order) x pressure H1(order - 1), component-wise Dirichlet regions;
    with ``multiplier_on`` (a boundary region) a third factor: continuous P1 with DOFs at that
    boundary's vertices only (the contact pressure; stable with P2 velocities,
    ../shared/notes/exact-contact.md). It is the volume P1 space compressed to those DOFs, not a
    space defined on the boundary: an element-boundary integral (which sees the volume
    gradient, e.g. Coulomb's cap k of the strain rate) evaluates it too, as the P1 trace."""
    from ngsolve import H1, Compress, VectorH1

    z = {} if dirichletz is None else {"dirichletz": dirichletz}       # a 3D mesh's
    V = fe_space(VectorH1, mesh, order=order, dirichletx=dirichletx, dirichlety=dirichlety, **z)
    Q = fe_space(H1, mesh, order=order - 1)
    if multiplier_on is None:
        return fe_space(mul, V, Q)
    full = fe_space(H1, mesh, order=1)
    L = fe_space(Compress, full, active_dofs=full.GetDofs(mesh.Boundaries(multiplier_on)))
    return fe_space(mul, fe_space(mul, V, Q), L)


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



class P2PointValues:
    """A P2 field at fixed points of its mesh (the thermal strip's column points): P2 is the
    Lagrange interpolant of its 6 nodal values on each triangle, u = sum_i l_i (2 l_i - 1) u_i
    + sum_e 4 l_i l_j u_e (l the barycentric coordinates, NGSolve's local x, y and 1 - x - y
    of vertices 0, 1, 2), so the values are 6 nodal values a point, weighted; 10x cheaper
    than NGSolve's evaluation point by point (issue 34 session 8; equal to 1e-15, tested)."""

    def __init__(self, nodes: P2Nodes, triangles: np.ndarray, elem: np.ndarray,
                 local: np.ndarray):
        nv = nodes.nv
        key = np.sort(np.stack([nodes.ea, nodes.eb], -1), axis=1)
        key = key[:, 0] * nv + key[:, 1]
        order = np.argsort(key)
        T = np.asarray(triangles, dtype=int)[np.asarray(elem, dtype=int)]

        def edge(i, j):
            k = np.minimum(T[:, i], T[:, j]) * nv + np.maximum(T[:, i], T[:, j])
            return nv + order[np.searchsorted(key[order], k)]

        l0, l1 = local[:, 0], local[:, 1]
        lam = np.stack([l0, l1, 1.0 - l0 - l1], -1)
        from scipy.sparse import csr_matrix

        self.nodes = nodes
        index = np.concatenate([T, np.stack([edge(0, 1), edge(1, 2), edge(0, 2)], -1)], axis=1)
        weight = np.concatenate([lam * (2.0 * lam - 1.0),
                                 4.0 * np.stack([lam[:, 0] * lam[:, 1], lam[:, 1] * lam[:, 2],
                                                 lam[:, 0] * lam[:, 2]], -1)], axis=1)
        n = len(T)
        #: (points, nodes): the 6 weights of each point (a sparse product: 0.1 ms for 16k)
        self.matrix = csr_matrix((weight.ravel(), index.ravel(), np.arange(0, 6 * n + 1, 6)),
                                 shape=(n, nodes.nv + len(nodes.ea)))

    def __call__(self, coefficients: np.ndarray) -> np.ndarray:
        """(N, 2): both components at the points, from the field's coefficient vector."""
        return self.matrix @ self.nodes.values(coefficients).T
