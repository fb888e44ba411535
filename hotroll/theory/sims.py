"""Sims' (1954) closed form for hot rolling with sticking friction.

R. B. Sims, "The calculation of roll force and torque in hot rolling mills",
Proc. Inst. Mech. Eng. 168 (1954) 191-200.

Sims integrates Orowan's equation under four assumptions: sticking friction (tau = k),
small angles (sin phi ~ tan phi ~ phi, cos phi ~ 1, h = h1 + R phi^2, alpha = sqrt(dh / R)),
constant (mean) k, and Orowan's inhomogeneous yield condition for sticking, p - q = (pi/4) 2k.
With a = sqrt(R / h1) the pressure is

    exit zone   p / 2k = pi/4 + (pi/4) ln(h / h1) + a atan(a phi)
    entry zone  p / 2k = pi/4 + (pi/4) ln(h / h0) + a [atan(a alpha) - atan(a phi)]

(the boundary value at both ends is (pi/4) 2k, not 2k).  Equating them gives

    phi_n = sqrt(h1/R) tan[ atan(sqrt(r/(1-r))) / 2 + (pi/8) sqrt(h1/R) ln(1 - r) ],  r = dh/h0,

and F = R int_0^alpha p dphi = 2k sqrt(R dh) Q_p with

    Q_p = (pi/2) c atan(1/c) - pi/4 - c a ln(h_n/h1) + (c a / 2) ln(1/(1-r)),  c = sqrt((1-r)/r),

h_n = h1 + R phi_n^2.  Q_p is exactly (1/alpha) int (p/2k) dphi (checked symbolically by
integration of the two branches; tests check it against the slab solver run with the same
assumptions), so the stress multiplying Q_p is the mean plane-strain flow stress
2k = 2 sigma_f / sqrt(3), not sigma_f (which would give a force 13.4 % lower).

Torque per roll from the sticking shear:  T = R^2 int (-s) k dphi = 2 R^2 k (alpha/2 - phi_n),
which is Sims' torque formula.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from hotroll.theory.slab import SQRT3, check_number, check_pass


@dataclass(frozen=True)
class SimsResult:
    """Sims' closed form for one pass, per unit width."""

    force: float              # N/m
    torque: float             # N m/m, per roll
    neutral_angle: float      # rad
    neutral_thickness: float  # m, h1 + R phi_n^2
    forward_slip: float       # h_n / h1 - 1 (small-angle form of h_n cos phi_n / h1 - 1)
    force_factor: float       # Q_p
    mean_pressure: float      # Pa, F / L
    contact_length: float     # m, sqrt(R dh)
    contact_angle: float      # rad, sqrt(dh / R)


def sims_neutral_angle(roll_radius: float, h0: float, h1: float) -> float:
    """Sims' neutral angle phi_n (rad) for sticking friction, no tensions."""
    R, h0, h1 = check_pass(roll_radius, h0, h1)
    r = (h0 - h1) / h0
    s = math.sqrt(h1 / R)
    phin = s * math.tan(0.5 * math.atan(math.sqrt(r / (1.0 - r))) + math.pi / 8.0 * s * math.log1p(-r))
    if phin <= 0.0:
        raise ValueError(f"Sims' neutral angle is {phin:g} <= 0 for R/h1 = {R / h1:g}, "
                         f"r = {r:g}: outside the range of the formula")
    return phin


def sims_force_factor(roll_radius: float, h0: float, h1: float) -> float:
    """Sims' Q_p = F / (2k sqrt(R dh))."""
    R, h0, h1 = check_pass(roll_radius, h0, h1)
    r = (h0 - h1) / h0
    c = math.sqrt((1.0 - r) / r)
    a = math.sqrt(R / h1)
    hn = h1 + R * sims_neutral_angle(R, h0, h1) ** 2
    return (math.pi / 2.0 * c * math.atan(1.0 / c) - math.pi / 4.0
            - c * a * math.log(hn / h1) - 0.5 * c * a * math.log1p(-r))


def sims(roll_radius: float, h0: float, h1: float, mean_flow_stress: float) -> SimsResult:
    """Roll force, torque and neutral angle after Sims (1954).

    mean_flow_stress is the uniaxial flow stress sigma_f averaged over the pass (Pa);
    2k = 2 sigma_f / sqrt(3) multiplies Q_p.
    """
    R, h0, h1 = check_pass(roll_radius, h0, h1)
    sf = check_number("mean_flow_stress", mean_flow_stress, low=0.0, low_open=True)
    two_k = 2.0 * sf / SQRT3
    dh = h0 - h1
    L, alpha = math.sqrt(R * dh), math.sqrt(dh / R)
    phin = sims_neutral_angle(R, h0, h1)
    hn = h1 + R * phin ** 2
    qp = sims_force_factor(R, h0, h1)
    force = two_k * L * qp
    torque = R ** 2 * two_k * (alpha / 2.0 - phin)
    return SimsResult(force=force, torque=torque, neutral_angle=phin, neutral_thickness=hn,
                      forward_slip=hn / h1 - 1.0, force_factor=qp, mean_pressure=force / L,
                      contact_length=L, contact_angle=alpha)
