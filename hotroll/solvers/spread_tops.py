"""The 3D strip's top per width level (issue 53 stage 3; ../shared/notes/3d-steady.md, "Free
surfaces in 3D").

The top is y = Y(x, z). On its free parts (before the bite and after the contact's end) it is a
stream surface: u_x Y_x + u_z Y_z = u_y. Each width level z_k of the extruded mesh carries its
own 2D strip shape (``fem/free_surface.StripShape``: the traced tops and the contact's start
x_c(z_k)), traced by the 2D pass's own ``kinematic_update`` with the level's velocity, its u_y
less the share of the flow across the level, (u_z - u_x z_k') dY/dz (``LevelTops.update``); the
2D pass's ``StripMap`` maps the reference mesh onto each level's shape, and the 3D mesh's x and
y displacement is each level's, quadratic in z between them (``LevelTops.displace``). The contact
is the reference arc in every level (the map stretches it between x_c(z) and the contact's
end x_e(z): the level's own with unilateral contact, ``solvers/spread_ends.py``, else the 2D
pass's).
"""
from __future__ import annotations

import numpy as np

from hotroll.fem.free_surface import kinematic_update
from hotroll.solvers.steady_settings import default_lengths

#: the levels' maps quadratic in z between levels (``LevelTops.displace``); False: linear, the
#: map before 2026-11-30 (kept to measure against: docs/validation/spread_3d.md, "Mass flux")
CURVED = True


