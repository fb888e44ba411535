"""Slab model of asymmetric flat rolling (two rolls of different radius, speed and friction).

Per unit width, SI units (m, m/s, Pa, N/m, N m/m).  The equations are those of
/work/shared/notes/asymmetric-rolling.md section 1 ("the note"), a von Karman / Orowan
homogeneous-compression slab model with two rolls derived there [E: the note author's own
derivation, not a published source].  Roll 1 is the upper roll, roll 2 the lower one.

* x runs in the rolling direction, x = 0 on the line of roll centres (the exit), -L the entry.
* The slab velocity is u = q / h (q the flux); roll i slips by D_i = U_i - u / cos(phi_i) and
  its neutral point x_ni is where D_i = 0, i.e. q = U_i cos(phi_i) h(x_ni) (note 1.2), clipped
  to [-L, 0].  The shear tau_i on the strip is positive forward, i.e. for x < x_ni.
* Horizontal balance with S = sigma_x h (tension positive), p1 = p2 = p (note 1.3), and the
  yield condition p = 2k - S / h give, with sigma = S / h,

      d sigma / dx = -(2k h' + tau_1 + tau_2) / h,      sigma(-L) = t_b,  sigma(0) = t_f.

* Roll force F = int p dx; the vertical force on roll i with its shear's projection
  F1 = int (p - tau_1 y1') dx, F2 = int (p + tau_2 y2') dx (note 1.6: read F, not F1 - F2);
  torque to drive roll i T_i = R_i int tau_i ds (ds = dx / cos phi_i); forward slip per roll
  f_i = v1 / U_i - 1, v1 = q / h1.

:func:`tresca_closed_form` is the note's small-angle Tresca solution (1.8, (star));
:func:`solve_asymmetric` shoots on q for Coulomb, Tresca and the
project's viscoplastic law on exact (or parabolic) arcs, optionally with the note's Variant C
yield condition (1.10).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from hotroll.model.friction.base import FrictionLaw
from hotroll.model.friction.coulomb import CoulombFriction
from hotroll.model.friction.tresca import TrescaFriction
from hotroll.model.friction.viscoplastic import ViscoplasticFriction
from hotroll.theory.slab import NoNeutralPointError, check_number


@dataclass(frozen=True)
class AsymmetricResult:
    """One asymmetric pass, per unit width.  Roll 1 upper, roll 2 lower; x < 0 upstream."""

    contact_length: float          # m, L (projected)
    x_n1: float                    # m, neutral point of roll 1 (in [-L, 0])
    x_n2: float                    # m, neutral point of roll 2
    cross_shear_length: float      # m, |x_n1 - x_n2| (zone II)
    force: float                   # N/m, int p dx
    torque1: float                 # N m/m, to drive roll 1 (< 0: the strip drives the roll)
    torque2: float                 # N m/m, to drive roll 2
    exit_speed: float              # m/s, v1 = q / h1
    flux: float                    # m^2/s, q
    forward_slip1: float           # 1, v1 / U1 - 1
    forward_slip2: float           # 1, v1 / U2 - 1
    saturated: bool                # the faster roll's neutral point at the exit: zone III absent
    shear_force1: float            # N/m, int tau_1 dx (horizontal, on the strip, forward +)
    shear_force2: float            # N/m, int tau_2 dx
    pressure_force_x: float        # N/m, int p |h'| dx (the rolls' pressure pushing back)
    x: np.ndarray                  # m, profile abscissae, entry to exit, switch points included
    pressure: np.ndarray           # Pa, p(x)


@dataclass(frozen=True)
class TrescaClosedForm(AsymmetricResult):
    """The small-angle Tresca closed form (note 1.8); r_star the saturation speed ratio."""

    r_star: float = math.nan       # 1, U_fast / U_slow above which zone III vanishes (inf: never);
    #                                the faster roll's (roll 1's at equal speeds)
    effective_radius: float = math.nan   # m, R_e = 2 R1 R2 / (R1 + R2)


# ----------------------------------------------------------------------------- input checks
def check_pass_inputs(h0, h1, k, radii, speeds, back_tension, front_tension):
    """Validated (h0, h1, k, (R1, R2), (U1, U2), t_b, t_f); ValueError naming the argument."""
    h0, h1, R = check_geometry(h0, h1, radii)
    k = check_number("k", k, low=0.0, low_open=True)
    U = tuple(check_number(n, v, low=0.0, low_open=True) for n, v in zip(("U1", "U2"), speeds))
    tb = check_number("back_tension", back_tension, high=2.0 * k, high_open=True)
    tf = check_number("front_tension", front_tension, high=2.0 * k, high_open=True)
    return h0, h1, k, R, U, tb, tf


def check_geometry(h0, h1, radii):
    """Validated (h0, h1, (R1, R2)): 0 < h1 < h0, each radius above the draft h0 - h1."""
    h0 = check_number("h0", h0, low=0.0, low_open=True)
    h1 = check_number("h1", h1, low=0.0, low_open=True)
    if h1 >= h0:
        raise ValueError(f"h1 must be in (0, h0) = (0, {h0:g}) m, got {h1:g} m")
    draft = h0 - h1
    R = tuple(check_number(n, v, low=0.0, low_open=True) for n, v in zip(("R1", "R2"), radii))
    for name, value in zip(("R1", "R2"), R):
        if value <= draft:
            raise ValueError(f"{name} must be > the draft h0 - h1 = {draft:g} m, got {value:g} m")
    return h0, h1, R


# ----------------------------------------------------------------------------- closed form
def tresca_closed_form(*, h0: float, h1: float, k: float, R1: float, R2: float, U1: float,
                       U2: float, m1: float, m2: float, back_tension: float = 0.0,
                       front_tension: float = 0.0, n_profile: int = 201) -> TrescaClosedForm:
    """Note 1.8: small angles (cos phi = 1, h = h1 + x^2 / R_e), Tresca tau_i = m_i k.

    Zone pressure p = p_a + 2k ln(h/h_a) + c k (G(x) - G(x_a)), c = sum of +-m_i by zone,
    G(x) = int_0^x dx/h = sqrt(R_e/h1) atan(x / sqrt(R_e h1)); the neutral points solve (star)
    m1 G(x_n1) + m2 G(x_n2) = (m1 + m2) G(-L)/2 + ln(h0/h1) + (t_b - t_f)/(2k) with
    q = U_i h(x_ni) (clipped to [-L, 0]), solved for q by Brent's method (either roll may be
    the faster); T_i = R_i m_i k (L + 2 x_ni); F = int p dx in closed form.  Inputs:
    thicknesses h0 > h1 (m), shear flow stress k (Pa), radii R1, R2 (m), surface
    speeds U1, U2 (m/s), friction factors m1, m2 in (0, 1], tensions (Pa, tensile +).
    """
    h0, h1, k, (R1, R2), (U1, U2), tb, tf = check_pass_inputs(
        h0, h1, k, (R1, R2), (U1, U2), back_tension, front_tension)
    m1 = check_number("m1", m1, 0.0, 1.0, low_open=True)
    m2 = check_number("m2", m2, 0.0, 1.0, low_open=True)
    Re = 2.0 * R1 * R2 / (R1 + R2)
    L = math.sqrt(Re * (h0 - h1))
    c = math.sqrt(Re * h1)
    h = lambda x: h1 + x * x / Re
    G = lambda x: Re / c * math.atan(x / c)

    rhs = 0.5 * (m1 + m2) * G(-L) + math.log(h0 / h1) + (tb - tf) / (2.0 * k)
    if rhs >= 0.0:
        raise NoNeutralPointError("no steady state: the strip skids (neutral points at the exit); "
                                  "friction too low or back tension too high", "exit")
    if rhs <= (m1 + m2) * G(-L):
        raise NoNeutralPointError("no steady state: the strip is pulled through faster than both "
                                  "rolls (neutral points at the entry); front tension too high",
                                  "entry")
    xn = lambda q, U: -math.sqrt(min(max(Re * (q / U - h1), 0.0), L * L))  # kinematics, clipped
    star = lambda q: m1 * G(xn(q, U1)) + m2 * G(xn(q, U2)) - rhs
    q_lo, q_hi = h1 * min(U1, U2), h0 * max(U1, U2)
    q = brentq(star, q_lo, q_hi, xtol=1e-15 * q_hi, rtol=4 * np.finfo(float).eps, maxiter=500)
    x1, x2 = xn(q, U1), xn(q, U2)

    # zones between the sorted switch points; c_zone = m1 s1 + m2 s2, s_i = +1 upstream of x_ni
    edges = [-L] + sorted([x1, x2]) + [0.0]
    pa, F, Fx = 2.0 * k - tb, 0.0, 0.0
    profile_x, profile_p = [], []
    for xa, xb in zip(edges[:-1], edges[1:]):
        mid = 0.5 * (xa + xb)
        cz = m1 * (1.0 if mid < x1 else -1.0) + m2 * (1.0 if mid < x2 else -1.0)
        A = pa - 2.0 * k * math.log(h(xa)) - cz * k * G(xa)   # p = A + 2k ln h + cz k G
        P = lambda x: (A * x + 2.0 * k * (x * math.log(h(x)) - 2.0 * x + 2.0 * c * math.atan(x / c))
                       + cz * k * Re / c * (x * math.atan(x / c) - 0.5 * c * math.log(x * x + c * c)))
        Ph = lambda x: A * h(x) + 2.0 * k * (h(x) * math.log(h(x)) - h(x)) + cz * k * (G(x) * h(x) - x)
        F += P(xb) - P(xa)                       # int p dx
        Fx -= Ph(xb) - Ph(xa)                    # int p |h'| dx, h' < 0 upstream
        xs = np.linspace(xa, xb, max(2, int(n_profile * (xb - xa) / L)))
        profile_x.append(xs)
        profile_p.append([A + 2.0 * k * math.log(h(x)) + cz * k * G(x) for x in xs])
        pa = A + 2.0 * k * math.log(h(xb)) + cz * k * G(xb)

    fast_x = x1 if U1 >= U2 else x2
    m_slow, U_fast, U_slow = (m2, U1, U2) if U1 >= U2 else (m1, U2, U1)
    g_star = rhs / m_slow                         # m_slow G(x_slow*) = rhs with x_fast = 0
    r_star = h(c * math.tan(g_star * c / Re)) / h1 if g_star >= G(-L) else math.inf
    v1 = q / h1
    return TrescaClosedForm(
        contact_length=L, x_n1=x1, x_n2=x2, cross_shear_length=abs(x1 - x2), force=F,
        torque1=R1 * m1 * k * (L + 2.0 * x1), torque2=R2 * m2 * k * (L + 2.0 * x2),
        exit_speed=v1, flux=q, forward_slip1=v1 / U1 - 1.0, forward_slip2=v1 / U2 - 1.0,
        saturated=fast_x == 0.0 and U_fast > U_slow, shear_force1=m1 * k * (L + 2.0 * x1),
        shear_force2=m2 * k * (L + 2.0 * x2), pressure_force_x=Fx,
        x=np.concatenate(profile_x), pressure=np.concatenate(profile_p), r_star=r_star,
        effective_radius=Re)


# ----------------------------------------------------------------------------- shooting
@dataclass(frozen=True)
class Roll:
    """A work roll: radius (m), surface speed U = omega R (m/s) and the friction law on its
    contact, one of the project's laws (hotroll.model.friction, the FE's forms and parameter
    names): ``TrescaFriction(v_reg, factor=)`` tau = factor k, ``CoulombFriction(v_reg, mu=,
    rounding=)`` tau = min(mu p, k) (rounding 0: the sharp law), ``ViscoplasticFriction(v_reg,
    K=, m=)`` tau = a_f K |D|^m (K in Pa s^m, ``a_f`` in m^-m given here).  v_reg (m/s) > 0
    regularises the slip as the FE does; 0 is the law itself."""

    radius: float
    speed: float
    friction: FrictionLaw
    a_f: float | None = None


@dataclass(frozen=True)
class AsymmetricSlabResult(AsymmetricResult):
    """The shooting solution (note 1.5); force1, force2 with the shear's vertical projection."""

    force1: float = math.nan       # N/m, int (p - tau_1 y1') dx, on roll 1
    force2: float = math.nan       # N/m, int (p + tau_2 y2') dx, on roll 2
    geometry: str = "arc"


