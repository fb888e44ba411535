"""Coulomb friction capped by sticking: |T_tau| = min(mu p, k)."""
from __future__ import annotations

from dataclasses import dataclass

from hotroll.model.friction.base import (
    FrictionLaw,
    smooth_minimum,
    smooth_minimum_partials,
    smooth_positive_part,
    smooth_positive_part_partials,
)
from hotroll.model.friction.registry import FrictionSpec, register
from hotroll.model.parameters import Parameter


@dataclass(frozen=True)
class CoulombFriction(FrictionLaw):
    """Coulomb friction capped by sticking: |T_tau| = min(mu p, k), p = max(pressure, 0).

    The two kinks (p = 0, mu p = k) are rounded over ``rounding`` x k (error <= 0.5 % of k at
    the kink, none away from it), so that Newton converges to its tolerance instead of
    oscillating between the two sides at a quadrature point (docs/theory.md 1b)."""

    mu: float = 0.3
    rounding: float = 0.01

    name = "coulomb"
    uses_pressure = True
    uses_k = True

    def limit(self, *, pressure=None, k=None):
        d = self.rounding * k
        return smooth_minimum(self.mu * smooth_positive_part(pressure, d / self.mu), k, d)

    def limit_partials(self, *, pressure=None, k=None):
        r, mu = self.rounding, self.mu
        d = r * k
        capped = mu * smooth_positive_part(pressure, d / mu)
        p_a, p_delta = smooth_positive_part_partials(pressure, d / mu)
        m_a, m_b, m_delta = smooth_minimum_partials(capped, k, d)
        return m_a * mu * p_a, m_a * mu * p_delta * (r / mu) + m_b + m_delta * r


SPEC = register(FrictionSpec(
    name="coulomb",
    summary="tau = min(mu p, k), p the contact pressure, k = sigma_ef/sqrt3",
    source="Coulomb; capped at the shear flow stress k (sticking)",
    parameters=(Parameter("mu", "Coulomb friction coefficient", "", "in (0, 2]", gt=0.0, le=2.0),),
    build=lambda p, v_reg, m: CoulombFriction(v_reg, mu=p["mu"]),
    v_reg_fraction=1e-3,
    slab=("coulomb", "mu"),
))
