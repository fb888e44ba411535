"""The 3D strip's mesh: a 2D strip mesh in (x, y) extruded along the width z in prism layers
(issue 53; ../shared/notes/3d-steady.md: an extruded mesh is 1.3-2.5x fewer Taylor-Hood
unknowns than an isotropic tetrahedral one on a roughing pass, and it keeps the 2D mesh's
grading towards the roll).

Axes: x along the strip, y through the thickness (the 2D model's), z across the width, z = 0
the mid-width plane of a quarter model. Each 2D triangle (counter-clockwise in (x, y)) gives
one prism per layer [z_k, z_k+1]; each 2D boundary segment one quadrilateral per layer, named
as the segment was (``sym``, ``arc``, ``top``, ``in``, ...). The two new faces: ``zsym`` at
z = z_0 (the mid-width symmetry plane) and ``edge`` at z = z_n (the strip's lateral face).
Lines (BBND): the contact's ``start`` across the layers (the 2D mesh's named point) and
``arc_edge``, where the arc meets ``edge`` (the elastic layer's line terms,
``RollingForm3D.layer_ends``).
The layers (``width_axis``) are thin at the free edge, where the spread and the edge's bulge
form, and grow towards mid-width, where the strip is nearly in plane strain.
"""
from __future__ import annotations

import numpy as np

from hotroll.fem.mesh import mesh_triangles
from hotroll.fem.reproducible import fe_space
from hotroll.fem.spaces import BUBBLE_MID

#: layer-to-layer growth from the free edge towards mid-width (3d-steady.md: 1.2)
WIDTH_GROWTH = 1.2
#: the line where the contact meets the lateral face (the arc's segments in the last layer)
ARC_EDGE = "arc_edge"


def width_axis(half_width: float, edge: float, growth: float = WIDTH_GROWTH,
               largest: float | None = None) -> np.ndarray:
    """z nodes from 0 (mid-width) to ``half_width`` (m): the layer at the free edge ``edge``
    thick, each next one towards mid-width ``growth`` times thicker, up to ``largest`` (default
    no limit); the last (innermost) layer takes what is left, at least half a layer."""
    if not 0.0 < edge <= half_width:
        raise ValueError(f"width layers: need 0 < edge ({edge!r} m) <= half width "
                         f"({half_width!r} m)")
    if not growth >= 1.0:
        raise ValueError(f"width layers: growth ({growth!r}) must be >= 1")
    largest = half_width if largest is None else max(float(largest), edge)
    z, s = [half_width], edge
    while z[-1] - s > 0.5 * s:
        z.append(z[-1] - s)
        s = min(s * growth, largest)
    z.append(0.0)
    return np.array(z[::-1])


