"""Friction laws on the roll contact.

Viscoplastic law (2.29a): T_tau = -a_f K |v_s|^(m-1) v_s, regularised at the neutral point as
-a_f K (|v_s|^2 + v_reg^2)^((m-1)/2) v_s, the same way as (2.21) regularises the material law.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class ViscoplasticFriction:
    """Viscoplastic friction (2.29a). ``a_f`` may be a number or an NGSolve Parameter."""

    K: float
    m: float
    v_reg: float  # regularisation velocity, m/s

    def coefficient(self, a_f, slip2, m=None, K=None):
        """Secant coefficient k with T_tau = -k v_s."""
        m = self.m if m is None else m
        K = self.K if K is None else K
        return a_f * K * (slip2 + self.v_reg**2) ** ((m - 1.0) / 2.0)

    def shear(self, a_f, slip, K=None):
        """Shear traction on the plate along the roll tangent, for a scalar slip velocity."""
        return -self.coefficient(a_f, slip * slip, K=K) * slip

    def power_density(self, a_f, slip, K=None):
        """Friction dissipation -T_tau . v_s = a_f K |v_s|^(m+1) (regularised)."""
        return self.coefficient(a_f, slip * slip, K=K) * slip * slip
