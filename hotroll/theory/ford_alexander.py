"""Ford and Alexander's simplified hot-rolling load formula (sticking friction).

H. Ford and J. M. Alexander, "Simplified hot-rolling calculations",
J. Inst. Metals 92 (1963-64) 397-404.  The form used here, as it is commonly quoted,

    p_mean / 2k = pi/4 + L / (4 h_mean),   L = sqrt(R dh),  h_mean = (h0 + h1) / 2,
    F = p_mean L   (per unit width),

could not be checked against the paper itself (not readable here).  What can be checked, and is
tested: it is the linearisation of Sims' Q_p -- Orowan's inhomogeneity offset pi/4 plus the
mean of a sticking-friction hill of slope 2k / h over a contact of length L with the neutral
point near its middle (L / 4h) -- so it reproduces Sims within a few % for ordinary passes.
It keeps Sims' assumptions: sticking friction, rigid roll, constant mean 2k = 2 sigma_f / sqrt(3).
Like every homogeneous slab formula it does NOT reproduce the rise of the load for thick
plates (L / h_mean below about 0.5-1), where slip-line fields show inhomogeneous,
indentation-like deformation; use it for L / h_mean of order 1 and above.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from hotroll.theory.slab import SQRT3, check_number, check_pass


@dataclass(frozen=True)
class FordAlexanderResult:
    force: float            # N/m
    mean_pressure: float    # Pa
    pressure_factor: float  # p_mean / 2k
    contact_length: float   # m, sqrt(R dh)
    l_over_h: float         # L / h_mean


def ford_alexander_factor(roll_radius: float, h0: float, h1: float) -> float:
    """p_mean / 2k = pi/4 + L / (4 h_mean)."""
    R, h0, h1 = check_pass(roll_radius, h0, h1)
    return math.pi / 4.0 + math.sqrt(R * (h0 - h1)) / (2.0 * (h0 + h1))


def ford_alexander(roll_radius: float, h0: float, h1: float,
                   mean_flow_stress: float) -> FordAlexanderResult:
    """Roll force per unit width after Ford & Alexander; mean_flow_stress is uniaxial (Pa)."""
    R, h0, h1 = check_pass(roll_radius, h0, h1)
    sf = check_number("mean_flow_stress", mean_flow_stress, low=0.0, low_open=True)
    L = math.sqrt(R * (h0 - h1))
    q = ford_alexander_factor(R, h0, h1)
    p = q * 2.0 * sf / SQRT3
    return FordAlexanderResult(force=p * L, mean_pressure=p, pressure_factor=q,
                               contact_length=L, l_over_h=2.0 * L / (h0 + h1))
