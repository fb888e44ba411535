"""Tresca friction (friction factor): |T_tau| = factor k."""
from __future__ import annotations

from dataclasses import dataclass

from hotroll.model.friction.base import FrictionLaw
from hotroll.model.friction.registry import FrictionSpec, register
from hotroll.model.parameters import Parameter


@dataclass(frozen=True)
class TrescaFriction(FrictionLaw):
    """Friction factor (Tresca, constant shear): |T_tau| = factor k."""

    factor: float = 0.8

    name = "tresca"
    uses_k = True

    def limit(self, *, pressure=None, k=None):
        return self.factor * k

    def limit_partials(self, *, pressure=None, k=None):
        return 0.0, self.factor


SPEC = register(FrictionSpec(
    name="tresca",
    summary="tau = m_f k (friction factor), k = sigma_ef/sqrt3",
    source="Tresca; the friction factor m_f",
    parameters=(Parameter("factor", "friction factor m_f (tau = m_f k)", "", "in (0, 1]", gt=0.0,
                          le=1.0),),
    build=lambda p, v_reg, m: TrescaFriction(v_reg, factor=p["factor"]),
    v_reg_fraction=1e-3,
    slab=("tresca", "factor"),
))
