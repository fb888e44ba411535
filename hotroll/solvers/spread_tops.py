"""The 3D strip's top per width level (issue 53 stage 3; ../shared/notes/3d-steady.md, "Free
surfaces in 3D").

The top is y = Y(x, z). On its free parts (before the bite and after the contact's end) it is
a stream surface: u_x Y_x + u_z Y_z = u_y. Each width level z_k of the extruded mesh carries
its own 2D strip shape (``fem/free_surface.StripShape``: the traced tops and the contact's start
x_c(z_k)), traced by the 2D pass's own ``kinematic_update`` with the level's velocity, its u_y
less the spreading's share u_z dY/dz (dY/dz upwind from the level inside it, towards
mid-width; 0 on the mid-width plane); the 2D pass's ``StripMap`` maps the reference mesh onto
each level's shape, and the 3D mesh's x and y displacement is each level's, linear in z between
two (``LayerCopy.per_layer``). The contact is the reference arc in every level (the map
stretches it between x_c(z) and the contact's end), its end the 2D pass's.
"""
from __future__ import annotations

import numpy as np

from hotroll.fem.free_surface import kinematic_update
from hotroll.solvers.steady_settings import default_lengths


class LevelTops:
    """The strip's shape per width level of the ``Spread3D`` ``s3`` (module docstring)."""

    def __init__(self, s3):
        run = self.run = s3.run2d
        self.s3, self.levels = s3, len(s3.z)
        self.shapes = [run.shape.copy() for _ in range(self.levels)]
        self.d2 = np.tile(run.d, (self.levels, 1))           # each level's 2D displacement
        V2 = run.disp.space
        self._V2, self._n2 = V2, V2.ndof // 2

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
        s3, n2 = self.s3, self._n2
        vel = np.zeros(2 * n2)
        self.s3.copy.take_vector(k, s3.form.nonlinear.velocity, self._V2.components[0], vel, 2)
        w = np.zeros(3 * n2)
        s3.copy.take_vector(k, s3.form.nonlinear.velocity, self._V2.components[0], w, 3)
        dz = np.zeros(3 * n2)
        s3.copy.take_vector(k, s3.disp, self._V2.components[0], dz, 3)
        return vel, np.concatenate([w[2 * n2:], dz[2 * n2:]])

    def update(self) -> float:
        """Trace every level's free tops with the 3D flow, map the mesh onto them; the largest
        distance (m) between a level's traced top and its current one."""
        run, rp = self.run, self.run.problem.rp
        x_up = rp.x_touch - default_lengths(rp)[0]
        part = None
        residual, prev = 0.0, None
        for k in range(self.levels):
            vel, wz = self._level_fields(k)
            xy = self._positions(self.d2[k])
            v = self._nodes(vel)
            uz_z = self._nodes(wz)                   # (u_z, z displacement) at the nodes
            z = self.s3.z[k] + uz_z[:, 1]
            if prev is not None:                     # u_z dY/dz, upwind from inside
                xy0, z0 = prev
                order = np.argsort(xy[:, 0], kind="stable")
                slope = np.gradient(xy[order, 1], xy[order, 0])
                dydx = np.empty_like(slope)
                dydx[order] = slope
                dz = np.where(np.abs(z - z0) > 1e-300, z - z0, 1e-300)
                dydz = ((xy[:, 1] - xy0[:, 1]) - dydx * (xy[:, 0] - xy0[:, 0])) / dz
                v[:, 1] -= uz_z[:, 0] * dydz
            prev = (xy, z)
            order = np.argsort(xy[:, 0], kind="stable")
            if part is None:
                part = self._parts()
            self.shapes[k], res = kinematic_update(rp, self.shapes[k], xy[order], v[order],
                                                   part[order], x_up, run.map.x_bounds())
            self.d2[k] = run.map.displacement(self.shapes[k])
            residual = max(residual, res)
        return residual

    def _parts(self) -> np.ndarray:
        """The top nodes' parts (0 entry, 1 contact, 2 exit), as the 2D pass has them (the
        contact is the reference arc in every level)."""
        return self.run._top_part

    def displace(self, disp3d) -> None:
        """The x and y parts of the extruded mesh's displacement: each level's 2D one."""
        V3 = disp3d.space
        n3, n2 = V3.ndof // 3, self._n2
        vec = disp3d.vec.FV().NumPy()
        for c in range(2):
            self.s3.copy.per_layer(self._V2.components[c], self.d2[:, c * n2:(c + 1) * n2],
                                   V3.components[c], vec[c * n3:(c + 1) * n3])

    def contact_starts(self) -> np.ndarray:
        """x_c of every level (m, the solver's frame)."""
        return np.array([s.x_c for s in self.shapes])
