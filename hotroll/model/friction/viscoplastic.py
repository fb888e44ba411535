"""Viscoplastic friction, the report's (2.29a): |T_tau| = a_f K |v_s|^m."""
from __future__ import annotations

from dataclasses import dataclass

from hotroll.model.friction.base import FrictionLaw
from hotroll.model.friction.registry import FrictionSpec, register
from hotroll.model.parameters import Parameter


@dataclass(frozen=True)
class ViscoplasticFriction(FrictionLaw):
    """Viscoplastic friction (2.29a): T_tau = -a_f K |v_s|^(m-1) v_s (regularised)."""

    K: float = 1.0   # consistency the law scales with (1 in reduced units)
    m: float = 0.2   # exponent, the material's strain-rate sensitivity (Section 2.6)

    name = "viscoplastic"
    uses_a_f = True

    def coefficient(self, slip2, *, a_f=None, m=None, pressure=None, k=None, K=None):
        """Secant coefficient a_f K (|v_s|^2 + v_reg^2)^((m-1)/2)."""
        m = self.m if m is None else m
        K = self.K if K is None else K
        return a_f * K * (slip2 + self.v_reg**2) ** ((m - 1.0) / 2.0)

    def coefficient_partials(self, slip2, *, a_f=None, m=None, pressure=None, k=None, K=None):
        """(d k_f/d slip2, 0, 0): the law takes neither the pressure nor k."""
        m = self.m if m is None else m
        K = self.K if K is None else K
        return a_f * K * (m - 1.0) / 2.0 * (slip2 + self.v_reg**2) ** ((m - 3.0) / 2.0), 0.0, 0.0


SPEC = register(FrictionSpec(
    name="viscoplastic",
    summary="tau = a_f K |dv|^(m-1) dv, the report's (2.29a); a_f estimated by (3.15) or given",
    source="Touloupoulos 2020 (the report), (2.29a), (3.15)",
    parameters=(Parameter("a_f", "(omit: estimate) viscoplastic friction coefficient (tau = a_f K "
                          "|dv|^(m-1) dv); estimate: the report's (3.15)", "m^-m", '"estimate" or a number > 0',
                          required=False, words=("estimate",), default="estimate", gt=0.0),),
    build=lambda p, v_reg, m: ViscoplasticFriction(v_reg, K=1.0, m=m),
    v_reg_fraction=1e-4,
    slab=("sticking", None),
))
