"""Tests of hotroll.theory.asymmetric: the asymmetric slab reference (note
/work/shared/notes/asymmetric-rolling.md section 1, an [E] derivation by the note's author).

Kinds of check (docs/testing.md): [ref] the existing symmetric slab solver
(hotroll.theory.slab.solve_pass, independent code), the symmetric Tresca neutral point by hand,
the exact scalings of the equations, the mirror; [id] the horizontal balance, an identity of the
slab equations; [self] the closed form against the shooting solver (two solutions of the same
equations: to 1e-8 on parabolic arcs; a measured band on exact arcs); [note] the note's own
tables, "agreement with the note's own computation [E], an independent implementation of the
same equations, not a published source".
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from hotroll.model.friction import CoulombFriction, TrescaFriction, ViscoplasticFriction
from hotroll.theory.asymmetric import (
    NoNeutralPointError,
    Roll,
    draft_split,
    shear_magnitude,
    solve_asymmetric,
    tresca_closed_form,
)
from hotroll.theory.slab import Coulomb, Tresca, constant_flow_stress, solve_pass

K = 100e6                   # Pa, shear flow stress
R = 0.25                    # m, Case R radius
H0, H1 = 0.010, 0.008       # m, Case R pass (note 1.9)
T_HOT = 1273.0              # K, only passed through to solve_pass (constant flow stress)


def tresca(m):
    return TrescaFriction(0.0, factor=m)


def case_r(r, m=0.3, **kw):
    """Case R closed form, roll 1 at r U2 (U2 = 1 m/s)."""
    return tresca_closed_form(h0=H0, h1=H1, k=K, R1=R, R2=R, U1=r, U2=1.0, m1=m, m2=m, **kw)


def shoot_r(r, m=0.3, geometry="arc", **kw):
    return solve_asymmetric(Roll(R, r, tresca(m)), Roll(R, 1.0, tresca(m)), H0, H1, K,
                            geometry=geometry, **kw)


# ----------------------------------------------------------------------------- the note's tables
CASE_R_TABLE = [  # r, F/F0, x_n1/L, x_n2/L, cross shear/L, T1/T0, T2/T0, v_exit/U2 (note 1.9)
    (1.00, 1.0000, -0.334, -0.334, 0.000, 1.000, 1.000, 1.028),
    (1.01, 0.9993, -0.303, -0.364, 0.061, 1.184, 0.815, 1.033),
    (1.02, 0.9973, -0.273, -0.395, 0.122, 1.365, 0.631, 1.039),
    (1.05, 0.9838, -0.185, -0.486, 0.301, 1.893, 0.085, 1.059),
    (1.08, 0.9599, -0.101, -0.575, 0.474, 2.398, -0.453, 1.083),
    (1.10, 0.9388, -0.047, -0.634, 0.587, 2.724, -0.808, 1.101),
    (1.118, 0.9167, 0.0, -0.686, 0.686, 3.005, -1.120, 1.118),
    (1.30, 0.9167, 0.0, -0.686, 0.686, 3.005, -1.120, 1.118),   # ">= r*"
]


def printed(value, digits):
    return round(value, digits) + 0.0   # -0.0 -> 0.0


@pytest.mark.parametrize("row", CASE_R_TABLE)
def test_case_r_table_to_its_printed_digits(row):
    """[note] Agreement with the note's own computation [E] (Case R, 1.9), an independent
    implementation of the same equations, not a published source: every column to the digits
    printed."""
    r, F, x1, x2, cs, T1, T2, v = row
    c0, c = case_r(1.0), case_r(r)
    L = c.contact_length
    assert printed(c.force / c0.force, 4) == F
    assert (printed(c.x_n1 / L, 3), printed(c.x_n2 / L, 3)) == (x1, x2)
    assert printed(c.cross_shear_length / L, 3) == cs
    assert (printed(c.torque1 / c0.torque1, 3), printed(c.torque2 / c0.torque2, 3)) == (T1, T2)
    assert printed(c.exit_speed / 1.0, 3) == v


def test_case_r_header_saturation_and_torque_sign_change():
    """[note] Case R's symmetric figures, r* = 1.118 and T2 = 0 at r = 1.055 (note 1.9, [E])."""
    c = case_r(1.0)
    L = c.contact_length
    assert round(L * 1e3, 2) == 22.36                            # mm
    assert round(L / (0.5 * (H0 + H1)), 2) == 2.48
    assert round(c.force / (2 * K * L), 3) == 1.137
    assert round(c.torque1 / (K * L * R), 4) == 0.0998
    assert round(100 * c.forward_slip1, 2) == 2.78                # %
    assert round(c.x_n1 / L, 3) == -0.334
    assert round(c.r_star, 3) == 1.118
    assert not c.saturated and not case_r(1.117).saturated and case_r(1.119).saturated
    assert round(brentq(lambda r: case_r(r).torque2, 1.0, 1.1, xtol=1e-10), 3) == 1.055