def check_roll(name: str, roll: Roll, yield_condition: str) -> Roll:
    """A Roll whose law and parameters are in range (ValueError naming ``name.field``)."""
    if not isinstance(roll, Roll):
        raise ValueError(f"{name} must be a Roll(radius, speed, friction, a_f), got {roll!r}")
    law = roll.friction
    check_number(f"{name}.friction.v_reg", law.v_reg, low=0.0)
    if isinstance(law, TrescaFriction):
        check_number(f"{name}.friction.factor", law.factor, 0.0, 1.0, low_open=True)
    elif isinstance(law, CoulombFriction):
        check_number(f"{name}.friction.mu", law.mu, 0.0, 2.0, low_open=True)
        check_number(f"{name}.friction.rounding", law.rounding, low=0.0)
        if yield_condition != "homogeneous":
            raise ValueError(f"{name}.friction: yield_condition {yield_condition!r} takes a shear "
                             "that does not depend on the pressure (Tresca or viscoplastic), "
                             "got Coulomb")
    elif isinstance(law, ViscoplasticFriction):
        check_number(f"{name}.friction.K", law.K, low=0.0, low_open=True)
        check_number(f"{name}.friction.m", law.m, 0.0, 1.0, low_open=True)
        if roll.a_f is None:
            raise ValueError(f"{name}.a_f must be given (> 0, m^-m) for the viscoplastic law")
        check_number(f"{name}.a_f", roll.a_f, low=0.0, low_open=True)
    else:
        raise ValueError(f"{name}.friction must be TrescaFriction, CoulombFriction or "
                         f"ViscoplasticFriction (hotroll.model.friction), got {law!r}")
    return roll