def extrude(mesh2d, z: np.ndarray, region: str = "strip"):
    """The prism mesh of ``mesh2d`` (an NGSolve 2D mesh in (x, y), straight-sided) through the
    layers ``z`` (increasing): vertex i of the 2D mesh in layer k is vertex k * nv + i. Returns
    an NGSolve mesh (module docstring for its boundaries)."""
    import ngsolve
    from netgen.meshing import Mesh as NetgenMesh

    z = np.asarray(z, dtype=float)
    if len(z) < 2 or np.any(np.diff(z) <= 0.0):
        raise ValueError("extrude: the layers' z must increase (at least two)")
    ng2 = mesh2d.ngmesh
    P = np.asarray(ng2.Coordinates())[:, :2]
    nv, nl = len(P), len(z) - 1
    if nv != mesh2d.nv:
        raise ValueError(f"extrude: the 2D mesh has {nv} points but {mesh2d.nv} vertices "
                         "(a curved, second-order mesh): extrude its straight-sided one")
    tri = mesh_triangles(mesh2d).astype(np.int64)
    seg = ng2.Elements1D().NumPy()
    seg_nodes = np.asarray(seg["nodes"][:, :2], dtype=np.int64) - 1
    seg_index = np.asarray(seg["index"], dtype=np.int64)
    ng = NetgenMesh(dim=3)
    pts = np.concatenate([np.tile(P, (nl + 1, 1)), np.repeat(z, nv)[:, None]], axis=1)
    ng.AddPoints(pts)
    dom = ng.AddRegion(region, dim=3)
    layer = (np.arange(nl) * nv)[:, None, None]
    prisms = np.concatenate([tri[None] + layer, tri[None] + layer + nv], axis=2).reshape(-1, 6)
    ng.AddElements(dim=3, index=dom, base=0, data=prisms.astype(np.int32))
    # the end faces: outward normal -z at z_0 (clockwise seen from +z), +z at z_n
    for name, faces in (("zsym", tri[:, ::-1]), ("edge", tri + nl * nv)):
        ng.AddElements(dim=2, index=ng.AddRegion(name, dim=2), base=0,
                       data=faces.astype(np.int32))
    # the 2D boundary's segments (a, b), outward normal on the right of a -> b: quads
    # (a, b, b', a') with a' = a one layer up
    for idx in np.unique(seg_index):
        name = ng2.GetBCName(int(idx) - 1)
        ab = seg_nodes[seg_index == idx]
        quads = np.concatenate([ab[None] + layer, ab[None, :, ::-1] + layer + nv],
                               axis=2).reshape(-1, 4)
        ng.AddElements(dim=2, index=ng.AddRegion(name, dim=2), base=0,
                       data=quads.astype(np.int32))
    # the 2D mesh's named points (the contact's start, ``mesh.strip_face``): lines across the
    # layers (BBND edges of the same name)
    from ngsolve import BBND

    for el in mesh2d.Elements(BBND):
        if el.mat == "start":
            v = el.vertices[0].nr
            lines = np.stack([np.arange(nl) * nv + v, np.arange(1, nl + 1) * nv + v], axis=1)
            ng.AddElements(dim=1, index=ng.AddRegion(el.mat, dim=1), base=0,
                           data=lines.astype(np.int32))
    # ... and the contact's lateral edge, where the arc meets the lateral face ``edge``: the
    # arc's segments in the last layer (``RollingForm3D.layer_ends``)
    arc = [idx for idx in np.unique(seg_index) if ng2.GetBCName(int(idx) - 1) == "arc"]
    if arc:
        ab = seg_nodes[np.isin(seg_index, arc)] + nl * nv
        ng.AddElements(dim=1, index=ng.AddRegion(ARC_EDGE, dim=1), base=0,
                       data=ab.astype(np.int32))
    return ngsolve.Mesh(ng)


