"""Top-boundary nodes of the moving plate and contact detection by projection, report (3.9).

The geometry lives in one P2 displacement field ``disp`` (VectorH1, order 2) on the
straight-sided reference mesh: vertex DOFs are nodal displacements, the edge DOF of a P2 edge
is the coefficient of its quadratic bubble, whose value at the edge midpoint is ``BUBBLE_MID``.
So every P2 geometry node (vertices and edge midpoints) can be read and moved exactly.
"""
from __future__ import annotations

import numpy as np

from hotroll.fem.spaces import BUBBLE_MID
from hotroll.model.geometry import RollPass

TOP_REGIONS = ("top", "arc", "exit")


class TopBoundary:
    """Vertices and edges of the plate's top boundary (free surface and contact).

    ``side`` = -1, ``suffix``: the lower surface of a full-thickness strip (regions ``top`` +
    suffix, ...), read and written in its roll's own frame, y -> -y (``mesh.strip_face``), so
    that everything one roll's side does (tracing, contact, the strip map) is the upper's."""

    def __init__(self, mesh, ndof_scalar: int, side: int = 1, suffix: str = ""):
        import ngsolve

        self.nv, self.n_scalar, self.side = mesh.nv, ndof_scalar, side
        names = tuple(r + suffix for r in TOP_REGIONS)
        edges, verts = [], set()
        for el in mesh.Elements(ngsolve.BND):
            if el.mat in names:
                e = el.edges[0].nr
                a, b = (v.nr for v in el.vertices)
                edges.append((e, a, b, names.index(el.mat)))
                verts.update((a, b))
        arr = np.array(sorted(edges), dtype=int)
        self.edge, self.ea, self.eb = arr[:, 0], arr[:, 1], arr[:, 2]
        self.region = np.array(TOP_REGIONS)[arr[:, 3]]          # top / arc / exit per edge
        self.verts = np.array(sorted(verts), dtype=int)
        self.vpos = {v: i for i, v in enumerate(self.verts)}   # vertex nr -> row in verts
        pts = np.array([mesh.vertices[i].point for i in range(mesh.nv)])[:, :2]
        if side < 0:
            pts[:, 1] = -pts[:, 1]
        self.X0 = pts                                           # all reference vertices
        self.M0 = 0.5 * (pts[self.ea] + pts[self.eb])           # reference edge midpoints
        self.vertex_contact = np.zeros(len(self.verts), dtype=bool)
        self.edge_contact = np.zeros(len(self.edge), dtype=bool)

    # --- reading and writing geometry through the displacement vector ----------------------
    def _xy(self, d: np.ndarray, dofs: np.ndarray) -> np.ndarray:
        y = d[self.n_scalar + dofs]
        return np.stack([d[dofs], y if self.side > 0 else -y], axis=-1)

    def vertex_values(self, f: np.ndarray, verts=None) -> np.ndarray:
        """A P2 vector field (coefficient vector ``f``) at top vertices."""
        return self._xy(f, self.verts if verts is None else verts)

    def midpoint_values(self, f: np.ndarray, rows=None) -> np.ndarray:
        """A P2 vector field at the midpoints of top edges ``rows`` (all by default)."""
        rows = slice(None) if rows is None else rows
        ea, eb, e = self.ea[rows], self.eb[rows], self.edge[rows]
        return (0.5 * (self._xy(f, ea) + self._xy(f, eb))
                + BUBBLE_MID * self._xy(f, self.nv + e))

    def vertex_positions(self, d: np.ndarray, verts=None) -> np.ndarray:
        verts = self.verts if verts is None else verts
        return self.X0[verts] + self.vertex_values(d, verts)

    def midpoint_positions(self, d: np.ndarray, rows=None) -> np.ndarray:
        rows = slice(None) if rows is None else rows
        return self.M0[rows] + self.midpoint_values(d, rows)

    def set_vertices(self, d: np.ndarray, verts: np.ndarray, xy: np.ndarray) -> None:
        disp = xy - self.X0[verts]
        d[verts], d[self.n_scalar + verts] = disp[:, 0], self.side * disp[:, 1]

    def set_midpoints(self, d: np.ndarray, rows: np.ndarray, xy: np.ndarray) -> None:
        """Move the midpoints of edges ``rows`` to ``xy`` by changing the bubble coefficient."""
        ea, eb = self.ea[rows], self.eb[rows]
        lin = self.M0[rows] + 0.5 * (self._xy(d, ea) + self._xy(d, eb))
        c = (xy - lin) / BUBBLE_MID
        dofs = self.nv + self.edge[rows]
        d[dofs], d[self.n_scalar + dofs] = c[:, 0], self.side * c[:, 1]

    # --- contact (3.9) -----------------------------------------------------------------------
    def detect(self, rp: RollPass, d: np.ndarray, tol: float, project_contact: bool,
               bilateral: bool = False) -> int:
        """Project penetrating nodes back onto the roll and flag contact nodes and edges.

        A node is in contact when its distance to the roll is below ``tol`` (3.9a); with
        ``bilateral`` (the moving plate) a node once in contact also stays so: the constraint
        (2.28a) holds it to the roll, and only the last contact point M releases it. Nodes
        inside the roll are always projected; with ``project_contact`` (every 10 steps) all
        contact nodes are put on the roll surface. An edge is in contact when both its vertices
        are; the midpoints of contact edges then follow the same projection rule. Nodes past
        the roll's lowest point x = X_roll (the report's last contact point M) are free.
        Returns the number of contact edges.
        """
        xv = self.vertex_positions(d)
        dist = rp.signed_distance(xv)
        # the last contact point is M = (X_roll, gap) (Section 3.4): nothing past it sticks
        before_m = xv[:, 0] <= rp.axis_x + tol
        held = (dist < tol) | (self.vertex_contact & before_m if bilateral else False)
        move = (held if project_contact else False) | (dist < 0.0)
        if move.any():
            self.set_vertices(d, self.verts[move], rp.project(xv[move]))
        self.vertex_contact = held & before_m
        vc = self.vertex_contact
        self.edge_contact = vc[[self.vpos[a] for a in self.ea]] & vc[[self.vpos[b] for b in self.eb]]
        xm = self.midpoint_positions(d)
        dm = rp.signed_distance(xm)
        mmove = (dm < 0.0) | (self.edge_contact & (project_contact | (dm > tol)))
        if mmove.any():
            rows = np.nonzero(mmove)[0]
            self.set_midpoints(d, rows, rp.project(xm[rows]))
        return int(self.edge_contact.sum())

    def set_contact_edges(self, edges: np.ndarray) -> None:
        """Flag the edges ``edges`` (boolean per top edge) and their vertices as the contact."""
        self.edge_contact = np.asarray(edges, dtype=bool).copy()
        on = np.concatenate([self.ea[self.edge_contact], self.eb[self.edge_contact]])
        self.vertex_contact = np.isin(self.verts, on)

    def write_indicator(self, chi_vec: np.ndarray) -> None:
        """Set the facet indicator (FacetFESpace order 0: one DOF per edge) to the contact flags."""
        chi_vec[:] = 0.0
        chi_vec[self.edge[self.edge_contact]] = 1.0
