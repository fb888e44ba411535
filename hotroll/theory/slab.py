"""Slab (elementary) theory of plane-strain flat rolling, solved numerically.

Per unit width, SI units (m, s, Pa, N/m, N m/m, rad). Symmetric pass, two rigid rolls of
radius R; phi is the angle from the line of roll centres (0 at the exit, alpha at the entry);
h(phi) is the full strip thickness.

Equations (von Karman 1925 slab balance in Orowan's 1943 angular form, homogeneous compression):

* equilibrium of a vertical slab, both roll surfaces (Orowan's equation with exact geometry)

      d(q h)/dphi = 2 R (p sin(phi) + s tau cos(phi)),

  q = mean horizontal compressive stress, p = roll pressure, tau = interface shear,
  s = +1 between exit and neutral point (forward slip: the strip outruns the roll and the
  friction on it points to the entry), s = -1 between neutral point and entry;
* yield (Tresca / von Mises in plane strain, vertical stress taken equal to p as in von Karman
  and Bland & Ford 1948):  p - q = w 2k,  2k = 2 sigma_f / sqrt(3).  w = 1 is homogeneous
  compression; w = pi/4 is Orowan's inhomogeneity factor for sticking friction used by
  Sims (1954) -- offered only to reproduce Sims' closed form;
* boundary values q = -back_tension at the entry and q = -front_tension at the exit, i.e.
  p = w 2k_end - sigma_b and p = w 2k_end - sigma_f: the entry branch is integrated from alpha
  to 0, the exit branch from 0 to alpha, the neutral angle phi_n is where the two q h cross.

Flow stress and strain rate.  Inside the arc 2k is the flow stress at the local homogeneous
strain rate 2/sqrt3 v |dh/dx| / h (v = v1 h1 / h).  That rate is exactly 0 at the exit
(dh/dx = 0 there), so for a rate-dependent law (Norton-Hoff K edot^m, Hensel-Spittel
edot^(m3 + m8 T)) the local 2k vanishes at the exit: the exit yield condition would give p = 0
and refuse any front tension.  The yield condition AT THE TWO ENDS (the boundary pressures
p = w 2k_end - sigma_b / - sigma_f and the tension admissibility check sigma < w 2k_end) is
therefore evaluated, at the end's own strain and temperature, at the pass's mean equivalent
strain rate

    edot_mean = (2/sqrt3) ln(h0/h1) / t_c,    t_c = int_0^L dx / v = int_0^L h dx / (v1 h1),

the pass strain divided by the slab's own residence time in the gap (the time mean of the local
rate along the strip's path; closed-form t_c for both geometries).  It is the classical mean
strain rate of hot-rolling flow-stress models, strain / contact time with t_c ~ L/U, i.e.
(U/L) ln(h0/h1) (e.g. PyRolL, pyroll-project/pyroll-core, roll_pass hook ``strain_rate`` =
velocity / contact_length * strain_change), computed with the slab's own kinematics: it reduces
to the classical value when v = U and h = h1 along the arc, and it scales with v1 exactly like
the local rate (the iterated slip acts on both alike).  The local rate is kept everywhere
inside the arc, so the ODE, force, torque, neutral point and slip are those of the local-rate
model; only the two end samples of the pressure / 2k profiles carry 2k_end, so a plotted
profile jumps there (tension_pass example: exit 2k_end 207 MPa, local 2k 119 MPa one profile
step inside).  For a power-law rate the local 2k ~ phi^m drops to 0 in a thin layer at the
exit, where under front tension p = q + w 2k < 0 over a fraction ~ (sigma_f / 2k)^(1/m) of
the arc (~1e-8 for m = 0.13, sigma_f = 0.1 2k: negligible).  For a rate-independent law
2k_end equals the local 2k and every result is unchanged.

Geometry ``"arc"`` (default): h = h1 + 2R (1 - cos phi), alpha = arccos(1 - dh / 2R), exact
sin/cos above, force F = R int (p cos phi - s tau sin phi) dphi (vertical projection of pressure
and shear).  ``"small_angle"``: von Karman's / Sims' approximations sin phi ~ phi, cos phi ~ 1,
h = h1 + R phi^2, alpha = sqrt(dh / R), F = R int p dphi.

Torque per roll T = R^2 int (-s) tau dphi (the pressure passes through the roll axis, so only
the shear has a moment; exact for a rigid circular roll).  Forward slip (Ford's form): at the
neutral point the strip moves with the roll surface's horizontal speed U cos phi_n, so mass flux
v1 h1 = U cos(phi_n) h_n gives  f = (v1 - U) / U = h_n cos(phi_n) / h1 - 1.
Strain rates (local and mean) use v = v1 h1 / h with v1 = U (1 + f), f iterated to convergence
(``iterate_slip``; otherwise the no-slip estimate v1 = U).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from hotroll.model.flow_stress import finite

SQRT3 = math.sqrt(3.0)

FlowStress = Callable[[float, float, float], float]


class NoNeutralPointError(RuntimeError):
    """The entry and exit pressure branches do not cross: no steady rolling state.

    ``where == "exit"``: the strip skids (neutral point at or beyond the exit; too little
    friction or too much back tension).  ``where == "entry"``: the strip is pulled through
    faster than the rolls everywhere (too much front tension).
    """

    def __init__(self, message: str, where: str):
        super().__init__(message)
        self.where = where


# ----------------------------------------------------------------------------- friction laws
def check_pass(roll_radius, h0, h1):
    R = check_number("roll_radius", roll_radius, low=0.0, low_open=True)
    h0 = check_number("h0", h0, low=0.0, low_open=True)
    h1 = check_number("h1", h1, low=0.0, low_open=True)
    if h1 >= h0:
        raise ValueError(f"h1 must be in (0, h0) = (0, {h0:g}), got {h1:g}")
    if R <= h0 - h1:
        raise ValueError(f"roll_radius must be > draft h0 - h1 = {h0 - h1:g}, got {R:g}")
    return R, h0, h1


def check_number(name: str, value, low=None, high=None, low_open=False, high_open=False):
    v = finite(name, value)
    lo_ok = low is None or (v > low if low_open else v >= low)
    hi_ok = high is None or (v < high if high_open else v <= high)
    if not (lo_ok and hi_ok):
        lo = "-inf" if low is None else f"{low:g}"
        hi = "inf" if high is None else f"{high:g}"
        rng = ("(" if low_open or low is None else "[") + f"{lo}, {hi}" + (
            ")" if high_open or high is None else "]")
        raise ValueError(f"{name} must be in {rng}, got {v:g}")
    return v


@dataclass(frozen=True)
class Coulomb:
    """Coulomb friction tau = mu p, capped at k (sticking where mu p > k).

    ``rounding`` r > 0 rounds the two kinks as the FE's law does (docs/theory.md 1b):
    max(p, 0) over r k / mu and the cap over r k, (a + sqrt(a^2 + d^2))/2 and
    (a + b - sqrt((a - b)^2 + d^2))/2; 0 (default): the sharp law."""

    mu: float
    rounding: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "mu", check_number("mu", self.mu, low=0.0))
        object.__setattr__(self, "rounding", check_number("rounding", self.rounding, low=0.0))

    def shear(self, p: float, k: float) -> float:
        if self.rounding == 0.0 or self.mu == 0.0:
            return min(self.mu * max(p, 0.0), k)
        d = self.rounding * k
        a = 0.5 * self.mu * (p + math.sqrt(p * p + (d / self.mu) ** 2))
        return 0.5 * (a + k - math.sqrt((a - k) ** 2 + d * d))


@dataclass(frozen=True)
class Tresca:
    """Friction factor law tau = factor k, factor in (0, 1]."""

    factor: float

    def __post_init__(self):
        object.__setattr__(self, "factor",
                           check_number("factor", self.factor, 0.0, 1.0, low_open=True))

    def shear(self, p: float, k: float) -> float:
        return self.factor * k


@dataclass(frozen=True)
class Sticking:
    """Sticking friction tau = k (Tresca factor 1)."""

    def shear(self, p: float, k: float) -> float:
        return k


def constant_flow_stress(sigma: float) -> FlowStress:
    """Rate- and strain-independent flow stress sigma (Pa)."""
    s = check_number("sigma", sigma, low=0.0, low_open=True)
    return lambda strain, strain_rate, temperature: s


# ----------------------------------------------------------------------------- result
@dataclass(frozen=True)
class SlabResult:
    """Slab solution of one pass, per unit width.  Profiles run from exit (phi = 0) to entry."""

    force: float              # N/m, vertical roll separating force
    torque: float             # N m/m, per roll (shear times R)
    power: float              # W/m, both rolls: 2 T U / R
    neutral_angle: float      # rad from the line of centres
    neutral_thickness: float  # m
    forward_slip: float       # (v1 - U) / U
    exit_speed: float         # m/s
    peak_pressure: float      # Pa
    mean_pressure: float      # Pa, force / contact_length
    contact_length: float     # m, projected (R sin alpha; R alpha for small_angle)
    contact_angle: float      # rad
    angle: np.ndarray
    x: np.ndarray             # horizontal distance from the line of centres (towards entry)
    pressure: np.ndarray
    shear: np.ndarray         # magnitude of the interface shear
    thickness: np.ndarray
    strain: np.ndarray
    strain_rate: np.ndarray
    plane_strain_flow_stress: np.ndarray  # 2k (local rate; the two end samples at mean_strain_rate)
    slip_iterations: int
    mean_strain_rate: float   # 1/s, (2/sqrt3) ln(h0/h1) / t_c: the rate of the end 2k


# ----------------------------------------------------------------------------- solver
class _Pass:
    """Geometry, material and the branch ODE for one forward-slip estimate."""

    def __init__(self, R, h0, h1, friction, flow_stress, temperature, entry_strain,
                 yield_offset, small_angle, v1):
        self.R, self.h0, self.h1 = R, h0, h1
        self.friction, self.flow_stress = friction, flow_stress
        self.T, self.e0, self.w, self.small = temperature, entry_strain, yield_offset, small_angle
        self.v1 = v1
        dh = h0 - h1
        self.alpha = a = math.sqrt(dh / R) if small_angle else math.acos(1.0 - dh / (2.0 * R))
        # int_0^L h dx (x = R phi, resp. R sin phi) in closed form; residence time
        # t_c = area / (v1 h1)
        if small_angle:
            area = R * (h1 * a + R * a ** 3 / 3.0)
        else:
            area = R * (h1 * math.sin(a)
                        + 2.0 * R * (math.sin(a) - 0.5 * a - 0.25 * math.sin(2.0 * a)))
        self.mean_rate = 2.0 / SQRT3 * math.log(h0 / h1) * v1 * h1 / area

    def h(self, phi):
        if self.small:
            return self.h1 + self.R * phi * phi
        return self.h1 + 2.0 * self.R * (1.0 - math.cos(phi))

    def sin_cos(self, phi):
        return (phi, 1.0) if self.small else (math.sin(phi), math.cos(phi))

    def two_k(self, strain, rate):
        sf = float(self.flow_stress(strain, rate, self.T))
        if not math.isfinite(sf) or sf < 0.0:
            raise ValueError(f"flow_stress returned {sf!r} at strain {strain:g}, "
                             f"strain rate {rate:g}, temperature {self.T:g}; "
                             "it must be finite and >= 0")
        return 2.0 * sf / SQRT3

    def state(self, phi):
        """(h, strain, local strain rate, 2k at the local rate) at phi."""
        h = self.h(phi)
        strain = self.e0 + 2.0 / SQRT3 * math.log(self.h0 / h)
        dhdx = 2.0 * phi if self.small else 2.0 * math.tan(phi)  # |dh/dx| along the arc
        rate = 2.0 / SQRT3 * (self.v1 * self.h1 / h) * dhdx / h
        return h, strain, rate, self.two_k(strain, rate)

    def end_two_k(self, phi):
        """2k for the yield condition at an end of the arc (phi = 0 or alpha): the end's strain,
        the pass's mean strain rate (see the module docstring)."""
        return self.two_k(self.state(phi)[1], self.mean_rate)

    def local(self, phi, H):
        """Pressure, shear and 2k from the branch state H = q h."""
        h, _, _, two_k = self.state(phi)
        p = H / h + self.w * two_k
        return p, self.friction.shear(p, 0.5 * two_k), two_k

    def rhs(self, s):
        """ODE for y = [q h, vertical force integral, shear integral]."""
        R = self.R

        def f(phi, y):
            p, tau, _ = self.local(phi, y[0])
            sn, cs = self.sin_cos(phi)
            dH = 2.0 * R * (p * sn + s * tau * cs)
            dF = R * p if self.small else R * (p * cs - s * tau * sn)
            return [dH, dF, tau]

        return f