def shear_magnitude(roll: Roll, slip: float, p: float, k: float) -> float:
    """|tau| (Pa) of the roll's law at slip speed |slip| (m/s), pressure p, shear flow stress k."""
    law, s2 = roll.friction, slip * slip
    if law.uses_a_f:                                   # viscoplastic (2.29a)
        return 0.0 if s2 == 0.0 else float(law.coefficient(s2, a_f=roll.a_f)) * abs(slip)
    if law.v_reg == 0.0:                               # the sign comes from the zone
        return float(law.limit(pressure=p, k=k))
    return float(law.coefficient(s2, pressure=p, k=k)) * abs(slip)


def mean_yield_shear(tau1: float, tau2: float, k: float) -> float:
    """Variant C (note 1.10): the thickness mean of sqrt(k^2 - s_xy^2), s_xy linear from -tau2
    (lower surface) to tau1 (upper surface), |s_xy| capped at k."""
    a, b = -tau2, tau1
    A = lambda s: 0.5 * (s * math.sqrt(k * k - s * s) + k * k * math.asin(s / k))
    clip = lambda s: min(max(s, -k), k)
    if abs(b - a) <= 1e-9 * k:
        return math.sqrt(k * k - clip(0.5 * (a + b)) ** 2)
    return (A(clip(b)) - A(clip(a))) / (b - a)


