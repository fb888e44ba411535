"""The friction terms of the rolling form (report (2.27)-(2.29), docs/theory.md 1a-1c): the
law's arguments and secant coefficient at a velocity, where the friction is integrated, and
Newton's tangent of the friction term by the chain rule through the law's partials. A mixin
of ``fem/rolling_form.py: RollingForm`` (and so of the full strip's ``GapForm``), whose
material, law, roll frame, slip, pressure and contact indicator these read. Split from
``fem/rolling_form.py``."""
from __future__ import annotations

from hotroll.fem.forms import strain_rate
from hotroll.fem.reproducible import integrate
from hotroll.model.material import edot_squared


class FrictionTerms:
    """The friction law's terms of ``RollingForm``."""

    def shear_flow_stress(self, w):
        """k = sigma_ef / sqrt3 of the strain rate of w (reduced; regularised (2.21)). Needs
        the volume gradient: valid in volume and element-boundary integrals only."""
        e2 = edot_squared(strain_rate(w))
        return self.material.sigma_ef_reg(e2, m=self.m_material, K=self.consistency) / 3.0**0.5

    def friction_arguments(self, w, k=None, lam=None) -> dict:
        """The friction law's keyword arguments at the velocity w (and multiplier ``lam``):
        a_f, m, and the pressure and k = sigma_ef/sqrt3 where the law takes them (``k`` given:
        that CF instead, e.g. a P1 field where the volume gradient is not at hand)."""
        law = self.friction
        if law.uses_k and k is None:
            k = self.shear_flow_stress(w)
        return dict(a_f=self.a_f, m=self.m,
                    pressure=self.pressure(w, lam) if law.uses_pressure else None,
                    k=k if law.uses_k else None)

    def friction_coefficient(self, w, k=None, lam=None):
        """The friction law's secant coefficient k_f at the velocity w (T_tau = -k_f v_s)."""
        s = self.slip(w)
        return self.friction.coefficient(s * s, **self.friction_arguments(w, k, lam))

    def friction_measure(self):
        """Where the friction term is integrated: the boundary the contact can be on
        (``contact_regions``: the steady strip's arc, the report's scheme's whole top; chi
        picks the contact, zero elsewhere: the rest of the top's 4.4 of 15.5 ms of a Jacobian's
        assembly on a ten-stand pass, issue 34 session 8), or, for a law with k (which needs
        the volume gradient: a boundary integral sees only the surface gradient), the
        boundaries of the elements along it."""
        from ngsolve import ds, dx

        if self.top_elements is None:
            return ds(self.contact_regions)
        return dx(element_boundary=True, definedonelements=self.top_elements)

    def integrate_friction(self, cf) -> float:
        """Integral of ``cf`` (with chi in it) over the contact, on ``friction_measure``."""
        from ngsolve import BND

        if self.top_elements is None:
            return integrate(cf.Compile(), self.mesh, BND,
                             definedon=self.mesh.Boundaries(self.contact_regions))
        return integrate(cf.Compile() * self.friction_measure(), self.mesh)

    def friction_tangent(self, w, u, v, lam=None, lam_w=None):
        """d/dw of the friction term chi k_f(w) s(w) (v.t) along u (and the multiplier's
        direction ``lam``; ``lam_w`` the multiplier at the iterate), by the chain rule through
        the law's ``coefficient_partials`` (slip^2, pressure, k of the strain rate)."""
        from ngsolve import InnerProduct

        law, s, s_u = self.friction, self.slip(w), self.tangential(u)
        kw = self.friction_arguments(w, lam=lam_w)
        kf = law.coefficient(s * s, **kw)
        d_s2, d_p, d_k = law.coefficient_partials(s * s, **kw)
        k = kw["k"]
        # Newton: d k_f = 2 k_f' s ds; primal-dual: one factor s/S replaced by the dual z
        # (fem/primal_dual.py: FrictionDual)
        if self.friction_dual is None:
            d_kf = d_s2 * 2.0 * s * s_u
        else:
            from ngsolve import sqrt

            S = sqrt(s * s + self.v_reg * self.v_reg)
            d_kf = d_s2 * 2.0 * S * self.friction_dual.z(s, self.v_reg) * s_u
        if law.uses_pressure:      # p = gamma (w.n) or s lambda~
            d_kf = d_kf + d_p * self.pressure(u, lam)
        if law.uses_k:             # k ~ (eps0^2 + e2)^(m/2), e2 = 2/3 eps(w):eps(w)
            ew = strain_rate(w)
            e2 = edot_squared(ew)
            dk_de2 = k * self.m_material / (2.0 * (self.material.eps0**2 + e2))
            d_kf = d_kf + d_k * dk_de2 * (4.0 / 3.0) * InnerProduct(ew, strain_rate(u))
        return self.chi * (kf * s_u + s * d_kf) * self.tangential(v)