def test_case_r_variant_c_on_exact_arcs():
    """[note] Variant C (1.10: the thickness-averaged shear in the yield condition), exact arcs:
    F/F0 = 0.9938, 0.9750, 0.9211, 0.8949 (F0 Variant C's own r = 1), r* = 1.119, T2 = 0 at
    r = 1.053 (note 1.9, [E]); its neutral points within 0.007 L of the closed form's table."""
    f = lambda r: shoot_r(r, yield_condition="shear_averaged")
    f0 = f(1.0)
    L = f0.contact_length
    ratios = [round(f(r).force / f0.force, 4) for r in (1.02, 1.05, 1.10, 1.30)]
    assert ratios == [0.9938, 0.9750, 0.9211, 0.8949]
    assert round(brentq(lambda r: f(r).x_n1 + 1e-9 * L, 1.0, 1.3, xtol=1e-8), 3) == 1.119
    assert round(brentq(lambda r: f(r).torque2, 1.0, 1.1, xtol=1e-8), 3) == 1.053
    for r in (1.02, 1.05, 1.10):
        v, c = f(r), case_r(r)
        assert abs(v.x_n1 - c.x_n1) < 0.007 * L and abs(v.x_n2 - c.x_n2) < 0.007 * L
    # the shear lowers the yield stress: Variant C's symmetric force is below the homogeneous one
    assert f0.force < shoot_r(1.0).force


def test_case_a_and_case_c_on_exact_arcs():
    """[note] Cases A (Tresca 0.8) and C (Coulomb 0.1, R 100 mm, 2 -> 1.6 mm), note 1.9 [E]:
    the printed figures are those of the exact-arc shooting solution (the small-angle closed form
    gives Case A's F/F0 0.979, 0.918, 0.826 and r* 1.193 instead)."""
    fa = lambda r: shoot_r(r, m=0.8)
    a0 = fa(1.0)
    L = a0.contact_length
    assert (round(a0.force / (2 * K * L), 3), round(100 * a0.forward_slip1, 1),
            round(a0.x_n1 / L, 3)) == (1.466, 4.3, -0.420)
    assert [round(fa(r).force / a0.force, 3) for r in (1.02, 1.05, 1.10, 1.15, 1.30)] == [
        0.996, 0.978, 0.916, 0.820, 0.726]
    sat = fa(1.3)
    assert (round(sat.x_n2 / L, 3), round(sat.torque1 / a0.torque1, 2),
            round(sat.torque2 / a0.torque2, 2)) == (-0.878, 6.19, -4.68)
    assert round(brentq(lambda r: fa(r).x_n1 + 1e-9 * L, 1.0, 1.3, xtol=1e-8), 3) == 1.189
    assert round(brentq(lambda r: fa(r).torque2, 1.0, 1.1, xtol=1e-8), 3) == 1.032

    law = CoulombFriction(0.0, mu=0.1, rounding=0.0)
    fc = lambda r: solve_asymmetric(Roll(0.1, r, law), Roll(0.1, 1.0, law), 0.002, 0.0016, K)
    c0 = fc(1.0)
    L = c0.contact_length
    assert (round(c0.force / (2 * K * L), 3), round(100 * c0.forward_slip1, 1),
            round(c0.x_n1 / L, 3)) == (1.142, 2.9, -0.340)
    assert [round(fc(r).force / c0.force, 3) for r in (1.02, 1.05, 1.08, 1.3)] == [
        0.997, 0.981, 0.955, 0.912]
    assert round(brentq(lambda r: fc(r).x_n1 + 1e-9 * L, 1.0, 1.3, xtol=1e-8), 3) == 1.116
    assert round(brentq(lambda r: fc(r).torque2, 1.0, 1.1, xtol=1e-8), 3) == 1.049


