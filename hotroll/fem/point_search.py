"""Points found in a straight-sided triangle mesh, vectorised (numpy), as NGSolve MeshPoints.

NGSolve's ``mesh(x, y)`` found the 16k column points of a steady pass's thermal strip in the
graded mechanics mesh (1.1k triangles) in 22 ms, 1.3 us a point; a schedule searched twice a
pass (the strip's points, the streamlines'), and the similar-pass start once. Here: a grid of
buckets over the mesh, each holding the triangles whose bounding box meets it, and the
barycentric test of every point against its bucket's triangles, all points at once (issue 34
session 8). The result is the array ``mesh(x, y)`` returns (element number and the local
coordinates, NGSolve's reference triangle: x v0 + y v1 + (1 - x - y) v2 for the element's
vertices v0, v1, v2), so every evaluation on it is NGSolve's own. A point on an edge shared by
two triangles is given to one of them (NGSolve may pick the other: a continuous field's value
is the same). Such a point, and one on no triangle, is searched by NGSolve instead: a strain
rate jumps between triangles, and NGSolve's choice of triangle is then kept (the thermal
strip's top vertices are the mechanics mesh's top vertices, each on two or more triangles).
"""
from __future__ import annotations

from collections import OrderedDict

import numpy as np

from hotroll.fem.reproducible import find_points

#: a point is inside a triangle when each barycentric coordinate is >= -INSIDE
INSIDE = 1e-12
#: ... and inside it alone when each is > CLEAR; nearer an edge or a corner NGSolve searches (its
#: own tolerance decides there: 1e-9 gave another triangle than NGSolve for the streamlines
#: 1e-8 inside the top, a 1e-3 change of the surface's pass strain; at 1e-6 NGSolve still
#: gave the neighbour for 12 % of the points 1.01e-6 inside a triangle and 1 % at 1.2e-6, none
#: from 2e-6 on (the session's review): 1e-5)
CLEAR = 1e-5
#: the meshes whose searches are kept (a schedule's last passes; ``for_mesh``)
KEPT = 4
_kept: OrderedDict = OrderedDict()


class TriangleSearch:
    """The triangles ``tris`` (ne, 3 vertex numbers) over the vertices ``points`` (nv, 2)."""

    def __init__(self, points: np.ndarray, tris: np.ndarray):
        P = np.asarray(points, dtype=float)[:, :2]
        T = np.asarray(tris, dtype=int)
        self.ne = len(T)
        a, b, c = P[T[:, 0]], P[T[:, 1]], P[T[:, 2]]
        # local (x, y) of p: p - c = x (a - c) + y (b - c)
        m = np.stack([a - c, b - c], axis=-1)                 # (ne, 2, 2): columns a-c, b-c
        self._inv = np.linalg.inv(m)
        self._c = c
        lo = np.minimum(np.minimum(a, b), c)
        hi = np.maximum(np.maximum(a, b), c)
        self._lo, span = P.min(axis=0), np.ptp(P, axis=0)
        # buckets about the size of the smaller triangles (the graded mesh's fine zone): a
        # large triangle is listed in several buckets, a bucket holds few triangles
        size = np.sqrt(np.abs(np.linalg.det(m)) / 2.0)
        cell = max(float(np.percentile(size, 25)), 1e-300)
        self._n = np.maximum(np.ceil(span / cell).astype(int), 1)
        self._cell = np.where(span > 0, span / self._n, 1.0)
        i0, j0 = self._bucket(lo).T
        i1, j1 = self._bucket(hi).T
        ni, nj = i1 - i0 + 1, j1 - j0 + 1
        count = ni * nj
        owner = np.repeat(np.arange(self.ne), count)
        k = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
        bi = i0[owner] + k % ni[owner]
        bj = j0[owner] + k // ni[owner]
        cell_id = bi * self._n[1] + bj
        order = np.argsort(cell_id, kind="stable")
        self._tri = owner[order]
        self._start = np.searchsorted(cell_id[order], np.arange(self._n[0] * self._n[1] + 1))

    def _bucket(self, xy: np.ndarray) -> np.ndarray:
        ij = np.floor((xy - self._lo) / self._cell).astype(int)
        return np.clip(ij, 0, self._n - 1)

    def find(self, x, y) -> tuple[np.ndarray, np.ndarray]:
        """(element number, -1 outside; local coordinates (N, 2)) of the points (x, y); a
        point on an edge shared by triangles is given to one of them."""
        p = np.stack([np.asarray(x, dtype=float).ravel(), np.asarray(y, dtype=float).ravel()],
                     axis=-1)
        ij = self._bucket(p)
        cell = ij[:, 0] * self._n[1] + ij[:, 1]
        first, count = self._start[cell], self._start[cell + 1] - self._start[cell]
        elem = np.full(len(p), -1, dtype=int)
        local = np.zeros((len(p), 2))
        todo = np.nonzero(count > 0)[0]
        k = 0
        while len(todo):
            t = self._tri[first[todo] + k]
            xy = np.einsum("nij,nj->ni", self._inv[t], p[todo] - self._c[t])
            ok = (xy[:, 0] >= -INSIDE) & (xy[:, 1] >= -INSIDE) & (xy.sum(axis=1) <= 1.0 + INSIDE)
            elem[todo[ok]], local[todo[ok]] = t[ok], xy[ok]
            k += 1
            todo = todo[~ok & (count[todo] > k)]
        return elem, local


def for_mesh(mesh) -> TriangleSearch:
    """The search of an NGSolve mesh's triangles in its undeformed (reference) coordinates,
    built once per mesh (the last ``KEPT`` meshes are kept)."""
    key = id(mesh)
    hit = _kept.get(key)
    if hit is not None and hit[0] is mesh:
        _kept.move_to_end(key)
        return hit[1]
    from hotroll.fem.mesh import mesh_triangles

    pts = np.asarray(mesh.ngmesh.Coordinates())[:, :2]
    search = TriangleSearch(pts, mesh_triangles(mesh))
    _kept[key] = (mesh, search)
    while len(_kept) > KEPT:
        _kept.popitem(last=False)
    return search


def mesh_points(mesh, x, y, deformation=None) -> np.ndarray:
    """``mesh(x, y)`` (NGSolve's MeshPoint array: evaluate any CF of the mesh on it) for
    points given in the mesh's reference coordinates: NGSolve's own result (module
    docstring); a point outside every triangle has element number -1. ``deformation``: the
    GridFunction the mesh is deformed by, unset for NGSolve's search of the points on edges."""
    x = np.asarray(x, dtype=float).ravel()
    y = np.asarray(y, dtype=float).ravel()
    elem, local = for_mesh(mesh).find(x, y)
    lam = np.stack([local[:, 0], local[:, 1], 1.0 - local[:, 0] - local[:, 1]], -1)
    unclear = np.nonzero((elem < 0) | np.any(lam <= CLEAR, axis=1))[0]
    # the record layout and the mesh's pointer from NGSolve's own search
    if deformation is not None:
        mesh.UnsetDeformation()
    try:
        theirs = find_points(mesh, np.append(x[unclear], 0.0), np.append(y[unclear], 0.0))
    finally:
        if deformation is not None:
            mesh.SetDeformation(deformation)
    out = np.zeros(len(elem), dtype=theirs.dtype)
    out["x"], out["y"] = local[:, 0], local[:, 1]
    out["meshptr"] = theirs["meshptr"][-1]
    out["nr"] = elem
    out["VorB"] = theirs["VorB"][-1]
    out["facetnr"] = -1
    out[unclear] = theirs[:-1]
    return out
