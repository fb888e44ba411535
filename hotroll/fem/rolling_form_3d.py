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
(``fem/primal_dual.py``): nu a 3 x 3 tensor, the friction's z a vector like the slip. Not yet:
flattened rolls, the strip's elasticity.
"""
from __future__ import annotations

from hotroll.fem.rolling_form import RollingForm
from hotroll.fem.spaces import taylor_hood


class RollingForm3D(RollingForm):
    """``RollingForm`` on a 3D quarter strip (module docstring)."""

    dim = 3

    def __init__(self, mesh, rp, material, friction, penalties, free_surface: str = "traced",
                 tensions: tuple = (0.0, 0.0), contact: str = "multiplier",
                 edge_held: bool = False, consistency=1.0, rate_offset=None,
                 primal_dual: bool = True, strip_compliance: float | None = None,
                 strip_depth: float | None = None):
        if rp.shape is not None:
            raise NotImplementedError("a flattened roll on the 3D strip")
        self.edge_held = bool(edge_held)
        self._layer_width = None
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