def draft_split(R1: float, R2: float, h0: float, h1: float, geometry: str = "arc"):
    """(dh1, dh2) in m: the drafts the two rolls take so that both contacts start at x = -L
    (note 1.1: dh_i = R_i - sqrt(R_i^2 - L^2); parabolic dh1 = dh R2 / (R1 + R2)).  The entry
    centreline then lies dh1 - h0/2 above roll 1's lowest point."""
    h0, h1, (R1, R2) = check_geometry(h0, h1, (R1, R2))
    if geometry not in ("arc", "parabolic"):
        raise ValueError(f"geometry must be 'arc' or 'parabolic', got {geometry!r}")
    gap = _Gap(R1, R2, h0, h1, geometry == "parabolic")
    return gap.rise(-gap.L, 0), gap.rise(-gap.L, 1)


class _Gap:
    """Roll-gap geometry: exact arcs or parabolas (h = h1 + x^2 / R_e), note 1.1."""

    def __init__(self, R1, R2, h0, h1, parabolic):
        self.R, self.h1, self.parabolic = (R1, R2), h1, parabolic
        if parabolic:
            self.L = math.sqrt(2.0 * R1 * R2 / (R1 + R2) * (h0 - h1))
        else:  # h(-R_min) >= h1 + R_min > h0 since R_i > h0 - h1
            self.L = -brentq(lambda x: self.h(x) - h0, -min(R1, R2), 0.0, xtol=1e-16, rtol=1e-15)

    def rise(self, x, i):
        """Roll i's surface above (1) or below (2) its point on the line of centres, m."""
        R = self.R[i]
        return 0.5 * x * x / R if self.parabolic else R - math.sqrt(R * R - x * x)

    def h(self, x):
        return self.h1 + self.rise(x, 0) + self.rise(x, 1)

    def slopes_cosines(self, x):
        """(y1', y2', cos phi1, cos phi2); y1' < 0 < y2' upstream."""
        R1, R2 = self.R
        if self.parabolic:
            return x / R1, -x / R2, 1.0, 1.0
        w1, w2 = math.sqrt(R1 * R1 - x * x), math.sqrt(R2 * R2 - x * x)
        return x / w1, -x / w2, w1 / R1, w2 / R2


