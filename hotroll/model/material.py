"""Norton-Hoff viscoplastic law, report (2.16), (2.17), (2.20), (2.21).

The functions work on numbers, numpy arrays and NGSolve CoefficientFunctions alike, and take
the exponent ``m`` as an argument so that the first Picard iterate can use m = 1 (Section 3.4).
"""
from __future__ import annotations

from dataclasses import dataclass

SQRT3 = 3.0**0.5


@dataclass(frozen=True)
class NortonHoff:
    """s = 2K (sqrt3 edot)^(m-1) eps_dot (2.20), regularised with eps0 (2.21)."""

    K: float            # consistency, Pa s^m
    m: float            # strain-rate sensitivity, 0 < m <= 1
    eps0: float = 1e-4  # regularisation strain rate, 1/s

    def viscosity(self, edot2, m=None, K=None):
        """Secant viscosity mu with s = mu eps_dot: 2K sqrt3^(m-1) (eps0^2 + edot^2)^((m-1)/2)."""
        m = self.m if m is None else m
        K = self.K if K is None else K
        return 2.0 * K * SQRT3 ** (m - 1.0) * (self.eps0**2 + edot2) ** ((m - 1.0) / 2.0)

    def sigma_ef(self, edot, K=None):
        """Effective (von Mises) stress K 3^((m+1)/2) edot^m, (2.17)."""
        K = self.K if K is None else K
        return K * 3.0 ** ((self.m + 1.0) / 2.0) * edot**self.m

    def sigma_ef_reg(self, edot2, m=None, K=None):
        """Effective stress of the regularised law (2.21): 3/2 mu sqrt(eps0^2 + edot^2)
        = K 3^((m+1)/2) (eps0^2 + edot^2)^(m/2); ``edot2`` the squared strain rate (2.16)."""
        m = self.m if m is None else m
        K = self.K if K is None else K
        return K * 3.0 ** ((m + 1.0) / 2.0) * (self.eps0**2 + edot2) ** (m / 2.0)

    def power_density(self, edot, K=None):
        """Plastic dissipation s:eps_dot = K (sqrt3 edot)^(m+1) (potential of Remark 2.4 times p)."""
        K = self.K if K is None else K
        return K * (SQRT3 * edot) ** (self.m + 1.0)


def edot_squared(eps):
    """Squared effective strain rate 2/3 eps:eps, (2.16); ``eps`` a 2x2 tensor (plane strain).

    Works for NGSolve matrix-valued CoefficientFunctions (``InnerProduct``) and numpy arrays.
    """
    try:
        from ngsolve import InnerProduct

        return 2.0 / 3.0 * InnerProduct(eps, eps)
    except (ImportError, TypeError, AttributeError):  # numpy (..., 2, 2)
        import numpy as np

        return 2.0 / 3.0 * np.einsum("...ij,...ij->...", eps, eps)
