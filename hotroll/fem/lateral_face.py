"""The 3D strip's lateral face as a stream surface (issue 53 stage 2;
../shared/notes/3d-steady.md, "Free surfaces in 3D").

The face is z = B(x, y), a height over the strip's cross-section (the 2D mesh, deformed as the
strip's (x, y) shape). In a steady flow it is a stream surface: u.n = 0, that is

    u_x dB/dx + u_y dB/dy = u_z   on the face, B = b0 on the entry face (the stock's half width),

a linear transport equation along the face's own streamlines (u_x > 0 in a steady pass). It is
solved for a P2 field B by streamline-upwind Petrov-Galerkin (SUPG: the test function w +
tau u.grad w, tau = h / 2|u|), the velocity the 3D solution's on the face. Every layer of the
extruded mesh then moves along its spine, z = z_0 + (Z - z_0) (B - z_0) / (b0 - z_0), z_0 = 0, the
mid-width plane (``displace``; the note: moving only
the edge layer folds it on narrow bars). The exit width and the spread are read off B.
"""
from __future__ import annotations

import numpy as np

from hotroll.fem.reproducible import fe_space
from hotroll.fem.spaces import P2Nodes


class LateralFace:
    """B(x, y) on the 2D cross-section ``mesh2d`` (its reference mesh: a copy is deformed by
    ``disp2d``, the 2D displacement's coefficient vector), for the extruded mesh of
    ``copy`` (``fem/extruded_mesh.LayerCopy``) with layers ``z`` (the last its free edge, b0)."""

    def __init__(self, mesh2d, disp2d: np.ndarray, z: np.ndarray, copy, inflow: str = "in"):
        import ngsolve as ng

        self.face = ng.Mesh(mesh2d.ngmesh.Copy())
        self._d = ng.GridFunction(fe_space(ng.VectorH1, self.face, order=2))
        self.set_shape(disp2d)
        self.z, self.b0, self.copy = np.asarray(z, dtype=float), float(z[-1]), copy
        self.S = fe_space(ng.H1, self.face, order=2, dirichlet=inflow)
        self.B = ng.GridFunction(self.S)
        self.B.Set(self.b0)
        self._scalar = fe_space(ng.H1, self.face, order=2)
        self.velocity = ng.GridFunction(self._scalar ** 3)
        u, w = self.S.TnT()
        v = ng.CF((self.velocity[0], self.velocity[1]))
        tau = ng.specialcf.mesh_size / (2.0 * ng.sqrt(v * v) + 1e-300)
        test = w + tau * (v * ng.grad(w))
        self._a = ng.BilinearForm(self.S)
        self._a += (v * ng.grad(u)) * test * ng.dx
        self._f = ng.LinearForm(self.S)
        self._f += self.velocity[2] * test * ng.dx
        self._dB = ng.GridFunction(self.S)
        self._nodes = P2Nodes(self.face, self.S.ndof)

    def set_shape(self, disp2d: np.ndarray) -> None:
        """The cross-section's (x, y) shape at the edge: the 2D displacement's coefficient
        vector ``disp2d`` (the edge level's, where the top is traced per level)."""
        self._d.vec.FV().NumPy()[:] = disp2d
        self.face.SetDeformation(self._d)

    def update(self, velocity3d) -> float:
        """Solve for B with the 3D velocity ``velocity3d`` (a VectorH1 GridFunction of the
        extruded mesh) on the face; the largest change of B (m)."""
        self.copy.take_vector(len(self.z) - 1, velocity3d, self._scalar,
                              self.velocity.vec.FV().NumPy(), 3)
        self._a.Assemble()
        self._f.Assemble()
        r = self._f.vec.CreateVector()
        r.data = self._f.vec - self._a.mat * self.B.vec
        self._dB.vec.data = self._a.mat.Inverse(self.S.FreeDofs(), inverse="umfpack") * r
        self.B.vec.data += self._dB.vec
        # the largest move of B at the P2 nodes (vertices and edge midpoints: an edge's DOF is
        # its bubble's coefficient, not a value)
        d = self._dB.vec.FV().NumPy()
        return float(np.abs(self._nodes.values(np.concatenate([d, np.zeros_like(d)]))[0]).max())

    def displace(self, disp3d) -> None:
        """The z part of the extruded mesh's displacement (a VectorH1 GridFunction, order 2):
        (Z - z_0) / (b0 - z_0) (B - b0) at every node of layer Z, z_0 the first layer's (0, the
        mid-width plane; x, y from the 2D shape, untouched)."""
        import ngsolve as ng

        V3 = disp3d.space
        n3 = V3.ndof // 3
        excess = ng.GridFunction(self.S)
        excess.Set(self.B - self.b0)            # exact: B - b0 is P2
        self.copy.copy(self.S, excess.vec.FV().NumPy(), V3.components[2],
                       disp3d.vec.FV().NumPy()[2 * n3:],
                       scale=(self.z - self.z[0]) / (self.b0 - self.z[0]))

    def half_width(self, x: float, y: np.ndarray) -> np.ndarray:
        """B (m) at the strip's points whose reference (undeformed 2D mesh) coordinates are
        (x, y_i): NGSolve finds a point in the reference mesh, whatever its deformation."""
        return np.array([self.B(self.face(x, float(yi))) for yi in np.asarray(y)])
