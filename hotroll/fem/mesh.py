"""Netgen mesh of the half plate in its initial, maximum-contact configuration (report Fig. 2a).

The plate occupies x in [axis_x - L, axis_x], y in [0, half_entry]; its top follows the roll arc
exactly for x in [x_touch, axis_x]. Boundary names:
``sym`` (y = 0), ``out`` (head face), ``arc`` (initial contact), ``top`` (free top), ``in`` (tail).
The steady strip (``steady_geometry``) adds ``exit``, the flat free top after the roll gap.
The mesh size is ``h`` on the top boundary and the arc over a fine zone upstream of the roll,
growing through the thickness to ``core_factor * h`` on the axis and to ``h_far`` far upstream.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from hotroll.fem.reproducible import parallel
from hotroll.model.geometry import RollPass

BOUNDARIES = ("sym", "out", "arc", "top", "in", "exit")


@dataclass(frozen=True)
class MeshSpec:
    h: float                    # mesh size at the contact (Table 2)
    fine_length: float          # length of the fine zone upstream of the exit, m
    h_far: float | None = None  # size far from the roll (None: automatic)
    core_factor: float = 2.0    # size on the symmetry axis relative to h
    grading: float = 0.3
    corner: float = 1.0         # h / the size at the contact's start (the steady strip's:
                                # ``_refine_corner``)

    def far(self, rp: RollPass) -> float:
        return self.h_far if self.h_far else min(rp.half_entry / 4.0, 15.0 * self.h)


def plate_geometry(rp: RollPass, length: float):
    """OCC face of the initial plate with named edges: the strip ending at the roll gap."""
    return _strip_geometry(rp, rp.axis_x - length, rp.axis_x)


def top_height(rp: RollPass, x: np.ndarray) -> np.ndarray:
    """Height of the top boundary in the maximum-contact shape: flat, the roll arc, flat."""
    x = np.asarray(x, dtype=float)
    on_arc = (x > rp.x_touch) & (x < rp.axis_x)
    y = np.where(x >= rp.axis_x, rp.half_exit, rp.half_entry)
    y[on_arc] = rp.height(x[on_arc])
    return y


def steady_geometry(rp: RollPass, upstream: float, downstream: float):
    """OCC face of the steady strip: flat entry of length ``upstream`` before the touching
    point, the full roll arc, flat exit at the roll gap of length ``downstream``."""
    return _strip_geometry(rp, rp.x_touch - upstream, rp.axis_x + downstream)


def _strip_geometry(rp: RollPass, x0: float, x1: float):
    """OCC face from x0 to x1 >= X_roll: flat at the entry half-thickness up to the touching
    point, the roll arc down to the gap at X_roll, flat at the gap after it (none if x1 = X_roll).

    Edges named ``sym`` (y = 0), ``in`` (x = x0), ``out`` (x = x1), ``top`` (flat entry),
    ``arc`` and ``exit`` (flat top after the gap).
    """
    from netgen.occ import OCCGeometry

    return OCCGeometry(strip_face(rp, x0, x1), dim=2)


def strip_face(rp: RollPass, x0: float, x1: float, side: int = 1, suffix: str = ""):
    """The OCC face of ``_strip_geometry``; ``side`` = -1: mirrored to y <= 0 (the lower roll's
    half of a full-thickness strip, ``rp`` that roll's pass in its own frame), its roll-side
    edges named with ``suffix`` (``arc`` + suffix, ...) and its y = 0 edge ``sym``."""
    from netgen.occ import ArcOfCircle, Face, Pnt, Segment, SplineInterpolation, Wire

    cx, cy = rp.centre
    xt, h0, h1, R = rp.x_touch, rp.half_entry, rp.half_exit, rp.radius
    am = 0.5 * (-math.pi / 2 + math.atan2(h0 - cy, xt - cx))
    gap = [(x1, h1)] + ([(rp.axis_x, h1)] if x1 > rp.axis_x else [])
    pts = [(x0, 0), (x1, 0), *gap, (xt, h0), (x0, h0)]
    if side < 0:        # mirrored, and reversed to keep the wire counter-clockwise
        pts = [(x, -y) for x, y in reversed(pts)]
    P = [Pnt(x, y, 0) for x, y in pts]
    arc = len(P) - 3 if side > 0 else 1     # between the gap point at X_roll and the touch
    if rp.shape is None:
        roll = ArcOfCircle(P[arc], Pnt(cx + R * math.cos(am), side * (cy + R * math.sin(am)), 0),
                           P[arc + 1])
    else:       # a flattened roll: a spline through its surface from the gap to the touch
        xs = rp.axis_x + (xt - rp.axis_x) * np.linspace(0.0, 1.0, 41)
        ys = rp.height(xs)
        ys[0], ys[-1] = h1, h0
        if side < 0:
            xs, ys = xs[::-1], -ys[::-1]
        roll = SplineInterpolation([Pnt(float(a), float(b), 0) for a, b in zip(xs, ys)])
    edges = [roll if i == arc else Segment(P[i], P[(i + 1) % len(P)]) for i in range(len(P))]
    face = Face(Wire(edges))
    # name the edges of the face itself (names on the input segments are not kept)
    scale = max(1.0, x1 - x0)
    for ed in face.edges:
        c = ed.center
        if abs(c.y) < 1e-12 * scale:
            ed.name = "sym"
        elif abs(c.x - x1) < 1e-9 * scale:
            ed.name = "out"
        elif abs(c.x - x0) < 1e-9 * scale:
            ed.name = "in"
        elif c.x > rp.axis_x:
            ed.name = "exit" + suffix
        elif abs(side * c.y - h0) < 1e-12 * max(1.0, h0):
            ed.name = "top" + suffix
        else:
            ed.name = "arc" + suffix
    # the contact's start as a named point (a BBND element), where the strip's elastic layer
    # is compressed at once (``RollingForm.constraint``)
    for vx in face.vertices:
        p = vx.p
        if abs(p.x - xt) < 1e-9 * scale and abs(side * p.y - h0) < 1e-12 * max(1.0, h0):
            vx.name = "start" + suffix
    return face


def _graded_mesh(geometry, rp: RollPass, spec: MeshSpec, x_lo: float, x_hi: float,
                 shift: float = 0.0, corner: float = 1.0):
    """Mesh ``geometry`` with size h on the top over [x_lo, x_hi], growing to
    ``core_factor * h`` on the axis and to ``spec.far`` elsewhere; then move it by ``shift``
    in x (the geometry is meshed in the roll's frame, so the mesh does not depend on where
    the case puts the roll axis); ``corner``: h / the size at the touching point
    (``_refine_corner``)."""
    import ngsolve
    from netgen.meshing import MeshingParameters

    h = spec.h
    mp = MeshingParameters(maxh=spec.far(rp), grading=spec.grading)
    xs = np.arange(x_lo, x_hi + 0.5 * h, 0.5 * h)
    hc = spec.core_factor * h
    for x, yt in zip(xs, top_height(rp, xs)):
        # size grows linearly from h at the top to core_factor*h on the axis
        n = max(2, int(math.ceil(yt / h)))
        for y in np.linspace(yt, 0.0, n):
            mp.RestrictH(float(x), float(y), 0.0, float(h + (hc - h) * (1.0 - y / yt)))
    _refine_corner(mp, rp, h, corner)
    with parallel():            # netgen's optimisation threaded: the same mesh to the bit
        ngmesh = geometry.GenerateMesh(mp=mp)
    if shift:
        ngmesh.Coordinates()[:, 0] += shift     # a view on netgen's points
    return ngsolve.Mesh(ngmesh)


def _refine_corner(mp, rp: RollPass, h: float, ratio: float) -> None:
    """Mesh size h / ``ratio`` at the contact's start (the touching point x_touch on the entry
    top), graded back to h by netgen's grading: the flow turns onto the roll there within the
    first element (the velocity's corner singularity), and the traced free top leaks mass
    through that element in proportion to its size (docs/theory.md 4e)."""
    if ratio > 1.0:
        mp.RestrictH(float(rp.x_touch), float(rp.half_entry), 0.0, float(h / ratio))


def _in_roll_frame(rp: RollPass) -> RollPass:
    """The same pass with the roll axis at x = 0."""
    return replace(rp, axis_x=0.0)


def plate_fine_length(rp: RollPass, h: float, end_time: float) -> float:
    """The report's scheme: the fine zone upstream of the gap, the contact length, what the
    roll surface travels until ``end_time`` and 6h."""
    return rp.contact_length + rp.u_roll * end_time + 6 * h


def plate_zone(rp: RollPass, length: float, fine_length: float) -> tuple[float, float, float,
                                                                          float]:
    """(x0, x1, fine from, fine to) of the initial plate's mesh."""
    x0, x1 = rp.axis_x - length, rp.axis_x
    return x0, x1, max(x0, x1 - fine_length), x1


def steady_zone(rp: RollPass, upstream: float, downstream: float,
                margin: float) -> tuple[float, float, float, float]:
    """(x0, x1, fine from, fine to) of the steady strip's mesh: fine over the arc and
    ``margin`` either side of it."""
    x0, x1 = rp.x_touch - upstream, rp.axis_x + downstream
    return x0, x1, max(x0, rp.x_touch - margin), min(x1, rp.axis_x + margin)


def build_plate_mesh(rp: RollPass, length: float, spec: MeshSpec):
    """Generate the graded NGSolve mesh (straight-sided; the arc is restored by the P2 geometry)."""
    r0 = _in_roll_frame(rp)
    _, _, x_lo, x_hi = plate_zone(r0, length, spec.fine_length)
    # (no refinement at the touching point: the transient plate's contact start moves)
    return _graded_mesh(plate_geometry(r0, length), r0, spec, x_lo, x_hi, shift=rp.axis_x)


#: The last steady meshes made, by what they are made from (``build_steady_mesh``).
_STEADY_MESHES: dict = {}
_KEEP_MESHES = 4


def build_steady_mesh(rp: RollPass, upstream: float, downstream: float, spec: MeshSpec,
                      margin: float):
    """Graded mesh of the steady strip (``steady_zone``). The same geometry and sizes again (a
    tandem stand solved again at its mass-flow speed, a study's cases at other speeds or
    materials) get a copy of the mesh made last time: netgen meshes the same input to the same
    mesh, in 85 ms on a finishing pass, the copy takes 3 ms."""
    from dataclasses import astuple

    shape = None if rp.shape is None else (rp.shape.theta.tobytes(), rp.shape.w.tobytes())
    key = (rp.radius, rp.half_entry, rp.half_exit, rp.axis_x, shape, upstream, downstream,
           astuple(spec), margin)
    kept = _STEADY_MESHES.get(key)
    if kept is None:
        r0 = _in_roll_frame(rp)
        _, _, x_lo, x_hi = steady_zone(r0, upstream, downstream, margin)
        mesh = _graded_mesh(steady_geometry(r0, upstream, downstream), r0, spec, x_lo, x_hi,
                            shift=rp.axis_x, corner=spec.corner)
        while len(_STEADY_MESHES) >= _KEEP_MESHES:
            _STEADY_MESHES.pop(next(iter(_STEADY_MESHES)))
        kept = _STEADY_MESHES[key] = mesh.ngmesh.Copy()
        return mesh
    import ngsolve

    return ngsolve.Mesh(kept.Copy())


def mesh_triangles(mesh) -> np.ndarray:
    """The triangles of an NGSolve mesh as vertex numbers (ne, 3), in element order (netgen's
    element array; it numbers the points from 1)."""
    nodes = mesh.ngmesh.Elements2D().NumPy()["nodes"][:, :3]
    return np.asarray(nodes, dtype=int) - 1


def structured_triangle_mesh(X: np.ndarray, Y: np.ndarray, mirrored: bool = False):
    """The tensor-product mesh of the axes X (nx+1) and Y (ny+1), each cell split into two
    triangles: the same points, triangles and boundaries ("bottom", "right", "top", "left";
    region "dom") as ``ngsolve.meshes.MakeStructured2DMesh(quads=False)`` with a mapping onto
    the axes, vertex i + j (nx + 1) at (X[i], Y[j]), built from arrays (~15x faster).
    ``mirrored``: the cells below Y = 0 split along the other diagonal, so that a Y axis
    symmetric about 0 gives a mesh that is its own mirror image (the full strip's)."""
    import ngsolve
    from netgen.meshing import Mesh as NetgenMesh

    X, Y = np.asarray(X, dtype=float), np.asarray(Y, dtype=float)
    nx, ny = len(X) - 1, len(Y) - 1
    Xg, Yg = np.meshgrid(X, Y)
    ngmesh = NetgenMesh(dim=2)
    ngmesh.AddPoints(np.stack([Xg.ravel(), Yg.ravel(), np.zeros(Xg.size)], -1))
    dom = ngmesh.AddRegion("dom", dim=2)
    names = ("bottom", "right", "top", "left")
    index = {name: ngmesh.AddRegion(name, dim=1) for name in names}
    col, row = np.meshgrid(np.arange(nx), np.arange(ny))
    base = (row * (nx + 1) + col).ravel()
    lower = np.stack([base, base + 1, base + nx + 1], -1)
    upper = np.stack([base + 1, base + nx + 2, base + nx + 1], -1)
    if mirrored:
        below = (Y[row + 1] <= 0.0).ravel()[:, None]
        lower = np.where(below, np.stack([base, base + 1, base + nx + 2], -1), lower)
        upper = np.where(below, np.stack([base, base + nx + 2, base + nx + 1], -1), upper)
    ngmesh.AddElements(dim=2, index=dom, base=0,
                       data=np.stack([lower, upper], 1).reshape(-1, 3).astype(np.int32))
    i, j = np.arange(nx), np.arange(ny)
    top = ny * (nx + 1)
    segments = {"bottom": (i, i + 1), "right": (j * (nx + 1) + nx, (j + 1) * (nx + 1) + nx),
                "top": (top + i + 1, top + i), "left": ((j + 1) * (nx + 1), j * (nx + 1))}
    for name in names:
        ngmesh.AddElements(dim=1, index=index[name], base=0,
                           data=np.stack(segments[name], -1).astype(np.int32))
    return ngsolve.Mesh(ngmesh)