class LevelTops:
    """The strip's shape per width level of the ``Spread3D`` ``s3`` (module docstring)."""

    def __init__(self, s3):
        run = self.run = s3.run2d
        self.s3, self.levels = s3, len(s3.z)
        #: the levels below this one (an edge zone's mid-width level: its interior in
        #: generalized plane strain, z-independent) take its shape, as the flow there is its
        self.tied = s3.interior
        self.shapes = [run.shape.copy() for _ in range(self.levels)]
        self.d2 = np.tile(run.d, (self.levels, 1))           # each level's 2D displacement
        V2 = run.disp.space
        self._V2, self._n2 = V2, V2.ndof // 2
        #: the 2D DOFs ahead of the bite in the reference mesh, the contact's start with them
        #: (its x is x_c: ``displace``; a tolerance of 1e-6 h, not the last bit of x_touch,
        #: decides, so the frame does not)
        self._entry = run.map.P[:, 0] <= run.map.rp.x_touch + 1e-6 * run.problem.h

    def _nodes(self, vec2: np.ndarray) -> np.ndarray:
        """A 2D P2 vector field (its first 2 n2 entries) at the top's vertices, then its edge
        midpoints (rows of (x, y))."""
        top = self.run.top
        return np.vstack([top.vertex_values(vec2), top.midpoint_values(vec2)])

    def _positions(self, d2: np.ndarray) -> np.ndarray:
        top = self.run.top
        return np.vstack([top.vertex_positions(d2), top.midpoint_positions(d2)])

    def _level_fields(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        """(u_x, u_y) and (u_z, the z displacement) of level ``k`` in the 2D layout."""
        s3, n2, S2 = self.s3, self._n2, self._V2.components[0]
        w = np.zeros(3 * n2)
        s3.copy.take_vector(k, s3.form.nonlinear.velocity, S2, w, 3)
        dz = np.zeros(n2)
        V3 = s3.disp.space
        n3 = V3.ndof // 3
        s3.copy.take(k, V3.components[2], s3.disp.vec.FV().NumPy()[2 * n3:], S2, dz)
        return w[:2 * n2], np.concatenate([w[2 * n2:], dz])

    def _level(self, k: int):
        """Level ``k``'s top nodes: positions (x, y), velocity (u_x, u_y), u_z and z (m), the
        nodes in the top's order (vertices, then edge midpoints)."""
        vel, wz = self._level_fields(k)
        uz_z = self._nodes(wz)                       # (u_z, z displacement) at the nodes
        return (self._positions(self.d2[k]), self._nodes(vel), uz_z[:, 0],
                self.s3.z[k] + uz_z[:, 1])

    def update(self) -> float:
        """Trace every level's free tops with the 3D flow, map the mesh onto them; the largest
        distance (m) between a level's traced top and its current one.

        A level's nodes move across the width with it (z_k(x) = z_0 + (Z_k - z_0)(B - z_0) /
        (b0 - z_0), z_0 the first level's), so the trace
        along the level, dy/dx = Y_x + Y_z z_k', takes u_y less (u_z - u_x z_k') Y_z: the flow
        across the level times the top's slope across the width, Y_z at fixed x (the levels'
        x shift taken off with the level's own slope), upwind: from the level inside where
        the flow crosses outwards, else from the one outside (its last shape; the edge level,
        which has none, takes the inside's either way); 0 on the first level (the mid-width
        plane; on an edge zone's cut the inside's slope is 0: the interior's levels are one
        shape, the cut's, ``tied``)."""
        run, rp = self.run, self.run.problem.rp
        x_up = rp.x_touch - default_lengths(rp)[0]
        part, bounds = self.run._top_part, run.map.x_bounds()
        residual, inside, nxt = 0.0, None, self._level(0)
        for k in range(self.levels):
            # each level read once: level k + 1's (its last shape, this z) is the outside of
            # level k and then level k + 1 itself
            xy, v, uz, z = nxt
            nxt = self._level(k + 1) if k + 1 < self.levels else None
            if k < self.tied:             # an edge zone's interior: the cut's shape (below)
                inside = (xy, z)
                continue
            order = np.argsort(xy[:, 0], kind="stable")
            if inside is not None:
                dydx, dzdx = (np.empty(len(order)) for _ in range(2))
                dydx[order] = np.gradient(xy[order, 1], xy[order, 0])
                dzdx[order] = np.gradient(z[order], xy[order, 0])
                across = uz - v[:, 0] * dzdx             # the flow across the level
                dydz = self._slope_across(xy, z, dydx, inside)
                if nxt is not None:
                    xy_out, _, _, z_out = nxt
                    dydz = np.where(across >= 0.0, dydz,
                                    self._slope_across(xy, z, dydx, (xy_out, z_out)))
                v[:, 1] -= across * dydz
            inside = (xy, z)
            self.shapes[k], res = kinematic_update(rp, self.shapes[k], xy[order], v[order],
                                                   part[order], x_up, bounds)
            self.d2[k] = run.map.displacement(self.shapes[k])
            residual = max(residual, res)
        for k in range(self.tied):
            self.shapes[k] = self.shapes[self.tied].copy()
            self.d2[k] = self.d2[self.tied].copy()
        return residual

    @staticmethod
    def _slope_across(xy, z, dydx, other) -> np.ndarray:
        """dY/dz at fixed x between a level's nodes (``xy``, ``z``, their slope along x
        ``dydx``) and another level's same nodes (``other``: their positions and z)."""
        xy1, z1 = other
        dz = z - z1
        dz = np.where(np.abs(dz) > 1e-300, dz, 1e-300)
        return ((xy[:, 1] - xy1[:, 1]) - dydx * (xy[:, 0] - xy1[:, 0])) / dz

    def displace(self, disp3d) -> None:
        """The x and y parts of the extruded mesh's displacement: each level's 2D one,
        quadratic in z between levels (``LayerCopy.per_layer``; an edge zone's interior
        layer linear, its two levels one shape); the x part only ahead of
        the bite, where the map's x depends on the contact's start alone, linear in z on the
        arc and after it (the ends' per-level search, module ``spread_ends``)."""
        V3 = disp3d.space
        n3, n2 = V3.ndof // 3, self._n2
        vec = disp3d.vec.FV().NumPy()
        for c, where in enumerate((self._entry, None)):
            self.s3.copy.per_layer(self._V2.components[c], self.d2[:, c * n2:(c + 1) * n2],
                                   V3.components[c], vec[c * n3:(c + 1) * n3],
                                   z=self.s3.z if CURVED else None, where=where,
                                   flat=self.tied)

    def contact_starts(self) -> np.ndarray:
        """x_c of every level (m, the solver's frame)."""
        return np.array([s.x_c for s in self.shapes])