def test_friction_and_radius_asymmetry_and_viscoplastic_figures():
    """[note] Note 1.9 [E]: Tresca 0.4/0.2 at equal speeds; R 275/225 mm at equal surface
    speeds and at equal angular speed (T0 the symmetric R_e = 247.5 mm pass); the viscoplastic
    tau = 0.8 k |D_i / U_i|^0.1 on Case A's geometry (exact arcs; U_i each roll's own speed,
    i.e. a_f K = 0.8 k U_i^-0.1, the reading that reproduces the note's figures)."""
    f = tresca_closed_form(h0=H0, h1=H1, k=K, R1=R, R2=R, U1=1, U2=1, m1=0.4, m2=0.2)
    assert f.force == pytest.approx(case_r(1.0).force, rel=1e-12)
    assert round(f.torque1 / (f.torque1 + f.torque2), 3) == 0.667 and f.cross_shear_length == 0
    ce = tresca_closed_form(h0=H0, h1=H1, k=K, R1=0.2475, R2=0.2475, U1=1, U2=1, m1=0.3, m2=0.3)
    d = tresca_closed_form(h0=H0, h1=H1, k=K, R1=0.275, R2=0.225, U1=1, U2=1, m1=0.3, m2=0.3)
    assert d.effective_radius == pytest.approx(0.2475, rel=1e-15)
    assert round(d.torque1 / (d.torque1 + d.torque2), 3) == 0.550
    w = 4.0  # rad/s, both rolls
    e = tresca_closed_form(h0=H0, h1=H1, k=K, R1=0.275, R2=0.225, U1=w * 0.275, U2=w * 0.225,
                           m1=0.3, m2=0.3)
    assert e.saturated and 0.275 / 0.225 > e.r_star
    assert (round(e.force / ce.force, 3), round(e.torque1 / ce.torque1, 2),
            round(e.torque2 / ce.torque1, 2)) == (0.917, 3.33, -1.01)

    def vp(r):
        rolls = [Roll(R, U, ViscoplasticFriction(0.0, K=K, m=0.1), a_f=0.8 * U ** -0.1)
                 for U in (r, 1.0)]
        return solve_asymmetric(*rolls, H0, H1, K)

    v0 = vp(1.0)
    assert [round(vp(r).force / v0.force, 3) for r in (1.1, 1.2, 1.3, 1.5)] == [
        0.930, 0.813, 0.796, 0.781]


# ----------------------------------------------------------------------------- closed form vs shooting
PARABOLIC_CASES = [  # (R1, R2, U1, U2, m1, m2, t_b / 2k, t_f / 2k)
    (0.25, 0.25, 1.05, 1.0, 0.3, 0.3, 0.0, 0.0),
    (0.25, 0.25, 1.3, 1.0, 0.3, 0.3, 0.0, 0.0),          # saturated
    (0.30, 0.20, 1.0, 1.12, 0.5, 0.25, 0.10, 0.05),      # roll 2 faster, tensions
    (0.25, 0.40, 2.0, 1.9, 0.8, 0.6, 0.0, 0.15),
]


@pytest.mark.parametrize("case", PARABOLIC_CASES)
def test_closed_form_equals_shooting_on_parabolic_arcs(case):
    """[self] The closed form (star) and the shooting solver (numerical ODE, neutral points from
    the kinematic condition, Brent on q) solve the same equations: with parabolic arcs they agree
    to 1e-8 (measured 1e-10 ... 2e-11; the ODE's rtol is 1e-10)."""
    R1, R2, U1, U2, m1, m2, b, f = case
    c = tresca_closed_form(h0=H0, h1=H1, k=K, R1=R1, R2=R2, U1=U1, U2=U2, m1=m1, m2=m2,
                           back_tension=2 * K * b, front_tension=2 * K * f)
    s = solve_asymmetric(Roll(R1, U1, tresca(m1)), Roll(R2, U2, tresca(m2)), H0, H1, K,
                         back_tension=2 * K * b, front_tension=2 * K * f, geometry="parabolic")
    L, T_scale = c.contact_length, K * c.contact_length * max(R1, R2)
    assert s.contact_length == pytest.approx(L, rel=1e-14)
    assert s.force == pytest.approx(c.force, rel=1e-8)
    assert abs(s.x_n1 - c.x_n1) < 1e-8 * L and abs(s.x_n2 - c.x_n2) < 1e-8 * L
    assert abs(s.torque1 - c.torque1) < 1e-8 * T_scale
    assert abs(s.torque2 - c.torque2) < 1e-8 * T_scale
    assert s.exit_speed == pytest.approx(c.exit_speed, rel=1e-9)
    assert s.forward_slip1 == pytest.approx(c.forward_slip1, abs=1e-9)
    assert s.saturated == c.saturated
    assert np.interp(c.x, s.x, s.pressure) == pytest.approx(c.pressure, rel=1e-4)  # profiles


