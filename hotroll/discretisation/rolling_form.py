"""The penalised weak form of the rolling problem, report (3.2), (3.3), (3.6).

Terms (all divided by K: the discrete problem is solved for p/K, so it is identical for every K
and stresses are K times the reduced ones; this is how the penalties of Table 1 "scale with K"):

- Norton-Hoff volume term (2.21) with the pressure as Lagrange multiplier (2.24);
- on the contact Gamma_C (edges flagged by ``chi``): viscoplastic friction (2.29a) on the slip
  v_s = (v - U_roll).t t (2.27), and the bilateral penalty gamma_vC (dv.n)(phi.n) for (2.28a);
  n and t are the roll's normal and tangent at the point, so U_roll.n = 0 exactly;
- on the free top Gamma_0 (top edges not in contact): the one-sided inlet penalty (3.2a) for
  x <= X_roll (Gamma_0L) or outlet penalty (3.2b) for x > X_roll (Gamma_0R), and, in the
  ``"constrained"`` free-surface model only, gamma_v0 (v.n)(phi.n) (3.2d), n the mesh normal on
  Gamma_0L and e_y on the flat exit surface Gamma_0R (``free_normal``); ``"traced"`` tops are
  traction-free;
- on the tail face Gamma_in: (3.2a); on the head face Gamma_out: (3.2b) plus gamma_v0 v_y phi_y,
  the vertical-motion correction T* the report adds on Gamma_out.
Penalty parameters follow Table 1: gamma_v0 = gamma_vC = 10/h in the soft zone I around the
first touching point, 25/h elsewhere; gamma_in = gamma_out = 2/h^(m+1).
"""
from __future__ import annotations

from dataclasses import dataclass

from ..physics.friction import ViscoplasticFriction
from ..physics.material import NortonHoff
from ..process.geometry import RollPass
from .forms import NonlinearProblem, norton_hoff_tangent, norton_hoff_volume, one_sided
from .spaces import taylor_hood

TOP = "top|arc|exit"   # the whole top boundary (the steady strip adds "exit")


@dataclass(frozen=True)
class PenaltyTable:
    """Table 1 of the report (for K = 1), with h the contact mesh size."""

    h: float
    soft: float = 10.0   # gamma_v0 = gamma_vC in the zone I
    hard: float = 25.0   # gamma_v0 = gamma_vC elsewhere
    inout: float = 2.0   # gamma_in = gamma_out = inout / h^(m+1)

    def surface(self, x, zone):
        from ngsolve import IfPos

        lo, hi = zone
        return IfPos((x - lo) * (hi - x), self.soft / self.h, self.hard / self.h)

    def inlet_outlet(self, m):
        return self.inout / self.h ** (m + 1.0)


class RollingForm:
    """Spaces, parameters and the Newton/Picard forms of (3.6) on one (moving) mesh."""

    def __init__(self, mesh, rp: RollPass, material: NortonHoff, friction: ViscoplasticFriction,
                 penalties: PenaltyTable, free_surface: str):
        from ngsolve import FacetFESpace, GridFunction, Parameter

        self.mesh, self.rp = mesh, rp
        self.free_surface = free_surface
        self.material, self.friction, self.penalties = material, friction, penalties
        self.fes = taylor_hood(mesh, dirichlety="sym")
        self.m = Parameter(material.m)      # set to 1 for the very first iterate (Section 3.4)
        self.a_f = Parameter(1.0)           # friction parameter, updated by (3.15) every step
        self.chi = GridFunction(FacetFESpace(mesh, order=0))  # 1 on contact edges
        self.problem = NonlinearProblem(self.fes, self.integrand, velocity_scale=rp.u_roll,
                                        jacobian=self.jacobian)

    # --- geometry of the roll as coefficient functions ------------------------------------
    def roll_frame(self):
        """(n, t): roll normal (out of the plate, into the roll) and tangent along U_roll."""
        from ngsolve import CF, sqrt, x, y

        cx, cy = self.rp.centre
        r = sqrt((x - cx) ** 2 + (y - cy) ** 2)
        n = CF(((cx - x) / r, (cy - y) / r))
        t = CF((-(y - cy) / r, (x - cx) / r))
        return n, t

    def free_normal(self, u):
        """u.n on the free top for (3.2d): the mesh normal before the gap, the normal of the
        flat exit surface, e_y, after it (x > X_roll). The Lagrangian exit surface is never
        exactly flat: with its own normal, (3.2d) pins u_x wherever it wrinkles, the wrinkles
        grow and the mesh tangles (see docs/theory.md, "Free exit surface")."""
        from ngsolve import IfPos, specialcf, x

        return IfPos(x - self.rp.axis_x, u[1], u * specialcf.normal(2))

    def slip(self, u):
        """Scalar slip v_s . t = u.t - |U_roll| (2.27); negative where the plate lags the roll."""
        _, t = self.roll_frame()
        return u * t - self.rp.u_roll

    def inlet_penalty(self, u, w):
        """(3.2a) per unit test v_x: gamma_in [v_x - |U_roll|]_+, active set taken at w."""
        U = self.rp.u_roll
        return self.penalties.inlet_outlet(self.m) * one_sided(u[0] - U, w[0] - U)

    def outlet_penalty(self, u, w):
        """(3.2b) per unit test v_x: -gamma_out [|U_roll| - v_x]_+, active set taken at w."""
        U = self.rp.u_roll
        return -self.penalties.inlet_outlet(self.m) * one_sided(U - u[0], U - w[0])

    # --- the form ---------------------------------------------------------------------------
    def integrand(self, u, p, w, v, q):
        """The residual form (3.6), coefficients at w (w = u: Newton; the last iterate: Picard)."""
        from ngsolve import dx

        vol = norton_hoff_volume(self.material, self.m, u, p, w, v, q, K=1.0)
        return vol * dx + self.boundary(u, w, v)

    def jacobian(self, w, u, p, v, q):
        """Newton's Jacobian of (3.6) at w: the Norton-Hoff tangent by hand, the boundary terms
        differentiated symbolically (w is the iterate's GridFunction component)."""
        from ngsolve import dx

        vol = norton_hoff_tangent(self.material, self.m, w, u, p, v, q, K=1.0)
        return vol * dx + self.boundary(w, w, v).Diff(w, u)

    def boundary(self, u, w, v):
        """Friction (2.29a) and penalty terms (3.2), (3.3) on the boundary, coefficients at w."""
        from ngsolve import IfPos, ds, x

        m, rp, pen = self.m, self.rp, self.penalties
        n, t = self.roll_frame()
        gam_s = pen.surface(x, rp.soft_zone)
        chi = self.chi

        s_u, s_w = self.slip(u), self.slip(w)
        k_f = self.friction.coefficient(self.a_f, s_w * s_w, m=m, K=1.0)
        contact = k_f * s_u * (v * t) + gam_s * (u * n) * (v * n)

        inlet = self.inlet_penalty(u, w) * v[0]
        outlet = self.outlet_penalty(u, w) * v[0]
        free = IfPos(x - rp.axis_x, outlet, inlet)
        if self.free_surface == "constrained":
            free = free + gam_s * self.free_normal(u) * self.free_normal(v)

        return ((chi * contact + (1.0 - chi) * free) * ds(TOP)
                + inlet * ds("in")
                + (outlet + gam_s * u[1] * v[1]) * ds("out"))
