"""The equivalent plastic strain carried with the material (issue 15; beyond the report).

A strain-dependent flow stress (Hensel-Spittel) needs the strain eps at every point:
d eps / dt = edot along the material path, edot = sqrt(2/3 eps_dot:eps_dot) (2.16).

- Steady strip (``transport``): v . grad eps = edot with eps = eps_entry on the inlet face,
  a stabilised (SUPG) P1 solve on the current strip: ``int (v.grad eps)(w + tau v.grad w) =
  int edot (w + tau v.grad w)``, tau = h / (2 |v|) (the strip always flows forward, no
  recirculation, so the inlet is the whole inflow boundary).
- Report's scheme (``integrate``): the mesh moves with the material (3.7), so the nodes are
  material points: eps_node += dt edot_node after each step (edot the P1 projection).

The flow stress enters the form as the consistency ratio K(eps, T) / K_ref
(``RollingForm(consistency=...)``).
"""
from __future__ import annotations

import numpy as np

from hotroll.fem.forms import strain_rate
from hotroll.fem.reproducible import fe_space, integrate, parallel
from hotroll.model.material import edot_squared


class StrainField:
    """P1 strain on a (moving) mesh, with its steady transport and transient update."""

    def __init__(self, mesh, entry_strain: float, inlet: str = "in", profile=None):
        """``profile``: the inlet's strain over eta = y / (the inlet's highest y) in the
        undeformed mesh (a ``process.profile.ThicknessProfile``), or None: ``entry_strain``."""
        from ngsolve import H1, GridFunction

        self.mesh, self.entry = mesh, float(entry_strain)
        self.space = fe_space(H1, mesh, order=1, dirichlet=inlet)
        self.gf = GridFunction(self.space)
        self._inlet = np.full(self.space.ndof, self.entry)
        if profile is not None:
            fixed = ~np.array(list(self.space.FreeDofs()), dtype=bool)
            y = np.asarray(mesh.ngmesh.Coordinates())[: mesh.nv, 1][fixed]
            # over |y|: the full strip's inlet (y < 0 too, issue 52) reads it mirrored
            self._inlet[fixed] = profile(np.abs(y) / np.max(np.abs(y)))
            self.entry = float(profile.mean())
            self._inlet[~fixed] = self.entry
        self.gf.vec.FV().NumPy()[:] = self._inlet
        self._edot = GridFunction(fe_space(H1, mesh, order=1))
        self._steady: list | None = None   # (velocity, a, f, inverse) of ``transport``

    @property
    def values(self) -> np.ndarray:
        return self.gf.vec.FV().NumPy()

    def _rate(self, velocity):
        from ngsolve import sqrt

        return sqrt(edot_squared(strain_rate(velocity)) + 1e-300)

    def transport(self, velocity) -> float:
        """Solve v . grad eps = edot (SUPG, P1) with eps = entry on the inlet; returns the
        largest change over the largest strain (1 on the first call from a flat field; 0 for
        a field that is 0 everywhere). The
        forms and the factorisation are kept for the same ``velocity`` (a coupling round
        re-assembles them and refactorises in place: 5.1 -> 3 ms a round on a ten-stand pass)."""
        old = self.values.copy()
        kept = self._steady
        if kept is None or kept[0] is not velocity:
            kept = self._steady = [velocity, *self._forms(velocity), None]
        _, a, f, inv = kept
        with parallel():
            a.Assemble()
            f.Assemble()
        if inv is None:
            inv = kept[3] = a.mat.Inverse(self.space.FreeDofs(), inverse="umfpack")
        else:
            inv.Update()
        self.values[:] = self._inlet          # Dirichlet values on the inlet
        r = f.vec.CreateVector()
        r.data = f.vec - a.mat * self.gf.vec
        self.gf.vec.data += inv * r
        # over the new field's largest (the old one's where the new one is 0 everywhere)
        scale = float(np.max(np.abs(self.values))) or float(np.max(np.abs(old)))
        return float(np.max(np.abs(self.values - old))) / scale if scale > 0.0 else 0.0

    def _forms(self, velocity):
        """The SUPG forms of ``transport``: tau = h / (2 |v|)."""
        from ngsolve import BilinearForm, InnerProduct, LinearForm, dx, grad, specialcf, sqrt

        e, w = self.space.TnT()
        speed = sqrt(InnerProduct(velocity, velocity) + 1e-300)
        tau = specialcf.mesh_size / (2.0 * speed)
        test = w + tau * (velocity * grad(w))
        a = BilinearForm(self.space)
        a += (velocity * grad(e)) * test * dx
        f = LinearForm(self.space)
        f += self._rate(velocity) * test * dx
        return a, f

    def integrate(self, velocity, dt: float) -> None:
        """One step of the material update: eps += dt edot at the (material) nodes."""
        with parallel():
            self._edot.Set(self._rate(velocity))
        self.values[:] += dt * np.maximum(self._edot.vec.FV().NumPy(), 0.0)

    def mean_where(self, vertex_mask) -> float:
        """Mean strain over the elements whose vertices are all in ``vertex_mask`` (P1
        indicator; the rest of the mesh weighs nothing)."""
        from ngsolve import H1, GridFunction, IfPos

        ind = GridFunction(fe_space(H1, self.mesh, order=1))
        ind.vec.FV().NumPy()[:] = np.asarray(vertex_mask, dtype=float)
        full = IfPos(ind - 0.999, 1.0, 0.0)
        area = integrate(full, self.mesh)
        return integrate(full * self.gf, self.mesh) / area if area > 0 else float("nan")

    def mean_between(self, x0: float, x1: float) -> float:
        """Mean strain over the strip between x0 and x1 (current coordinates): the
        thickness-weighted mean of a cross-section where the strip is rigid."""
        from ngsolve import IfPos, x

        band = IfPos(x - x0, IfPos(x1 - x, 1.0, 0.0), 0.0)
        area = integrate(band, self.mesh)
        return integrate(band * self.gf, self.mesh) / area if area > 0 else float("nan")