class _Shot:
    """The slab ODE for one trial flux q: neutral points, zones, integrals (note 1.5)."""

    def __init__(self, gap, rolls, k, tb, rtol, shear_averaged):
        self.gap, self.rolls, self.k, self.tb, self.rtol = gap, rolls, k, tb, rtol
        self.shear_averaged = shear_averaged

    def neutral_point(self, q, i):
        gap, U = self.gap, self.rolls[i].speed
        g = lambda x: q / gap.h(x) - U * gap.slopes_cosines(x)[2 + i]
        if g(-gap.L) >= 0.0:
            return -gap.L
        if g(0.0) <= 0.0:
            return 0.0
        return brentq(g, -gap.L, 0.0, xtol=1e-15 * gap.L, rtol=4 * np.finfo(float).eps)

    def rhs(self, q, s1, s2):
        """y = [sigma, int p, int tau1, int tau2, int tau1 ds, int tau2 ds, int -tau1 y1',
        int tau2 y2', int p |h'|] (all dx); s_i the zone's shear sign of roll i."""
        gap, (r1, r2), k = self.gap, self.rolls, self.k

        def f(x, y):
            h = gap.h(x)
            y1p, y2p, c1, c2 = gap.slopes_cosines(x)
            u = q / h
            d1, d2 = r1.speed - u / c1, r2.speed - u / c2
            if self.shear_averaged:   # Variant C: shear independent of p
                t1, t2 = s1 * shear_magnitude(r1, d1, 0.0, k), s2 * shear_magnitude(r2, d2, 0.0, k)
                k_e = mean_yield_shear(t1, t2, k)
            else:
                k_e = k
            p = 2.0 * k_e - y[0]
            if not self.shear_averaged:
                t1, t2 = s1 * shear_magnitude(r1, d1, p, k), s2 * shear_magnitude(r2, d2, p, k)
            hp = y1p - y2p
            return [-(2.0 * k_e * hp + t1 + t2) / h, p, t1, t2, t1 / c1, t2 / c2, -t1 * y1p,
                    t2 * y2p, -p * hp]

        return f

    def run(self, q, dense=False):
        """(x_n1, x_n2, zone solutions, y at the exit)."""
        L, k = self.gap.L, self.k
        x1, x2 = self.neutral_point(q, 0), self.neutral_point(q, 1)
        edges = [-L] + sorted([x1, x2]) + [0.0]
        y = [self.tb] + [0.0] * 8
        atol = self.rtol * np.array([k] + [k * L] * 8)
        sols = []
        for xa, xb in zip(edges[:-1], edges[1:]):
            if xb - xa <= 1e-14 * L:
                continue
            mid = 0.5 * (xa + xb)
            f = self.rhs(q, 1.0 if mid < x1 else -1.0, 1.0 if mid < x2 else -1.0)
            sol = solve_ivp(f, (xa, xb), y, method="DOP853", rtol=self.rtol, atol=atol,
                            dense_output=dense)
            if not sol.success:
                raise RuntimeError(f"slab ODE integration failed: {sol.message}")
            y = sol.y[:, -1]
            sols.append((sol, f))
        return x1, x2, sols, y