def _solve_once(ps: _Pass, back_tension, front_tension, rtol):
    a = ps.alpha
    scale = ps.state(a)[3] * ps.h0 + abs(back_tension) * ps.h0 + abs(front_tension) * ps.h1 + 1.0
    atol = [rtol * scale, rtol * scale, rtol * scale / ps.R]
    opts = dict(method="DOP853", rtol=rtol, atol=atol, dense_output=True)
    ent = solve_ivp(ps.rhs(-1.0), (a, 0.0), [-back_tension * ps.h0, 0.0, 0.0], **opts)
    ext = solve_ivp(ps.rhs(+1.0), (0.0, a), [-front_tension * ps.h1, 0.0, 0.0], **opts)
    if not (ent.success and ext.success):
        raise RuntimeError(f"slab ODE integration failed: {ent.message} / {ext.message}")
    D = lambda phi: float(ext.sol(phi)[0] - ent.sol(phi)[0])
    grid = np.linspace(0.0, a, 401)
    d = np.array([D(g) for g in grid])
    if d[0] >= 0.0:
        raise NoNeutralPointError(
            "no neutral point: the strip skids (neutral point at or beyond the exit); "
            "friction too low or back tension too high for this pass", "exit")
    if d[-1] <= 0.0:
        raise NoNeutralPointError(
            "no neutral point: the strip is pulled through faster than the rolls "
            "(neutral point at or before the entry); front tension too high", "entry")
    i = int(np.argmax(d > 0.0))  # first crossing from the exit
    phin = brentq(D, grid[i - 1], grid[i], xtol=1e-14 * a, rtol=1e-15)
    force = float(ext.sol(phin)[1] - ent.sol(phin)[1])
    shear_int = float(ent.sol(phin)[2]) * -1.0  # int_{phin}^{alpha} tau dphi (entry zone)
    torque = ps.R ** 2 * (shear_int - float(ext.sol(phin)[2]))
    return ent, ext, phin, force, torque