class ShearStrainField(StrainField):
    """The engineering shear strain gamma_xy carried by the steady flow (issue 52: asymmetric
    rolling shears the strip through its thickness): v . grad gamma = du_x/dy + du_y/dx, gamma
    = 0 on the inlet (small-strain accumulation along the streamlines, signed: > 0 where the
    upper layers move forward relative to the lower)."""

    def __init__(self, mesh, inlet: str = "in"):
        super().__init__(mesh, 0.0, inlet=inlet)

    def _rate(self, velocity):
        from ngsolve import Grad

        g = Grad(velocity)
        return g[0, 1] + g[1, 0]

    def on_boundary(self, region: str, y_of_vertex) -> tuple[np.ndarray, np.ndarray]:
        """(y, gamma) at the vertices of the boundary ``region`` (e.g. the outlet ``out``),
        sorted by y; ``y_of_vertex``: the vertices' current y (m, an array over the mesh)."""
        verts = sorted({v.nr for el in self.mesh.Boundaries(region).Elements()
                        for v in el.vertices})
        y = np.asarray(y_of_vertex)[verts]
        order = np.argsort(y)
        return y[order], self.values[np.asarray(verts)[order]]


class CarriedField(StrainField):
    """A scalar carried unchanged by the steady flow: v . grad theta = 0 (SUPG P1, as the
    strain's transport with no source), theta = ``inlet(x, y, z)`` at the inlet's vertices (a
    function of their reference coordinates, arrays). The 3D strip's entry temperature across
    the width (issue 53): the bite is too short for heat to cross the width."""

    def __init__(self, mesh, inlet_values, inlet: str = "in"):
        super().__init__(mesh, 0.0, inlet=inlet)
        fixed = ~np.array(list(self.space.FreeDofs()), dtype=bool)
        X = np.asarray(mesh.ngmesh.Coordinates())[: mesh.nv]
        self._inlet[fixed] = inlet_values(*X[fixed].T)
        self.values[:] = self._inlet

    def _rate(self, velocity):
        from ngsolve import CF

        return CF(0.0)