def test_closed_form_against_shooting_on_exact_arcs_band():
    """[self] Exact arcs versus the small-angle closed form, Case R over r = 1 ... 1.25.
    Measured (commit time): |dF|/F <= 4.4e-3, |d(F/F0)| <= 2.9e-3, |dx_n| <= 0.0060 L,
    |d(T/T0)| <= 0.033, |dv1|/v1 <= 2.1e-3, all largest at r = 1.115, between the two
    saturation ratios (arcs 1.1155, closed form 1.1178).  The note says 0.3 % in force (true of
    F/F0; the force itself differs by up to 0.44 %) and 0.006 L (true).  The bands: 1.3 x the
    measured.  Their size is the small-angle error, O(alpha^2) with alpha = L/R = 0.089
    (alpha^2 = 0.008), amplified near r* where x_n1 reaches the exit at slightly different r;
    the lower bounds prove that the arcs are not parabolas."""
    c0, s0 = case_r(1.0), shoot_r(1.0)
    L, T0 = c0.contact_length, c0.torque1
    rows = []
    for r in np.linspace(1.0, 1.25, 26).tolist() + [1.115, 1.117]:
        c, s = case_r(r), shoot_r(r)
        rows.append([abs(s.force / c.force - 1), abs(s.force / s0.force - c.force / c0.force),
                     max(abs(s.x_n1 - c.x_n1), abs(s.x_n2 - c.x_n2)) / L,
                     max(abs(s.torque1 / s0.torque1 - c.torque1 / T0),
                         abs(s.torque2 / s0.torque2 - c.torque2 / T0)),
                     abs(s.exit_speed / c.exit_speed - 1)])
    worst = np.max(rows, axis=0)
    assert worst[0] < 5.7e-3 and worst[1] < 3.8e-3 and worst[2] < 0.0078
    assert worst[3] < 0.043 and worst[4] < 2.7e-3
    assert worst[0] > 1e-3 and worst[2] > 1e-3      # arcs, not parabolas


# ----------------------------------------------------------------------------- symmetric limit
def G_by_hand(x, Re, h1):
    return math.sqrt(Re / h1) * math.atan(x / math.sqrt(Re * h1))


@pytest.mark.parametrize("m,tb,tf", [(0.3, 0.0, 0.0), (0.8, 0.0, 0.0), (0.5, 0.1, 0.05)])
def test_symmetric_limit_is_the_usual_tresca_neutral_point(m, tb, tf):
    """[ref] r = 1, equal rolls: G(x_n) = G(-L)/2 + ln(h0/h1)/(2m) (+ (t_b - t_f)/(4 m k) with
    tensions), G = int_0^x dx/h written here; both rolls' neutral points there, no cross shear,
    T = R m k (L + 2 x_n)."""
    c = tresca_closed_form(h0=H0, h1=H1, k=K, R1=R, R2=R, U1=3.0, U2=3.0, m1=m, m2=m,
                           back_tension=2 * K * tb, front_tension=2 * K * tf)
    L = math.sqrt(R * (H0 - H1))
    expected = (0.5 * G_by_hand(-L, R, H1) + math.log(H0 / H1) / (2 * m)
                + (2 * K * tb - 2 * K * tf) / (4 * m * K))
    assert G_by_hand(c.x_n1, R, H1) == pytest.approx(expected, rel=1e-12)
    assert c.x_n2 == c.x_n1 and c.cross_shear_length == 0 and not c.saturated
    assert c.torque1 == pytest.approx(R * m * K * (L + 2 * c.x_n1), rel=1e-12)


SYMMETRIC_LAWS = [  # slab.py's law, the project's law, geometry
    (Tresca(0.3), tresca(0.3), "small_angle"),
    (Tresca(0.3), tresca(0.3), "arc"),
    (Coulomb(0.12), CoulombFriction(0.0, mu=0.12, rounding=0.0), "arc"),
    (Coulomb(0.6), CoulombFriction(0.0, mu=0.6, rounding=0.0), "arc"),       # capped at k
    (Coulomb(0.12, rounding=0.01), CoulombFriction(0.0, mu=0.12, rounding=0.01), "arc"),
]


@pytest.mark.parametrize("old,new,geometry", SYMMETRIC_LAWS)
@pytest.mark.parametrize("tb,tf", [(0.0, 0.0), (0.1, 0.05)])
def test_symmetric_limit_equals_the_existing_slab_solver(old, new, geometry, tb, tf):
    """[ref] Equal rolls: the existing symmetric slab solver (theory/slab.py: Orowan's angular
    form, branch crossing, independent code) gives the same force (roll 1's, with the shear's
    vertical projection on arcs), torque per roll, neutral point and forward slip, to 1e-8
    (measured <= 1.3e-9)."""
    U = 2.0
    ref = solve_pass(R, H0, H1, U, old, constant_flow_stress(K * math.sqrt(3)), T_HOT,
                     geometry=geometry, back_tension=2 * K * tb, front_tension=2 * K * tf)
    s = solve_asymmetric(Roll(R, U, new), Roll(R, U, new), H0, H1, K,
                         geometry="parabolic" if geometry == "small_angle" else "arc",
                         back_tension=2 * K * tb, front_tension=2 * K * tf)
    phin = ref.neutral_angle
    xn = -R * phin if geometry == "small_angle" else -R * math.sin(phin)
    assert (s.force if geometry == "small_angle" else s.force1) == pytest.approx(ref.force, rel=1e-8)
    assert s.torque1 == pytest.approx(ref.torque, rel=1e-8)
    assert s.torque2 == pytest.approx(ref.torque, rel=1e-8)
    assert abs(s.x_n1 - xn) < 1e-8 * s.contact_length and s.x_n2 == s.x_n1
    assert s.forward_slip1 == pytest.approx(ref.forward_slip, abs=1e-9)
    assert s.contact_length == pytest.approx(ref.contact_length, rel=1e-12)