def solve_pass(roll_radius: float, h0: float, h1: float, roll_speed: float, friction,
               flow_stress: FlowStress, temperature: float, *, entry_strain: float = 0.0,
               back_tension: float = 0.0, front_tension: float = 0.0,
               geometry: str = "arc", yield_offset: float = 1.0, iterate_slip: bool = True,
               n_profile: int = 201, rtol: float = 1e-10) -> SlabResult:
    """Solve the slab equation for one flat pass (see module docstring for the equations).

    roll_radius R, thicknesses h0 > h1 (full), roll_speed U = omega R (m/s), friction one of
    Coulomb / Tresca / Sticking, flow_stress(strain, strain_rate, temperature_K) -> Pa
    (uniaxial), temperature in K (uniform), tensions in Pa (tensile positive).
    Raises ValueError for invalid input, NoNeutralPointError when no steady state exists.
    """
    R, h0, h1 = check_pass(roll_radius, h0, h1)
    U = check_number("roll_speed", roll_speed, low=0.0, low_open=True)
    if not isinstance(friction, (Coulomb, Tresca, Sticking)):
        raise ValueError(f"friction must be Coulomb(mu), Tresca(factor) or Sticking(), "
                         f"got {friction!r}")
    if not callable(flow_stress):
        raise ValueError("flow_stress must be callable (strain, strain_rate, temperature) -> Pa")
    T = check_number("temperature", temperature, low=0.0, low_open=True)
    e0 = check_number("entry_strain", entry_strain, low=0.0)
    sb = check_number("back_tension", back_tension)
    sf = check_number("front_tension", front_tension)
    if geometry not in ("arc", "small_angle"):
        raise ValueError(f"geometry must be 'arc' or 'small_angle', got {geometry!r}")
    w = check_number("yield_offset", yield_offset, 0.0, 1.0, low_open=True)
    n_profile = int(check_number("n_profile", n_profile, low=3))
    small = geometry == "small_angle"

    slip, iterations = 0.0, 0
    for iterations in range(1, 31):
        ps = _Pass(R, h0, h1, friction, flow_stress, T, e0, w, small, U * (1.0 + slip))
        if iterations == 1:  # tension must leave a positive pressure at each end
            for name, value, phi in (("back_tension", sb, ps.alpha), ("front_tension", sf, 0.0)):
                wk = w * ps.end_two_k(phi)
                if value >= wk and value != 0.0:
                    raise ValueError(f"{name} must be < {wk:g} Pa (w 2k at that end, at the "
                                     "mean strain rate: the strip would yield outside the "
                                     f"gap), got {value:g}")
        ent, ext, phin, force, torque = _solve_once(ps, sb, sf, rtol)
        hn = ps.h(phin)
        new_slip = hn / h1 - 1.0 if small else hn * math.cos(phin) / h1 - 1.0
        converged = abs(new_slip - slip) <= 1e-10 * max(1.0, abs(new_slip))
        slip = new_slip
        if converged or not iterate_slip:
            break

    a = ps.alpha
    angle = np.union1d(np.linspace(0.0, a, n_profile), [phin])
    pr, sh, th, st, sr, tk = (np.empty_like(angle) for _ in range(6))
    for j, phi in enumerate(angle):
        H = ext.sol(phi)[0] if phi <= phin else ent.sol(phi)[0]
        p, tau, two_k = ps.local(phi, H)
        h, strain, rate, _ = ps.state(phi)
        if phi == 0.0 or phi == a:  # yield condition at the ends: 2k at the mean rate
            two_k = ps.end_two_k(phi)
            p = H / h + w * two_k
            tau = friction.shear(p, 0.5 * two_k)
        pr[j], sh[j], th[j], st[j], sr[j], tk[j] = p, tau, h, strain, rate, two_k
    x = R * angle if small else R * np.sin(angle)
    length = R * a if small else R * math.sin(a)
    return SlabResult(
        force=force, torque=torque, power=2.0 * torque * U / R, neutral_angle=phin,
        neutral_thickness=hn, forward_slip=slip, exit_speed=U * (1.0 + slip),
        peak_pressure=float(pr.max()), mean_pressure=force / length, contact_length=length,
        contact_angle=a, angle=angle, x=x, pressure=pr, shear=sh, thickness=th, strain=st,
        strain_rate=sr, plane_strain_flow_stress=tk, slip_iterations=iterations,
        mean_strain_rate=ps.mean_rate)