def solve_asymmetric(upper: Roll, lower: Roll, h0: float, h1: float, k: float, *,
                     back_tension: float = 0.0, front_tension: float = 0.0,
                     geometry: str = "arc", yield_condition: str = "homogeneous",
                     n_profile: int = 201, rtol: float = 1e-10) -> AsymmetricSlabResult:
    """Shooting solution of the asymmetric slab model (note 1.3-1.6).

    upper, lower: the two rolls (``Roll``); h0 > h1 thicknesses (m); k shear flow stress (Pa),
    constant; tensions (Pa, tensile +).  ``geometry``: "arc" (exact circles) or "parabolic"
    (h = h1 + x^2 / R_e, cos phi = 1: the closed form's).  ``yield_condition``: "homogeneous"
    (p = 2k - sigma) or "shear_averaged" (note 1.10 Variant C: 2k -> 2 mean sqrt(k^2 - s_xy^2);
    Tresca and viscoplastic only).  Brent's method on sigma(0; q) = t_f, q in
    [0.5 U_min h1, 1.5 U_max h0].  Raises ValueError for bad input, NoNeutralPointError when no
    flux satisfies both boundary conditions.
    """
    if yield_condition not in ("homogeneous", "shear_averaged"):
        raise ValueError("yield_condition must be 'homogeneous' or 'shear_averaged', "
                         f"got {yield_condition!r}")
    rolls = (check_roll("upper", upper, yield_condition), check_roll("lower", lower, yield_condition))
    h0, h1, k, (R1, R2), (U1, U2), tb, tf = check_pass_inputs(
        h0, h1, k, (upper.radius, lower.radius), (upper.speed, lower.speed), back_tension,
        front_tension)
    rolls = tuple(Roll(R, U, r.friction, r.a_f) for R, U, r in zip((R1, R2), (U1, U2), rolls))
    if geometry not in ("arc", "parabolic"):
        raise ValueError(f"geometry must be 'arc' or 'parabolic', got {geometry!r}")
    rtol = check_number("rtol", rtol, 1e-13, 1e-4)
    gap = _Gap(R1, R2, h0, h1, geometry == "parabolic")
    shot = _Shot(gap, rolls, k, tb, rtol, yield_condition == "shear_averaged")

    residual = lambda q: shot.run(q)[3][0] - tf
    q_lo, q_hi = 0.5 * min(U1, U2) * h1, 1.5 * max(U1, U2) * h0
    if residual(q_lo) >= 0.0:
        raise NoNeutralPointError("no steady state: the strip skids (both rolls drag it over the "
                                  "whole arc and the exit stress still exceeds front_tension); "
                                  "friction too low or back tension too high", "exit")
    if residual(q_hi) <= 0.0:
        raise NoNeutralPointError("no steady state: the strip is pulled through faster than both "
                                  "rolls; front tension too high", "entry")
    q = brentq(residual, q_lo, q_hi, xtol=1e-14 * q_hi, rtol=4 * np.finfo(float).eps)
    x1, x2, sols, y = shot.run(q, dense=True)

    L = gap.L
    xs, ps = [], []
    for sol, f in sols:
        xa, xb = sol.t[0], sol.t[-1]
        grid = np.linspace(xa, xb, max(2, int(n_profile * (xb - xa) / L)))
        xs.append(grid)
        ps.append([f(x, sol.sol(x))[1] for x in grid])
    v1 = q / h1
    fast_x = x1 if U1 >= U2 else x2
    return AsymmetricSlabResult(
        contact_length=L, x_n1=x1, x_n2=x2, cross_shear_length=abs(x1 - x2), force=y[1],
        torque1=R1 * y[4], torque2=R2 * y[5], exit_speed=v1, flux=q,
        forward_slip1=v1 / U1 - 1.0, forward_slip2=v1 / U2 - 1.0,
        saturated=fast_x == 0.0 and U1 != U2, shear_force1=y[2], shear_force2=y[3],
        pressure_force_x=y[8], x=np.concatenate(xs), pressure=np.concatenate(ps),
        force1=y[1] + y[6], force2=y[1] + y[7], geometry=geometry)