# ----------------------------------------------------------------------------- consequences of (star)
@pytest.mark.parametrize("R1,R2", [(0.25, 0.25), (0.30, 0.20)])
def test_equal_speeds_unequal_friction(R1, R2):
    """[ref] (star) with U1 = U2: x_n1 = x_n2, T1/T2 = R1 m1/(R2 m2), F a function of m1 + m2
    only (note 1.8).  The shooting solver on parabolic arcs agrees (independent of (star))."""
    f = lambda m1, m2: tresca_closed_form(h0=H0, h1=H1, k=K, R1=R1, R2=R2, U1=1.5, U2=1.5,
                                          m1=m1, m2=m2)
    a, b, c = f(0.4, 0.2), f(0.3, 0.3), f(0.55, 0.05)
    assert a.x_n1 == a.x_n2 and a.cross_shear_length == 0.0
    assert a.torque1 / a.torque2 == pytest.approx(R1 * 0.4 / (R2 * 0.2), rel=1e-12)
    assert a.force == pytest.approx(b.force, rel=1e-12) and c.force == pytest.approx(b.force, rel=1e-12)
    s = solve_asymmetric(Roll(R1, 1.5, tresca(0.4)), Roll(R2, 1.5, tresca(0.2)), H0, H1, K,
                         geometry="parabolic")
    assert s.force == pytest.approx(b.force, rel=1e-8)
    assert s.torque1 / s.torque2 == pytest.approx(R1 * 0.4 / (R2 * 0.2), rel=1e-8)


def test_equal_surface_speeds_unequal_radii():
    """[ref] (star) with U1 = U2, R1 != R2: F is the symmetric pass's of radius
    R_e = 2 R1 R2/(R1 + R2), T1/T2 = R1/R2 (note 1.8).  On exact arcs only the cos phi_i
    difference makes a cross-shear zone: measured 0.0011 L (note: 0.0015 L; by hand,
    d(cos phi) / d ln(u) at x = -0.33 L gives 0.0012 L)."""
    R1, R2 = 0.275, 0.225
    Re = 2 * R1 * R2 / (R1 + R2)
    d = tresca_closed_form(h0=H0, h1=H1, k=K, R1=R1, R2=R2, U1=1, U2=1, m1=0.3, m2=0.3)
    e = tresca_closed_form(h0=H0, h1=H1, k=K, R1=Re, R2=Re, U1=1, U2=1, m1=0.3, m2=0.3)
    assert d.force == pytest.approx(e.force, rel=1e-12)
    assert d.torque1 / d.torque2 == pytest.approx(R1 / R2, rel=1e-12)
    s = solve_asymmetric(Roll(R1, 1.0, tresca(0.3)), Roll(R2, 1.0, tresca(0.3)), H0, H1, K)
    assert 0.0008 < s.cross_shear_length / s.contact_length < 0.0015
    assert s.x_n1 > s.x_n2            # the larger roll's neutral point downstream


def test_above_r_star_nothing_depends_on_r():
    """[ref] Saturation (note 1.8): above r* the fast roll drags everywhere, so force, torques,
    the slow roll's neutral point and the exit speed are those at r*: the closed form to 1e-12,
    the shooting solver on exact arcs to 1e-9 (it never sees U1 once zone III is gone).  Below
    r* the force still falls.  The viscoplastic law has no plateau (note 0: a slow decline)."""
    c = case_r(1.0)
    rs = c.r_star
    sat = [case_r(r) for r in (rs * 1.0001, 1.2, 1.5, 3.0)]
    for s in sat:
        assert s.saturated and s.x_n1 == 0.0
        for name in ("force", "torque1", "torque2", "x_n2", "exit_speed"):
            assert getattr(s, name) == pytest.approx(getattr(sat[0], name), rel=1e-12)
    assert case_r(rs * 0.999).force > sat[0].force * (1 + 1e-5)
    assert sat[0].exit_speed == pytest.approx(rs * 1.0, rel=1e-9)   # v1 = r* U2 (note 1.8)
    a, b = shoot_r(1.2), shoot_r(1.6)
    assert a.saturated and b.saturated
    for name in ("force", "torque1", "torque2", "x_n2", "exit_speed", "force1", "force2"):
        assert getattr(b, name) == pytest.approx(getattr(a, name), rel=1e-9)
    law = ViscoplasticFriction(0.0, K=K, m=0.1)
    vp = lambda r: solve_asymmetric(Roll(R, r, law, a_f=0.8 * r ** -0.1),
                                    Roll(R, 1.0, law, a_f=0.8), H0, H1, K, geometry="parabolic")
    assert vp(1.5).force < vp(1.3).force * (1 - 1e-3)


