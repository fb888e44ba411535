"""The full-thickness steady strip between two rolls (issue 52): its mesh and its map onto the
two free surfaces.

The strip is the upper roll's half strip (``mesh.strip_face``, y >= 0) glued along y = 0 to
the lower roll's, mirrored (y <= 0): each half is the half model's strip of its own roll, in
the roll's own frame (``RollPass``: centre above, y -> -y for the lower). Boundaries: ``arc``,
``top``, ``exit`` (upper roll side), ``arcl``, ``topl``, ``exitl`` (lower), ``in``, ``out``;
``sym`` is the interior line y = 0 where the halves meet (no condition on it). Both arcs end
at the same x (the roll axes on one vertical line, the exit mid-plane at y = 0); both begin at
their own touching point: with the pass line of the draft split (``model/roll_gap.py``) these
coincide to first order in the bite angle.

``FullStripMap`` maps the reference mesh onto two ``StripShape``s, one per side, each in its
roll's frame: every node of a half moves as the half model's map moves it (``StripMap``), with
the x-stretch blended through the thickness from the mean of the two sides' at y = 0 to the
side's own at its surface (the two contacts start at different x when the rolls differ). Both
halves' reference is the reference roll's half strip (``build_full_mesh``); each side's map
puts its arc on its own roll (``StripMap.roll``) from its contact start to its end.
"""
from __future__ import annotations

import numpy as np

from hotroll.fem.free_surface import StripMap, StripShape
from hotroll.fem.mesh import MeshSpec, build_steady_mesh
from hotroll.model.geometry import RollPass

#: the region suffix of each side: +1 upper roll, -1 lower roll
SUFFIX = {1: "", -1: "l"}


def build_full_mesh(reference: RollPass, upstream: float, downstream: float, spec: MeshSpec,
                    margin: float):
    """The full strip's reference mesh: the half strip's mesh of the ``reference`` roll
    (``mesh.build_steady_mesh``, its points and triangles unchanged) and its mirror image in
    y = 0, the points on y = 0 shared. The lower side's boundaries are the upper's with the
    suffix ``l``; ``sym`` becomes the interior line y = 0. Exactly mirror-symmetric: two equal
    rolls give the half model's answer to the solver's tolerance, and swapping the rolls of an
    asymmetric pass mirrors every figure to round-off (the reference roll is chosen by the
    gap, not by its side: ``reference_roll``)."""
    import ngsolve
    from netgen.meshing import Mesh as NetgenMesh

    half = build_steady_mesh(reference, upstream, downstream, spec, margin).ngmesh
    P = half.Coordinates()
    tri = np.asarray(half.Elements2D().NumPy()["nodes"][:, :3], dtype=np.int64) - 1
    seg = half.Elements1D().NumPy()
    seg_nodes = np.asarray(seg["nodes"][:, :2], dtype=np.int64) - 1
    seg_names = [half.GetBCName(int(i) - 1) for i in seg["index"]]
    on_axis = np.abs(P[:, 1]) <= 1e-14 * max(1.0, float(np.ptp(P[:, 0])))
    # the mirror's point numbers: the axis points shared, the others appended
    mirror = np.arange(len(P))
    off = np.flatnonzero(~on_axis)
    mirror[off] = len(P) + np.arange(len(off))
    points = np.concatenate([P, P[off] * np.array([1.0, -1.0])])
    ng = NetgenMesh(dim=2)
    ng.AddPoints(np.concatenate([points, np.zeros((len(points), 1))], axis=1))
    dom = ng.AddRegion("strip", dim=2)
    # the mirrored triangles reversed (kept counter-clockwise)
    tris = np.concatenate([tri, mirror[tri][:, ::-1]])
    ng.AddElements(dim=2, index=dom, base=0, data=tris.astype(np.int32))
    names: dict[str, int] = {}
    for name, (a, b) in zip(seg_names, seg_nodes):
        pairs = [(name, (a, b))]
        if name != "sym":
            low = name if name in ("in", "out") else name + SUFFIX[-1]
            pairs.append((low, (mirror[b], mirror[a])))
        for nm, ab in pairs:
            if nm not in names:
                names[nm] = ng.AddRegion(nm, dim=1)
            ng.AddElements(dim=1, index=names[nm], base=0,
                           data=np.array([ab], dtype=np.int32))
    # the contacts' starts, named points (``mesh.strip_face``): where the arc meets the top
    from netgen.meshing import Element0D, PointId

    ends = {nm: set(ab.tolist()) for nm in ("arc", "top")
            for ab in [seg_nodes[[n == nm for n in seg_names]].ravel()]}
    start = sorted(ends["arc"] & ends["top"])
    for k, (name, v) in enumerate([("start", start[0]), ("start" + SUFFIX[-1], mirror[start[0]])]):
        ng.SetCD2Name(k + 1, name)
        ng.Add(Element0D(PointId(int(v) + 1), index=k + 1))
    return ngsolve.Mesh(ng)


class FullStripMap:
    """The reference full strip's P2 nodes mapped onto one ``StripShape`` per side."""

    def __init__(self, reference: RollPass, rolls: dict[int, RollPass], mesh, n_scalar: int,
                 d_ref: np.ndarray, x_in: float):
        self.maps = {}
        for side, roll in rolls.items():
            m = StripMap(reference, mesh, n_scalar, d_ref, x_in)
            if side < 0:
                m.P = m.P * np.array([1.0, -1.0])        # the lower roll's own frame
            m.roll = roll
            self.maps[side] = m
        y = self.maps[1].P[:, 1]
        self.side = np.where(y > 0.0, 1, np.where(y < 0.0, -1, 0))
        self.nodes = self.maps[1].nodes

    def x_bounds(self, side: int) -> tuple[float, float]:
        return self.maps[side].x_bounds()

    def end_bounds(self, side: int, past_gap: float = 0.0) -> tuple[float, float]:
        return self.maps[side].end_bounds(past_gap)

    def displacement(self, shapes: dict[int, StripShape]) -> np.ndarray:
        """Coefficient vector of the P2 displacement onto ``shapes`` ({+1: upper, -1: lower})."""
        pos = {s: m.positions(shapes[s]) for s, m in self.maps.items()}
        pos[-1][:, 1] *= -1.0
        x_mid = 0.5 * (pos[1][:, 0] + pos[-1][:, 0])
        new = np.empty_like(pos[1])
        for s, m in self.maps.items():
            on = self.side == s
            w = np.clip(m.P[on, 1] / m.H_ref[on], 0.0, 1.0)
            new[on, 0] = x_mid[on] + w * (pos[s][on, 0] - x_mid[on])
            new[on, 1] = pos[s][on, 1]
        mid = self.side == 0
        new[mid] = np.stack([x_mid[mid], np.zeros(int(mid.sum()))], axis=1)
        return self.nodes.coefficients((new - self.nodes.X0).T)
