"""Friction laws on the roll contact, one interface for the weak form and the post-processing.

Every law gives the shear traction on the plate as T_tau = -k_f v_s (secant form), v_s the slip
(2.27), with the coefficient ``k_f = coefficient(slip2, a_f=, m=, pressure=, k=)``. All
arguments are numbers, numpy arrays or NGSolve CoefficientFunctions; stresses are in the units
of the caller (the weak form passes them divided by K: reduced units).

- ``ViscoplasticFriction`` (2.29a): |T_tau| = a_f K |v_s|^m;
- ``CoulombFriction``: |T_tau| = min(mu p, k), p the contact pressure (>= 0), k = sigma_ef/sqrt3
  the local shear flow stress (sticking where mu p > k);
- ``TrescaFriction``: |T_tau| = factor k.

All three are regularised at the neutral point the way (2.21) regularises the material law:
|v_s|^(q-1) v_s -> (|v_s|^2 + v_reg^2)^((q-1)/2) v_s with q = m (viscoplastic) or q = 0
(Coulomb, Tresca: the shear's magnitude does not depend on the slip speed).
"""
from __future__ import annotations

from dataclasses import dataclass


def _is_cf(*values) -> bool:
    try:
        from ngsolve import CoefficientFunction
    except ImportError:  # pragma: no cover - ngsolve is a dependency
        return False
    return any(isinstance(v, CoefficientFunction) for v in values)


def _sqrt(a):
    if _is_cf(a):
        from ngsolve import sqrt

        return sqrt(a)
    import numpy as np

    return np.sqrt(a)


def smooth_positive_part(a, delta):
    """max(a, 0) rounded over |a| < delta: (a + sqrt(a^2 + delta^2)) / 2 (error <= delta/2)."""
    return 0.5 * (a + _sqrt(a * a + delta * delta))


def smooth_minimum(a, b, delta):
    """min(a, b) rounded over |a - b| < delta: (a + b - sqrt((a - b)^2 + delta^2)) / 2."""
    return 0.5 * (a + b - _sqrt((a - b) ** 2 + delta * delta))


def smooth_positive_part_partials(a, delta):
    """(d/da, d/ddelta) of ``smooth_positive_part``."""
    root = _sqrt(a * a + delta * delta)
    return 0.5 * (1.0 + a / root), 0.5 * delta / root


def smooth_minimum_partials(a, b, delta):
    """(d/da, d/db, d/ddelta) of ``smooth_minimum``."""
    root = _sqrt((a - b) ** 2 + delta * delta)
    return 0.5 * (1.0 - (a - b) / root), 0.5 * (1.0 + (a - b) / root), -0.5 * delta / root


@dataclass(frozen=True)
class FrictionLaw:
    v_reg: float  # regularisation velocity, m/s

    name = "law"
    uses_a_f = False       # the coefficient takes a_f ((3.15) or a number)
    uses_pressure = False  # the coefficient takes the contact pressure
    uses_k = False         # the coefficient takes the shear flow stress k

    def limit(self, *, pressure=None, k=None):
        """Shear stress magnitude of a sliding contact (the rate-independent laws)."""
        raise NotImplementedError

    def limit_partials(self, *, pressure=None, k=None):
        """(d limit/d pressure, d limit/d k)."""
        raise NotImplementedError

    def coefficient(self, slip2, *, a_f=None, m=None, pressure=None, k=None):
        """Secant coefficient k_f with T_tau = -k_f v_s (rate-independent laws)."""
        return self.limit(pressure=pressure, k=k) * (slip2 + self.v_reg**2) ** -0.5

    def coefficient_partials(self, slip2, *, a_f=None, m=None, pressure=None, k=None):
        """(d k_f/d slip2, d k_f/d pressure, d k_f/d k): the friction part of Newton's
        Jacobian, written out (the symbolic derivative on the element boundaries cost 5 times
        the rest of the Jacobian's assembly)."""
        g = (slip2 + self.v_reg**2) ** -0.5
        lim = self.limit(pressure=pressure, k=k)
        d_p, d_k = self.limit_partials(pressure=pressure, k=k)
        return -0.5 * lim * g * g * g, d_p * g, d_k * g

    def shear(self, slip, **kw):
        """Shear traction on the plate along the roll tangent, for a scalar slip velocity."""
        return -self.coefficient(slip * slip, **kw) * slip

    def power_density(self, slip, **kw):
        """Friction dissipation -T_tau . v_s = k_f v_s^2 >= 0."""
        return self.coefficient(slip * slip, **kw) * slip * slip


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