@pytest.mark.parametrize("solver", ["closed", "arc", "coulomb", "viscoplastic"])
def test_horizontal_balance(solver):
    """[id] Identity of the slab equations (note 1.6): int (tau1 + tau2) dx =
    int p |h'| dx + t_b h0 - t_f h1 (the closed form: shear from the neutral points, pressure
    from its integrated p; the shooting solver: separate ODE components), with tensions."""
    tb, tf = 0.12 * 2 * K, 0.04 * 2 * K
    if solver == "closed":
        s = tresca_closed_form(h0=H0, h1=H1, k=K, R1=0.3, R2=0.22, U1=1.04, U2=1.0, m1=0.4,
                               m2=0.3, back_tension=tb, front_tension=tf)
    else:
        laws = {"arc": (tresca(0.4), tresca(0.3), None),
                "coulomb": (CoulombFriction(0.0, mu=0.2, rounding=0.0),
                            CoulombFriction(0.0, mu=0.5, rounding=0.0), None),
                "viscoplastic": (ViscoplasticFriction(0.0, K=K, m=0.1),) * 2 + (0.8,)}[solver]
        s = solve_asymmetric(Roll(0.3, 1.04, laws[0], laws[2]), Roll(0.22, 1.0, laws[1], laws[2]),
                             H0, H1, K, back_tension=tb, front_tension=tf)
    lhs = s.shear_force1 + s.shear_force2
    assert lhs == pytest.approx(s.pressure_force_x + tb * H0 - tf * H1, rel=1e-8)
    # and the profile integrates to the force (trapezoid on the written profile)
    assert np.trapezoid(s.pressure, s.x) == pytest.approx(s.force, rel=2e-4)


# ----------------------------------------------------------------------------- scalings, mirror
def test_k_scaling():
    """[ref] The equations are homogeneous in stress: k, tensions (and a viscoplastic K) x 7.3
    scale force and torques by 7.3 and leave neutral points, speeds and slips unchanged."""
    lam = 7.3
    c1 = tresca_closed_form(h0=H0, h1=H1, k=K, R1=0.3, R2=0.2, U1=1.06, U2=1, m1=0.4, m2=0.3,
                            back_tension=0.1 * K)
    c2 = tresca_closed_form(h0=H0, h1=H1, k=lam * K, R1=0.3, R2=0.2, U1=1.06, U2=1, m1=0.4,
                            m2=0.3, back_tension=0.1 * K * lam)
    law = lambda kk: CoulombFriction(0.0, mu=0.25, rounding=0.0)
    s1 = solve_asymmetric(Roll(0.3, 1.06, law(K)), Roll(0.2, 1.0, tresca(0.3)), H0, H1, K,
                          front_tension=0.1 * K)
    s2 = solve_asymmetric(Roll(0.3, 1.06, law(lam * K)), Roll(0.2, 1.0, tresca(0.3)), H0, H1,
                          lam * K, front_tension=0.1 * K * lam)
    v = lambda kk: ViscoplasticFriction(0.0, K=kk, m=0.15)
    v1 = solve_asymmetric(Roll(0.3, 1.06, v(K), 0.7), Roll(0.2, 1.0, v(K), 0.7), H0, H1, K)
    v2 = solve_asymmetric(Roll(0.3, 1.06, v(lam * K), 0.7), Roll(0.2, 1.0, v(lam * K), 0.7),
                          H0, H1, lam * K)
    for a, b in ((c1, c2), (s1, s2), (v1, v2)):
        for name in ("force", "torque1", "torque2"):
            assert getattr(b, name) == pytest.approx(lam * getattr(a, name), rel=1e-8)
        for name in ("x_n1", "x_n2", "exit_speed"):
            assert getattr(b, name) == pytest.approx(getattr(a, name), rel=1e-8, abs=1e-12)


