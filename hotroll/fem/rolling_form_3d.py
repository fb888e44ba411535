"""The rolling form (3.6) on a 3D strip (issue 53): a quarter model on the extruded prism mesh
(``fem/extruded_mesh.py``), x along the strip, y through the thickness (``sym`` at y = 0), z
across the width (``zsym`` at z = 0, the lateral face ``edge``).

The terms are the 2D form's (``fem/rolling_form.py``), written in the roll's frame: the roll is
a cylinder about an axis along z, its normal n and its circle's tangent t have no z part, and
the friction acts in the roll's tangent plane, spanned by t and e_z: the slip is the vector
v_s = (u.t - |U_roll|) t + u_z e_z (2.27 in 3D; the strip slides across the roll where it
spreads), the laws take |v_s|^2 as in 2D and the shear is -k_f v_s. With ``edge_held`` the
lateral face has u_z = 0 (plane strain): the 2D solution, the same in every layer, solves this
form (the consistency check of issue 53). Newton's tangent is the primal-dual one
(``fem/primal_dual.py``): nu a 3 x 3 tensor, the friction's z a vector like the slip.

The strip's elasticity (``RollingForm.constraint``): the layer between the plastic flow's
surface and the roll carries the flux F = c_e p (u.t t + u_z e_z) in the roll's tangent plane,
and the roll is impermeable to u.n - div F, div F = dF_t/ds + dF_z/dz on the cylinder (the
roll's t and e_z as the surface's coordinates; ``layer_flux_rate``), weakly: int w [u.n -
div F] dA + int xi F.nu dl = 0, the line integral over the contact's boundary where the layer
is loaded or leaves it sideways (``layer_ends``: its start line and its lateral edge
``arc_edge``, where the arc meets the lateral face; zero on ``zsym``, where u_z = 0), nu the
outward conormal in the (t, e_z) plane. With xi = 1: int u.n dA = the layer's flux out at the
levels' ends (p = 0 there to the search's tolerance where they are searched; a held end passes
its F, as in 2D). With the edge held (u_z = 0) every term is the 2D form's in each layer. Not
yet: flattened rolls.

An edge zone's interior (``interior_cut``): the width layer inside the cut, between mid-width
and the zone, is one layer in generalized plane strain, u_x and u_y not varying across it and
u_z = z e(x, y) free (the interior's uniform lateral strain rate e, which a wide strip's
interior takes where it slips backwards: docs/validation/spread_3d.md), by a penalty on
du_x/dz and du_y/dz there (``interior_term``).
"""
from __future__ import annotations

from hotroll.fem.extruded_mesh import ARC_EDGE
from hotroll.fem.rolling_form import RollingForm
from hotroll.fem.spaces import taylor_hood

#: the interior's penalty on du_x/dz, du_y/dz over the reduced viscosity at U / l_c times the
#: flow stress's consistency (unit-free): their share of the interior's shear 1/GPS_PENALTY
GPS_PENALTY = 1e6


