"""Netgen mesh of the half plate in its initial, maximum-contact configuration (report Fig. 2a).

The plate occupies x in [axis_x - L, axis_x], y in [0, half_entry]; its top follows the roll arc
exactly for x in [x_touch, axis_x]. Boundary names:
``sym`` (y = 0), ``out`` (head face), ``arc`` (initial contact), ``top`` (free top), ``in`` (tail).
The mesh size is ``h`` on the top boundary and the arc over a fine zone upstream of the roll,
growing through the thickness to ``core_factor * h`` on the axis and to ``h_far`` far upstream.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..process.geometry import RollPass

BOUNDARIES = ("sym", "out", "arc", "top", "in")


@dataclass(frozen=True)
class MeshSpec:
    h: float                    # mesh size at the contact (Table 2)
    fine_length: float          # length of the fine zone upstream of the exit, m
    h_far: float | None = None  # size far from the roll (None: automatic)
    core_factor: float = 2.0    # size on the symmetry axis relative to h
    grading: float = 0.3

    def far(self, rp: RollPass) -> float:
        return self.h_far if self.h_far else min(rp.half_entry / 4.0, 15.0 * self.h)


def plate_geometry(rp: RollPass, length: float):
    """OCC face of the initial plate with named edges."""
    from netgen.occ import ArcOfCircle, Face, OCCGeometry, Pnt, Segment, Wire

    x0, x1 = rp.axis_x - length, rp.axis_x
    cx, cy = rp.centre
    xt, h0, h1, R = rp.x_touch, rp.half_entry, rp.half_exit, rp.radius
    a0, a1 = -math.pi / 2, math.atan2(h0 - cy, xt - cx)
    am = 0.5 * (a0 + a1)
    edges = [
        Segment(Pnt(x0, 0, 0), Pnt(x1, 0, 0)),
        Segment(Pnt(x1, 0, 0), Pnt(x1, h1, 0)),
        ArcOfCircle(Pnt(x1, h1, 0), Pnt(cx + R * math.cos(am), cy + R * math.sin(am), 0),
                    Pnt(xt, h0, 0)),
        Segment(Pnt(xt, h0, 0), Pnt(x0, h0, 0)),
        Segment(Pnt(x0, h0, 0), Pnt(x0, 0, 0)),
    ]
    face = Face(Wire(edges))
    # name the edges of the face itself (names on the input segments are not kept)
    for ed in face.edges:
        c = ed.center
        if abs(c.y) < 1e-12 * max(1.0, length):
            ed.name = "sym"
        elif abs(c.x - x1) < 1e-9 * length and c.y < h1 + 1e-12:
            ed.name = "out"
        elif abs(c.x - x0) < 1e-9 * length:
            ed.name = "in"
        elif abs(c.y - h0) < 1e-12 * max(1.0, h0):
            ed.name = "top"
        else:
            ed.name = "arc"
    return OCCGeometry(face, dim=2)


def top_height(rp: RollPass, x: np.ndarray) -> np.ndarray:
    """Initial height of the top boundary: flat, then the roll arc."""
    cx, cy = rp.centre
    x = np.asarray(x, dtype=float)
    on_arc = x > rp.x_touch
    y = np.full_like(x, rp.half_entry)
    y[on_arc] = cy - np.sqrt(np.maximum(rp.radius**2 - (x[on_arc] - cx) ** 2, 0.0))
    return y


def build_plate_mesh(rp: RollPass, length: float, spec: MeshSpec):
    """Generate the graded NGSolve mesh (straight-sided; the arc is restored by the P2 geometry)."""
    import ngsolve
    from netgen.meshing import MeshingParameters

    h = spec.h
    mp = MeshingParameters(maxh=spec.far(rp), grading=spec.grading)
    x_lo = max(rp.axis_x - length, rp.axis_x - spec.fine_length)
    xs = np.arange(x_lo, rp.axis_x + 0.5 * h, 0.5 * h)
    ytop = top_height(rp, xs)
    hc = spec.core_factor * h
    for x, yt in zip(xs, ytop):
        # size grows linearly from h at the top to core_factor*h on the axis
        n = max(2, int(math.ceil(yt / h)))
        for y in np.linspace(yt, 0.0, n):
            mp.RestrictH(float(x), float(y), 0.0, float(h + (hc - h) * (1.0 - y / yt)))
    ngmesh = plate_geometry(rp, length).GenerateMesh(mp=mp)
    return ngsolve.Mesh(ngmesh)