def test_speed_scaling():
    """[ref] Rate-independent friction: both speeds x 40 change only the speeds (exit speed,
    flux x 40; slips, neutral points, force, torques the same).  Viscoplastic: the same with
    a_f x 40^-m, since tau = a_f K |D|^m."""
    lam = 40.0
    c1 = tresca_closed_form(h0=H0, h1=H1, k=K, R1=0.3, R2=0.2, U1=1.06, U2=1, m1=0.4, m2=0.3)
    c2 = tresca_closed_form(h0=H0, h1=H1, k=K, R1=0.3, R2=0.2, U1=1.06 * lam, U2=lam, m1=0.4,
                            m2=0.3)
    law = CoulombFriction(0.0, mu=0.25, rounding=0.0)
    s1 = solve_asymmetric(Roll(0.3, 1.06, law), Roll(0.2, 1.0, tresca(0.3)), H0, H1, K)
    s2 = solve_asymmetric(Roll(0.3, 1.06 * lam, law), Roll(0.2, lam, tresca(0.3)), H0, H1, K)
    v = ViscoplasticFriction(0.0, K=K, m=0.15)
    v1 = solve_asymmetric(Roll(0.3, 1.06, v, 0.7), Roll(0.2, 1.0, v, 0.9), H0, H1, K)
    v2 = solve_asymmetric(Roll(0.3, 1.06 * lam, v, 0.7 * lam ** -0.15),
                          Roll(0.2, lam, v, 0.9 * lam ** -0.15), H0, H1, K)
    for a, b in ((c1, c2), (s1, s2), (v1, v2)):
        for name in ("force", "torque1", "torque2", "x_n1", "x_n2", "forward_slip1"):
            assert getattr(b, name) == pytest.approx(getattr(a, name), rel=1e-8, abs=1e-12)
        assert b.exit_speed == pytest.approx(lam * a.exit_speed, rel=1e-9)
        assert b.flux == pytest.approx(lam * a.flux, rel=1e-9)


@pytest.mark.parametrize("solver", ["closed", "arc"])
def test_mirror_swaps_the_rolls(solver):
    """[ref] Swapping all upper and lower data (radius, speed, friction) swaps the torques,
    neutral points and slips and keeps the force (note 6.2, check 1's mirror)."""
    if solver == "closed":
        run = lambda a, b: tresca_closed_form(h0=H0, h1=H1, k=K, R1=a[0], R2=b[0], U1=a[1],
                                              U2=b[1], m1=a[2], m2=b[2], back_tension=0.05 * K)
        up, low = (0.3, 1.07, 0.45), (0.2, 1.0, 0.3)
    else:
        run = lambda a, b: solve_asymmetric(Roll(a[0], a[1], a[2]), Roll(b[0], b[1], b[2]), H0,
                                            H1, K, back_tension=0.05 * K)
        up = (0.3, 1.07, CoulombFriction(0.0, mu=0.3, rounding=0.0))
        low = (0.2, 1.0, tresca(0.3))
    a, b = run(up, low), run(low, up)
    assert b.force == pytest.approx(a.force, rel=1e-9)
    assert (b.torque1, b.torque2) == pytest.approx((a.torque2, a.torque1), rel=1e-9)
    assert (b.x_n1, b.x_n2) == pytest.approx((a.x_n2, a.x_n1), rel=1e-9)
    assert (b.forward_slip1, b.forward_slip2) == pytest.approx((a.forward_slip2, a.forward_slip1),
                                                               rel=1e-8)
    assert a.torque1 != pytest.approx(a.torque2, rel=1e-2)   # the case is asymmetric


def test_draft_split():
    """[ref] Note 1.1: parabolic dh1 = dh R2/(R1 + R2), the smaller roll the larger draft; on
    arcs dh_i = R_i - sqrt(R_i^2 - L^2) (Pythagoras, by hand) with dh1 + dh2 = dh."""
    R1, R2, dh = 0.3, 0.2, H0 - H1
    p1, p2 = draft_split(R1, R2, H0, H1, geometry="parabolic")
    assert (p1, p2) == pytest.approx((dh * R2 / (R1 + R2), dh * R1 / (R1 + R2)), rel=1e-12)
    a1, a2 = draft_split(R1, R2, H0, H1)
    assert a1 + a2 == pytest.approx(dh, rel=1e-12) and a2 > a1
    L = solve_asymmetric(Roll(R1, 1.0, tresca(0.3)), Roll(R2, 1.0, tresca(0.3)), H0, H1,
                         K).contact_length
    assert (a1, a2) == pytest.approx((R1 - math.sqrt(R1 ** 2 - L ** 2),
                                      R2 - math.sqrt(R2 ** 2 - L ** 2)), rel=1e-9)
    assert a1 == pytest.approx(p1, rel=0.01)     # arcs = parabolas to O(alpha^2)


# ----------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("kw,match", [
    (dict(U1=0.0), r"U1 must be in \(0"),
    (dict(U2=-1.0), r"U2 must be in \(0"),
    (dict(R1=0.001), r"R1 must be > the draft"),
    (dict(R2=0.002), r"R2 must be > the draft"),
    (dict(m1=1.2), r"m1 must be in \(0, 1\]"),
    (dict(m2=0.0), r"m2 must be in \(0, 1\]"),
    (dict(h1=0.012), r"h1 must be in \(0, h0\)"),
    (dict(k=-1.0), r"k must be in \(0"),
    (dict(front_tension=3 * K), r"front_tension must be in"),
])
def test_closed_form_refuses_bad_input_naming_it(kw, match):
    args = dict(h0=H0, h1=H1, k=K, R1=R, R2=R, U1=1.0, U2=1.0, m1=0.3, m2=0.3) | kw
    with pytest.raises(ValueError, match=match):
        tresca_closed_form(**args)


