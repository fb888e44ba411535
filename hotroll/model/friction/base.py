"""The interface of the friction laws on the roll contact (one for the weak form and the
post-processing) and the smoothing they share; the laws are one module each
(``viscoplastic.py``, ``coulomb.py``, ``tresca.py``), registered in ``registry.py``.

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


def is_cf(*values) -> bool:
    try:
        from ngsolve import CoefficientFunction
    except ImportError:  # pragma: no cover - ngsolve is a dependency
        return False
    return any(isinstance(v, CoefficientFunction) for v in values)


def sqrt_any(a):
    if is_cf(a):
        from ngsolve import sqrt

        return sqrt(a)
    import numpy as np

    return np.sqrt(a)


def smooth_positive_part(a, delta):
    """max(a, 0) rounded over |a| < delta: (a + sqrt(a^2 + delta^2)) / 2 (error <= delta/2)."""
    return 0.5 * (a + sqrt_any(a * a + delta * delta))


def smooth_minimum(a, b, delta):
    """min(a, b) rounded over |a - b| < delta: (a + b - sqrt((a - b)^2 + delta^2)) / 2."""
    return 0.5 * (a + b - sqrt_any((a - b) ** 2 + delta * delta))


def smooth_positive_part_partials(a, delta):
    """(d/da, d/ddelta) of ``smooth_positive_part``."""
    root = sqrt_any(a * a + delta * delta)
    return 0.5 * (1.0 + a / root), 0.5 * delta / root


def smooth_minimum_partials(a, b, delta):
    """(d/da, d/db, d/ddelta) of ``smooth_minimum``."""
    root = sqrt_any((a - b) ** 2 + delta * delta)
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