class RollingForm3D(RollingForm):
    """``RollingForm`` on a 3D quarter strip (module docstring)."""

    dim = 3

    def __init__(self, mesh, rp, material, friction, penalties, free_surface: str = "traced",
                 tensions: tuple = (0.0, 0.0), contact: str = "multiplier",
                 edge_held: bool = False, consistency=1.0, rate_offset=None,
                 primal_dual: bool = True, strip_compliance: float | None = None,
                 strip_depth: float | None = None, interior_cut: float | None = None):
        if rp.shape is not None:
            raise NotImplementedError("a flattened roll on the 3D strip")
        self.edge_held = bool(edge_held)
        self._layer_width = None
        #: z of an edge zone's cut (m, the reference mesh's) or None; its layer indicator
        self.interior_cut, self._interior = interior_cut, None
        super().__init__(mesh, rp, material, friction, penalties, free_surface, tensions,
                         consistency=consistency, rate_offset=rate_offset, contact=contact,
                         contact_regions="arc", primal_dual=primal_dual,
                         strip_compliance=strip_compliance, strip_depth=strip_depth)

    def arc_step(self):
        """The contact face's length along t: mesh_size (the square root of the quadrilateral's
        area) squared over its layer's width across the strip (the reference one: exact with
        the edge held, a stabilisation weight off by the face's stretch B / b0 <= 1.2 where the
        strip spreads)."""
        import numpy as np
        from ngsolve import BND, FacetFESpace, GridFunction, specialcf

        from hotroll.fem.reproducible import fe_space

        if self._layer_width is None:
            g = self._layer_width = GridFunction(fe_space(FacetFESpace, self.mesh, order=0))
            vec = g.vec.FV().NumPy()
            for el in self.mesh.Elements(BND):
                z = [self.mesh[v].point[2] for v in el.vertices]
                if len(z) == 4:
                    vec[g.space.GetDofNrs(el)[0]] = np.ptp(z)
        return specialcf.mesh_size ** 2 / self._layer_width

    def interior_term(self, u, v):
        """The interior layer's generalized plane strain (module docstring): GPS_PENALTY
        mu_ref K (du_x/dz dv_x/dz + du_y/dz dv_y/dz) on the elements inside the cut (their
        reference vertices at z <= the cut), or None without an edge zone."""
        if self.interior_cut is None:
            return None
        from ngsolve import L2, GridFunction, grad

        from hotroll.fem.reproducible import fe_space

        if self._interior is None:
            g = self._interior = GridFunction(fe_space(L2, self.mesh, order=0))
            vec = g.vec.FV().NumPy()
            tol = 1e-9 * max(abs(self.interior_cut), 1.0)
            for el in self.mesh.Elements():
                if max(self.mesh[v].point[2] for v in el.vertices) <= self.interior_cut + tol:
                    vec[g.space.GetDofNrs(el)[0]] = 1.0
        gu, gv = grad(u), grad(v)
        return (GPS_PENALTY * self._mu * self.consistency * self._interior
                * (gu[0, 2] * gv[0, 2] + gu[1, 2] * gv[1, 2]))

    def integrand(self, u, p, w, v, q, lam=None, xi=None):
        """The 2D form's (3.6) and, in an edge zone, the interior's term."""
        from ngsolve import dx

        out = super().integrand(u, p, w, v, q, lam=lam, xi=xi)
        extra = self.interior_term(u, v)
        return out if extra is None else out + extra * dx

    def jacobian(self, w, u, p, v, q, lam=None, xi=None, lam_w=None):
        """The 2D form's Jacobian and the interior's term (linear in u)."""
        from ngsolve import dx

        out = super().jacobian(w, u, p, v, q, lam=lam, xi=xi, lam_w=lam_w)
        extra = self.interior_term(u, v)
        return out if extra is None else out + extra * dx

    def _spaces(self, multiplier_on: str | None):
        """Taylor-Hood with v_y = 0 on ``sym``, v_z = 0 on ``zsym`` (and on ``edge`` if held)."""
        return taylor_hood(self.mesh, dirichlety="sym", multiplier_on=multiplier_on,
                           dirichletz="zsym|edge" if self.edge_held else "zsym")

    def roll_frame(self):
        """(n, t): the roll's normal (out of the strip, into the roll) and its circle's tangent
        along U_roll, in the (x, y) plane."""
        from ngsolve import CF, sqrt, x, y

        cx, cy = self.rp.centre
        r = sqrt((x - cx) ** 2 + (y - cy) ** 2)
        return CF(((cx - x) / r, (cy - y) / r, 0.0)), CF((-(y - cy) / r, (x - cx) / r, 0.0))

    def tangential(self, u):
        """u's part in the roll's tangent plane: (u.t) t + u_z e_z."""
        from ngsolve import CF

        _, t = self.roll_frame()
        return (u * t) * t + u[2] * CF((0.0, 0.0, 1.0))

    def slip(self, u):
        """The slip vector v_s = (u.t - |U_roll|) t + u_z e_z (2.27)."""
        _, t = self.roll_frame()
        return self.tangential(u) - self.roll_speed() * t

    def layer_flux_rate(self, u, du, lam, glam, t, n, depth, slope):
        """div F of the layer's flux F = c_e lambda~ (u.t t + u_z e_z) per unit s K: the 2D
        form's dF_t/ds plus dF_z/dz = c_e (u_z dlambda~/dz + lambda~ du_z/dz) (bilinear in
        (u, lam); ``du`` u's derivative matrix on the surface, ``glam`` lambda~'s gradient
        on it; c_e = compliance min(y, depth) does not vary along z)."""
        from ngsolve import CF

        e_z = CF((0.0, 0.0, 1.0))
        across = self.compliance * depth * (u[2] * (glam * e_z) + lam * (du * e_z)[2])
        return super().layer_flux_rate(u, du, lam, glam, t, n, depth, slope) + across

    def layer_ends(self, u, lam, xi, t, depth, u_w=None, lam_w=None):
        """The layer's flux out through the contact's boundary lines, s^2 K^-1 int xi F.nu dl:
        on its ``start`` line (-F_t where the line runs across the width: F's jump from 0 on
        the free top, as the 2D form's point term) and its lateral edge ``arc_edge`` (+F_z
        where the edge runs along t; the edge is a stream line of the flow, so F.nu = c_e p
        u.nu is the lateral face's kinematic error, small). nu dl = +-(tau_z t - tau_t e_z)
        dl, tau the line's unit tangent (either way along it): the line's conormal in the
        (t, e_z) plane the rate is written in, its sign outward (-t at the start, +e_z at the
        edge; the start line is skewed where the levels' contact starts x_c(z) differ). No
        term on the end line (``RollingForm.layer_ends``) nor on ``zsym`` (u_z = 0)."""
        from ngsolve import CF, IfPos, specialcf

        e_z = CF((0.0, 0.0, 1.0))
        tau = specialcf.tangential(3)
        f_t = self.layer_flux(u, lam, t, depth, u_w, lam_w)
        f_z = self.layer_flux(u, lam, e_z, depth, u_w, lam_w)
        flux = self._lam * self._lam * (f_t * (tau * e_z) - f_z * (tau * t)) * xi
        along_z, along_t = IfPos(tau * e_z, 1.0, -1.0), IfPos(tau * t, 1.0, -1.0)
        return ((-along_z * flux) * self.layer_point(self.START)
                + (-along_t * flux) * self.layer_point(ARC_EDGE))