class LayerCopy:
    """Fields of the 2D mesh carried onto its extrusion and back: a 3D field the same in every
    layer (``copy``, ``vector``; ``scale`` per layer: a field linear in z along each spine), and
    one layer of a 3D field read as a 2D one (``take``). The 3D field's vertex DOFs and the DOFs
    of the edges inside a layer are the 2D vertex's and edge's; the DOFs of the edges across a
    layer and of the quadrilateral faces are zero (constant, or linear, along z). Exact for H1
    of order <= 2: a prism's shape functions of a layer's vertex or edge are the triangle's
    times the layer's linear hat in z."""

    def __init__(self, mesh2d, mesh3d):
        from ngsolve import EDGE, VERTEX, NodeId

        nv = mesh2d.nv
        if mesh3d.nv % nv:
            raise ValueError(f"LayerCopy: {mesh3d.nv} 3D vertices are not layers of the 2D "
                             f"mesh's {nv}")
        self.nv2, self.layers = nv, mesh3d.nv // nv - 1
        #: the 2D mesh's edges by their (sorted) vertex numbers
        self._flat = flat = {tuple(sorted(v.nr for v in e.vertices)): e.nr
                             for e in mesh2d.edges}
        self._mesh3 = mesh3d
        #: (layer, 3D node, 2D node) of every vertex and every edge inside a layer
        self.nodes = [(v // nv, NodeId(VERTEX, v), NodeId(VERTEX, v % nv))
                      for v in range(mesh3d.nv)]
        for e in mesh3d.edges:
            a, b = sorted(v.nr for v in e.vertices)
            if a // nv == b // nv:
                self.nodes.append((a // nv, NodeId(EDGE, e.nr),
                                   NodeId(EDGE, flat[(a % nv, b % nv)])))
        self._cache: dict = {}

    def indices(self, space2d, space3d) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(layer, 3D DOF, 2D DOF) arrays of the scalar spaces' matching DOFs (cached)."""
        return self._rows((id(space2d), id(space3d)), lambda: self.nodes, space2d, space3d)

    def _rows(self, key, nodes, space2d, space3d):
        """(layer, 3D DOF, 2D DOF) of the matching DOFs of the (layer, 3D node, 2D node)
        triples ``nodes()``, cached under ``key`` (the spaces are kept with them: their ids
        stay theirs)."""
        hit = self._cache.get(key)
        if hit is None:
            rows = [(k, a, b) for k, n3, n2 in nodes()
                    for a, b in zip(space3d.GetDofNrs(n3), space2d.GetDofNrs(n2))
                    if a >= 0 and b >= 0]
            arr = np.array(rows, dtype=np.int64).reshape(-1, 3)
            hit = self._cache[key] = (arr[:, 0], arr[:, 1], arr[:, 2], space2d, space3d)
        return hit[:3]

    def copy(self, space2d, vec2d, space3d, vec3d, scale=None) -> None:
        """vec3d (numpy, of the scalar ``space3d``) = vec2d (of ``space2d``) in every layer,
        times ``scale[layer]`` if given; zero elsewhere."""
        layer, d3, d2 = self.indices(space2d, space3d)
        vec3d[:] = 0.0
        vec3d[d3] = vec2d[d2] if scale is None else np.asarray(scale)[layer] * vec2d[d2]

    def per_layer(self, space2d, vecs2d, space3d, vec3d, z=None, where=None,
                  flat: int = 0) -> None:
        """vec3d = a 2D field of its own in each layer (``vecs2d``: one vector of ``space2d``
        per layer, z_0 first), linear in z between two layers; zero elsewhere (a field whose
        shape changes across the width: the contact and the top per layer, issue 53 stage 3).
        With the layers' ``z``: quadratic in z inside each layer instead (``spine_bubbles``),
        at the 2D DOFs ``where`` (a mask; default all), the first ``flat`` layers linear."""
        layer, d3, d2 = self.indices(space2d, space3d)
        stack = np.asarray(vecs2d, dtype=float)
        if stack.shape[0] != self.layers + 1:
            raise ValueError(f"LayerCopy.per_layer: {stack.shape[0]} fields for "
                             f"{self.layers + 1} layers")
        vec3d[:] = 0.0
        vec3d[d3] = stack[layer, d2]
        if z is not None and self.layers > 1:
            layer, d3, d2 = self.spine_indices(space2d, space3d)
            bubbles = spine_bubbles(np.asarray(z, dtype=float), stack, flat)
            if where is not None:
                bubbles[:, ~np.asarray(where, dtype=bool)] = 0.0
            vec3d[d3] = bubbles[layer, d2]

    def spine_indices(self, space2d, space3d) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(layer, 3D DOF, 2D DOF) of the DOFs across a layer: an edge across layer k above
        a 2D vertex, a quadrilateral face of layer k above a 2D edge (cached)."""
        from ngsolve import EDGE, FACE, VERTEX, NodeId

        def nodes():
            nv, out = self.nv2, []
            for e in self._mesh3.edges:
                a, b = sorted(v.nr for v in e.vertices)
                if b - a == nv:
                    out.append((a // nv, NodeId(EDGE, e.nr), NodeId(VERTEX, a % nv)))
            for f in self._mesh3.faces:
                vs = sorted(v.nr for v in f.vertices)
                if len(vs) == 4:
                    out.append((vs[0] // nv, NodeId(FACE, f.nr),
                                NodeId(EDGE, self._flat[(vs[0] % nv, vs[1] % nv)])))
            return out

        return self._rows(("spine", id(space2d), id(space3d)), nodes, space2d, space3d)

    def take(self, layer: int, space3d, vec3d, space2d, vec2d) -> None:
        """vec2d = the 3D field's values in ``layer`` (its nodes' DOFs)."""
        k, d3, d2 = self.indices(space2d, space3d)
        on = k == layer
        vec2d[d2[on]] = vec3d[d3[on]]

    def take_vector(self, layer: int, gf3d, space2d, vec2d: np.ndarray, ncomp: int) -> None:
        """The first ``ncomp`` components of a 3D VectorH1 GridFunction in ``layer`` into
        ``vec2d`` (the blocks of ``ncomp`` copies of the scalar ``space2d``)."""
        s3, n2 = gf3d.space, space2d.ndof
        n3 = s3.ndof // 3
        v3 = gf3d.vec.FV().NumPy()
        for c in range(ncomp):
            self.take(layer, s3.components[c], v3[c * n3:(c + 1) * n3], space2d,
                      vec2d[c * n2:(c + 1) * n2])

    def elements(self, vec2d: np.ndarray) -> np.ndarray:
        """One value per 2D triangle onto its prisms (an L2 field of order 0): prism
        k * n_triangles + t is triangle t's in layer k (``extrude``'s order)."""
        return np.tile(np.asarray(vec2d, dtype=float), self.layers)

    def scalar(self, gf2d):
        """A new 3D GridFunction equal to the scalar 2D one ``gf2d`` in every layer: H1 of
        order <= 2 (``copy``) or L2 of order 0 (``elements``)."""
        import ngsolve as ng

        space, v2 = gf2d.space, gf2d.vec.FV().NumPy()
        order = space.globalorder
        if isinstance(space, ng.L2) and order == 0:
            out = ng.GridFunction(fe_space(ng.L2, self._mesh3, order=0))
            out.vec.FV().NumPy()[:] = self.elements(v2)
        elif isinstance(space, ng.H1) and order <= 2:
            out = ng.GridFunction(fe_space(ng.H1, self._mesh3, order=order))
            self.copy(space, v2, out.space, out.vec.FV().NumPy())
        else:
            raise ValueError(f"LayerCopy.scalar: {type(space).__name__} of order {order} "
                             "(H1 of order <= 2 or L2 of order 0)")
        return out

    def vector(self, gf2d, gf3d) -> None:
        """A 2D VectorH1 GridFunction (x, y) onto a 3D one (x, y, 0)."""
        s2, s3 = gf2d.space, gf3d.space
        n2, n3 = s2.ndof // 2, s3.ndof // 3
        v2, v3 = gf2d.vec.FV().NumPy(), gf3d.vec.FV().NumPy()
        v3[2 * n3:] = 0.0
        for c in range(2):
            self.copy(s2.components[c], v2[c * n2:(c + 1) * n2], s3.components[c],
                      v3[c * n3:(c + 1) * n3])

    def facets(self, space2d, vec2d, space3d, vec3d) -> None:
        """A facet field of order 0 (one value per edge, as the contact indicator chi) onto
        the extrusion: every quadrilateral boundary face takes the value of the 2D boundary
        edge it is extruded from; every other face 0."""
        from ngsolve import BND, EDGE, NodeId

        nv = self.nv2
        vec3d[:] = 0.0
        for el in self._mesh3.Elements(BND):
            vs = sorted(v.nr for v in el.vertices)
            low = [v % nv for v in vs if v // nv == vs[0] // nv]
            if len(vs) == 4 and len(low) == 2:
                edge = NodeId(EDGE, self._flat[tuple(sorted(low))])
                vec3d[space3d.GetDofNrs(el)[0]] = vec2d[space2d.GetDofNrs(edge)[0]]


#: a trio of levels gives a layer's midpoint only where the sum of its quadratic's weights'
#: magnitudes there stays below this (1.25 at equal spacing, 1.67 beside a layer twice as
#: wide): a layer much wider than its neighbours (an edge zone's interior) is not given the
#: neighbours' gradient extrapolated across it
WEIGHT_LIMIT = 2.0


def spine_bubbles(z: np.ndarray, values: np.ndarray, flat: int = 0) -> np.ndarray:
    """The across-layer bubble coefficients (one row per layer) that make fields given per
    layer (``values``: one row per z) quadratic in z inside each layer, through the value at
    the layer's midpoint that the quadratics through three neighbouring layers give (the mean
    of those that exist and keep their weights' magnitudes below ``WEIGHT_LIMIT``: at equal
    spacing the cubic's; none: linear in the layer). The bubble of an edge across a layer is
    NGSolve's order-2 edge bubble (``BUBBLE_MID`` at its midpoint), that of a quadrilateral
    face the product of its two edges' bubbles. The first ``flat`` layers stay linear (an edge
    zone's interior, uniform across the width)."""
    n = len(z) - 1
    out = np.zeros((n,) + values.shape[1:])
    for k in range(flat, n):
        zm, mids = 0.5 * (z[k] + z[k + 1]), []
        for trio in ((k - 1, k, k + 1), (k, k + 1, k + 2)):
            if trio[0] < 0 or trio[2] > n:
                continue
            w = [np.prod([(zm - z[j]) / (z[i] - z[j]) for j in trio if j != i]) for i in trio]
            if sum(abs(wi) for wi in w) <= WEIGHT_LIMIT:
                mids.append(sum(wi * values[i] for wi, i in zip(w, trio)))
        if mids:
            out[k] = (sum(mids) / len(mids) - 0.5 * (values[k] + values[k + 1])) / BUBBLE_MID
    return out