@pytest.mark.parametrize("upper,kw,match", [
    (Roll(R, 0.0, tresca(0.3)), {}, r"U1 must be in \(0"),
    (Roll(0.001, 1.0, tresca(0.3)), {}, r"R1 must be > the draft"),
    (Roll(R, 1.0, tresca(1.5)), {}, r"upper.friction.factor must be in \(0, 1\]"),
    (Roll(R, 1.0, CoulombFriction(0.0, mu=-0.1)), {}, r"upper.friction.mu must be in \(0, 2\]"),
    (Roll(R, 1.0, ViscoplasticFriction(0.0, K=K, m=0.1)), {}, r"upper.a_f must be given"),
    (Roll(R, 1.0, ViscoplasticFriction(0.0, K=K, m=0.1), a_f=-1), {}, r"upper.a_f must be in"),
    (Roll(R, 1.0, CoulombFriction(0.0, mu=0.3)), dict(yield_condition="shear_averaged"),
     r"upper.friction: yield_condition 'shear_averaged'"),
    (Roll(R, 1.0, tresca(0.3)), dict(geometry="circle"), r"geometry must be 'arc' or 'parabolic'"),
    (Roll(R, 1.0, tresca(0.3)), dict(yield_condition="vm"), r"yield_condition must be"),
    ("roll", {}, r"upper must be a Roll"),
])
def test_shooting_refuses_bad_input_naming_it(upper, kw, match):
    with pytest.raises(ValueError, match=match):
        solve_asymmetric(upper, Roll(R, 1.0, tresca(0.3)), H0, H1, K, **kw)


def test_no_steady_state_is_said():
    """Too little friction for the bite (Tresca 0.05, Coulomb 0.02 on Case R: the friction hill
    cannot draw the strip) and too much front tension: NoNeutralPointError with where."""
    with pytest.raises(NoNeutralPointError) as e:
        case_r(1.0, m=0.05)
    assert e.value.where == "exit"
    law = CoulombFriction(0.0, mu=0.02, rounding=0.0)
    with pytest.raises(NoNeutralPointError) as e:
        solve_asymmetric(Roll(R, 1.1, law), Roll(R, 1.0, law), H0, H1, K)
    assert e.value.where == "exit"
    with pytest.raises(NoNeutralPointError) as e:
        shoot_r(1.0, front_tension=1.9 * K, back_tension=-3 * K)
    assert e.value.where == "entry"


def test_no_steady_state_says_why():
    """The closed form's refusal says what happens (the strip skids), not only where."""
    with pytest.raises(NoNeutralPointError, match=r"^no steady state: the strip skids"):
        case_r(1.0, m=0.05)


def test_a_rate_independent_law_with_v_reg_is_regularised_as_the_fe():
    """Tresca m = 0.5 with v_reg = 0.01 m/s at a slip of 0.03 m/s: |tau| = m k |v|/sqrt(v^2 +
    v_reg^2) = 0.5 k 0.03/sqrt(0.001) (the FE's secant form), not m k."""
    tau = shear_magnitude(Roll(R, 1.0, TrescaFriction(0.01, factor=0.5)), 0.03, 2 * K, K)
    assert tau == pytest.approx(0.5 * K * 0.03 / math.sqrt(0.001), rel=1e-14)


@pytest.mark.parametrize("solver", [case_r, shoot_r])
def test_n_profile_two_samples_each_zone_at_its_ends(solver):
    """n_profile = 2: every zone between entry, the two neutral points and the exit is
    sampled at its two ends only; the closed form's ends are the entry's 2k - t_b and the
    exit's 2k - t_f."""
    tb, tf = 0.1 * K, 0.2 * K
    r = solver(1.05, back_tension=tb, front_tension=tf, n_profile=2)
    ends = np.array([r.x[0], r.x_n1, r.x_n2, 0.0])
    assert all(np.min(np.abs(ends - x)) <= 1e-12 * r.contact_length for x in r.x)
    assert len(r.x) % 2 == 0 and r.x[-1] == 0.0
    if solver is case_r:
        assert r.x[0] == -r.contact_length and len(r.x) == 6
        assert r.pressure[0] == pytest.approx(2 * K - tb, rel=1e-14)
        assert r.pressure[-1] == pytest.approx(2 * K - tf, rel=1e-9)
