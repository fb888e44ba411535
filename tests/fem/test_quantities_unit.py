"""Fast unit tests (no FE solve) of the pure formulas behind the reported figures.

Every expected number is derived by hand from the formula the function's docstring (or the
report equation it cites) states; the comment next to each assertion says how. The numbers are
chosen so that a planted bug (a constant off by 10 %, a flipped sign, < for <=, a clipping side
dropped, a function returning [] or its input) changes at least one of them:
- ``model/friction_estimate.py``: (3.15) for a_f, its clipping and its error branches;
- ``model/friction.py``: the three friction laws' coefficient, shear and dissipation;
- ``fem/quantities.py``: exit-pressure correction, contact loss, neutral point, smoothing;
- ``results/engineering.py``: display units and whole-width totals;
- ``algorithms``: the continuation path, default strip lengths, the steady-state test's scales
  (and ``workflows/runner.py``'s contact tolerance and default end time).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from hotroll.fem.quantities import (
    contact_loss,
    exit_corrected,
    neutral_index,
    neutral_point,
    smoothed,
)
from hotroll.model.friction import (
    CoulombFriction,
    FrictionLaw,
    TrescaFriction,
    ViscoplasticFriction,
    smooth_minimum,
    smooth_positive_part,
)
from hotroll.model.friction_estimate import estimate_a_f, lambda_factor
from hotroll.results.engineering import display, width_totals
from hotroll.results.units import UNITS


# =============================================================================================
# 1. a_f from the stability bound (3.15)
#    a_f = C5/h * V / ((|lam|^(p-1) - |lam|^p) * L * U^p),  p = m + 1,  C5 = 2^p
# =============================================================================================
def test_lambda_factor_by_hand():
    # p = 2: lam - lam^2 = 0.5 - 0.25
    assert lambda_factor(0.5, 2.0) == pytest.approx(0.25, rel=1e-15)
    # |lam| is taken: same for -0.5
    assert lambda_factor(-0.5, 2.0) == pytest.approx(0.25, rel=1e-15)
    # p = 1.2: 0.25^0.2 - 0.25^1.2 = 0.25^0.2 * (1 - 0.25) = 0.7578582832552 * 0.75
    assert lambda_factor(0.25, 1.2) == pytest.approx(0.5683937124413993, rel=1e-13)
    # p = 1 (m = 0): lam^0 - lam = 1 - 0.3
    assert lambda_factor(0.3, 1.0) == pytest.approx(0.7, rel=1e-15)


def test_estimate_a_f_by_hand():
    # m = 1 -> p = 2, C5 = 4; lam = 0.25: lam - lam^2 = 0.1875;
    # denominator 0.1875 * L=1.5 * U^2=4 = 1.125; a_f = 4/0.5 * 3/1.125 = 8 * 8/3 = 64/3
    assert estimate_a_f(3.0, 0.5, 0.25, 1.5, 2.0, 1.0) == pytest.approx(64.0 / 3.0, rel=1e-14)
    # lam enters as |lam|: -0.25 gives the same 64/3
    assert estimate_a_f(3.0, 0.5, -0.25, 1.5, 2.0, 1.0) == pytest.approx(64.0 / 3.0, rel=1e-14)
    # m = 0 -> p = 1, C5 = 2; lam = 0.6: 1 - 0.6 = 0.4; denominator 0.4 * 0.5 * 4 = 0.8;
    # a_f = 2/0.2 * 1/0.8 = 12.5
    assert estimate_a_f(1.0, 0.2, 0.6, 0.5, 4.0, 0.0) == pytest.approx(12.5, rel=1e-14)
    # m = 0.2 -> p = 1.2, C5 = 2^1.2 = 2.2973967099940700; lam = 0.5:
    # 0.5^0.2 - 0.5^1.2 = 0.5^1.2, so the denominator 0.5^1.2 * 0.3 * 2^1.2 = 0.3;
    # a_f = 2^1.2 / 0.1 * 2 / 0.3 = 153.15978066627133
    a_f = estimate_a_f(2.0, 0.1, 0.5, 0.3, 2.0, 0.2)
    assert a_f == pytest.approx(153.15978066627133, rel=1e-13)
    assert isinstance(a_f, float)


def test_estimate_a_f_clips_lambda_on_both_sides():
    # lam_min = 0.1, m = 1 (p = 2, C5 = 4), V = 0.9, h = L = U = 1: a_f = 4 * 0.9 / (lam - lam^2)
    kw = dict(lam_min=0.1)
    # below lam_min: lam -> 0.1, 0.1 - 0.01 = 0.09, a_f = 3.6/0.09 = 40
    # (unclipped lam = 0.05 would give 3.6/0.0475 = 75.79, lam = 0 a division by zero)
    assert estimate_a_f(0.9, 1.0, 0.05, 1.0, 1.0, 1.0, **kw) == pytest.approx(40.0, rel=1e-13)
    assert estimate_a_f(0.9, 1.0, 0.0, 1.0, 1.0, 1.0, **kw) == pytest.approx(40.0, rel=1e-13)
    assert estimate_a_f(0.9, 1.0, -0.05, 1.0, 1.0, 1.0, **kw) == pytest.approx(40.0, rel=1e-13)
    # above 1 - lam_min: lam -> 0.9, 0.9 - 0.81 = 0.09, a_f = 40 again
    # (unclipped 0.95 would give 75.79, 1.0 a division by zero, 1.7 a negative a_f)
    for lam in (0.95, 1.0, 1.7, -1.7):
        assert estimate_a_f(0.9, 1.0, lam, 1.0, 1.0, 1.0, **kw) == pytest.approx(40.0, rel=1e-13)
    # inside [0.1, 0.9] nothing is clipped: lam = 0.2: 0.2 - 0.04 = 0.16, a_f = 3.6/0.16 = 22.5
    assert estimate_a_f(0.9, 1.0, 0.2, 1.0, 1.0, 1.0, **kw) == pytest.approx(22.5, rel=1e-13)
    # p = 1.2, where lam^0.2 - lam^1.2 is not symmetric about 1/2: the upper clip is 0.9
    # (0.9^0.2 * 0.1 = 0.09791483623609768), not 0.1 (0.1^0.2 * 0.9 = 0.5678616100);
    # a_f = 2^1.2 / 1 * 1 / 0.09791483623609768 = 23.4632135
    a_hi = estimate_a_f(1.0, 1.0, 0.99, 1.0, 1.0, 0.2, **kw)
    assert a_hi == pytest.approx(2.0**1.2 / (0.9**0.2 - 0.9**1.2), rel=1e-13)
    assert a_hi == pytest.approx(23.4632135, rel=1e-8)
    # a_f(lam = 0.01) with the lower clip 0.1: 2^1.2 / (0.1^0.2 * 0.9) = 4.0456982
    a_lo = estimate_a_f(1.0, 1.0, 0.01, 1.0, 1.0, 0.2, **kw)
    assert a_lo == pytest.approx(4.0456982, rel=1e-7)


def test_estimate_a_f_default_lam_min():
    # default lam_min = 1e-3; m = 1, V = h = L = U = 1: a_f = 4 / (1e-3 - 1e-6) = 4004.004004
    assert estimate_a_f(1.0, 1.0, 0.0, 1.0, 1.0, 1.0) == pytest.approx(4004.004004004004,
                                                                       rel=1e-12)
    # lam = 1 clipped to 0.999: 0.999 - 0.998001 = 0.000999, the same 4004.004
    assert estimate_a_f(1.0, 1.0, 1.0, 1.0, 1.0, 1.0) == pytest.approx(4004.004004004004,
                                                                       rel=1e-9)


def test_estimate_a_f_backward_length_at_least_h():
    # m = 1, V = 1, h = 0.5, lam = 0.5 (factor 0.25), U = 1: a_f = 4/0.5 / (0.25 L) = 32 / L
    # L = 0.1 < h -> L = h = 0.5: a_f = 64 (not 320)
    assert estimate_a_f(1.0, 0.5, 0.5, 0.1, 1.0, 1.0) == pytest.approx(64.0, rel=1e-14)
    # an empty backward-slip zone L = 0: also one element, 64
    assert estimate_a_f(1.0, 0.5, 0.5, 0.0, 1.0, 1.0) == pytest.approx(64.0, rel=1e-14)
    # L = h exactly: 64; L = 1 > h: kept, 32
    assert estimate_a_f(1.0, 0.5, 0.5, 0.5, 1.0, 1.0) == pytest.approx(64.0, rel=1e-14)
    assert estimate_a_f(1.0, 0.5, 0.5, 1.0, 1.0, 1.0) == pytest.approx(32.0, rel=1e-14)


def test_estimate_a_f_cap_and_non_finite():
    # the first hand case gives 64/3 = 21.33: capped to a_f_max = 20, untouched under 22
    assert estimate_a_f(3.0, 0.5, 0.25, 1.5, 2.0, 1.0, a_f_max=20.0) == 20.0
    assert estimate_a_f(3.0, 0.5, 0.25, 1.5, 2.0, 1.0, a_f_max=22.0) == pytest.approx(64 / 3)
    # default cap 1e6: lam_min = 1e-9 near-sticking, m = 1: 4 / (1e-9 - 1e-18) = 4e9 -> 1e6
    assert estimate_a_f(1.0, 1.0, 0.0, 1.0, 1.0, 1.0, lam_min=1e-9) == 1e6
    # overflow: 4 / 1e-3 * 1e308 = inf -> the cap
    assert estimate_a_f(1e308, 1e-3, 0.5, 1.0, 1.0, 1.0) == 1e6
    assert estimate_a_f(1e308, 1e-3, 0.5, 1.0, 1.0, 1.0, a_f_max=123.0) == 123.0
    # inf / inf = nan (numerator 4e3 * 1e308, denominator 0.25 * 1e308 * 100): min(nan, cap)
    # would be nan, the non-finite branch returns the cap
    assert estimate_a_f(1e308, 1e-3, 0.5, 1e308, 10.0, 1.0) == 1e6
    assert estimate_a_f(1e308, 1e-3, 0.5, 1e308, 10.0, 1.0, a_f_max=7.0) == 7.0


@pytest.mark.parametrize("args", [
    (0.0, 0.5, 0.5, 1.0, 1.0, 1.0), (-1.0, 0.5, 0.5, 1.0, 1.0, 1.0),   # volume_v_p <= 0
    (1.0, 0.0, 0.5, 1.0, 1.0, 1.0), (1.0, -0.5, 0.5, 1.0, 1.0, 1.0),   # h <= 0
    (1.0, 0.5, 0.5, 1.0, 0.0, 1.0), (1.0, 0.5, 0.5, 1.0, -2.0, 1.0),   # u_roll <= 0
])
def test_estimate_a_f_rejects_non_positive_inputs(args):
    with pytest.raises(ValueError):
        estimate_a_f(*args)


# =============================================================================================
# 2. friction laws: T_tau = -k_f v_s, k_f = coefficient(v_s^2, ...)
# =============================================================================================
def test_law_flags_names_and_defaults():
    vp, co, tr = ViscoplasticFriction(1e-3), CoulombFriction(1e-3), TrescaFriction(1e-3)
    # (2.29a) needs a_f only; Coulomb min(mu p, k) pressure and k; Tresca factor k only k
    assert (vp.uses_a_f, vp.uses_pressure, vp.uses_k) == (True, False, False)
    assert (co.uses_a_f, co.uses_pressure, co.uses_k) == (False, True, True)
    assert (tr.uses_a_f, tr.uses_pressure, tr.uses_k) == (False, False, True)
    assert (vp.name, co.name, tr.name) == ("viscoplastic", "coulomb", "tresca")
    # docstring defaults: K = 1 (reduced units), m = 0.2; mu = 0.3, rounding 1 %; factor 0.8
    assert (vp.K, vp.m, co.mu, co.rounding, tr.factor) == (1.0, 0.2, 0.3, 0.01, 0.8)
    with pytest.raises(NotImplementedError):
        FrictionLaw(1e-3).limit(pressure=1.0, k=1.0)


def test_smooth_helpers_on_pythagorean_triples():
    # (a + sqrt(a^2 + d^2)) / 2 with (3, 4, 5): (3 + 5)/2 = 4, (-3 + 5)/2 = 1, (0 + 4)/2 = 2
    assert smooth_positive_part(3.0, 4.0) == pytest.approx(4.0, rel=1e-15)
    assert smooth_positive_part(-3.0, 4.0) == pytest.approx(1.0, rel=1e-15)
    assert smooth_positive_part(0.0, 4.0) == pytest.approx(2.0, rel=1e-15)
    # (a + b - sqrt((a-b)^2 + d^2)) / 2: (1 + 4 - 5)/2 = 0 both ways round, (10 + 4 - 10)/2 = 2
    # with (6, 8, 10), at a = b: (2 + 2 - 6)/2 = -1
    assert smooth_minimum(1.0, 4.0, 4.0) == pytest.approx(0.0, abs=1e-15)
    assert smooth_minimum(4.0, 1.0, 4.0) == pytest.approx(0.0, abs=1e-15)
    assert smooth_minimum(10.0, 4.0, 8.0) == pytest.approx(2.0, rel=1e-15)
    assert smooth_minimum(2.0, 2.0, 6.0) == pytest.approx(-1.0, rel=1e-15)


def test_viscoplastic_law_by_hand():
    # (2.29a) regularised: k_f = a_f K (v_s^2 + v_reg^2)^((m-1)/2)
    law = ViscoplasticFriction(0.3, K=2.0, m=0.2)
    # v_reg = 0.3, v_s = 0.4: v_s^2 + v_reg^2 = 0.25, 0.25^(-0.4) = 2^0.8 = 1.7411011265922482;
    # a_f K = 3 * 2 = 6: k_f = 10.446606759553490
    assert law.coefficient(0.16, a_f=3.0) == pytest.approx(10.44660675955349, rel=1e-13)
    # shear -k_f v_s = -4.178642703821396, opposing the slip; +4.1786 for v_s = -0.4
    assert law.shear(0.4, a_f=3.0) == pytest.approx(-4.178642703821396, rel=1e-13)
    assert law.shear(-0.4, a_f=3.0) == pytest.approx(4.178642703821396, rel=1e-13)
    # dissipation k_f v_s^2 = 10.4466 * 0.16 = 1.6714570815285583 (>= 0 both ways)
    assert law.power_density(0.4, a_f=3.0) == pytest.approx(1.6714570815285583, rel=1e-13)
    assert law.power_density(-0.4, a_f=3.0) == pytest.approx(1.6714570815285583, rel=1e-13)
    # no slip, no shear; the coefficient there is a_f K v_reg^(m-1) = 6 * 0.3^-0.8 = 15.7200617
    assert law.shear(0.0, a_f=3.0) == 0.0
    assert law.coefficient(0.0, a_f=3.0) == pytest.approx(6.0 * 0.3**-0.8, rel=1e-13)
    assert law.coefficient(0.0, a_f=3.0) == pytest.approx(15.7200617, rel=1e-8)
    # m and K given at the call win: m = 1 is linear, k_f = a_f K = 3 * 5 = 15 at any slip
    assert law.coefficient(0.16, a_f=3.0, m=1.0, K=5.0) == pytest.approx(15.0, rel=1e-15)
    assert law.shear(0.4, a_f=3.0, m=1.0) == pytest.approx(-2.4, rel=1e-15)   # -6 * 0.4
    # m = 0: k_f = 6 / sqrt(0.25) = 12, shear -12 * 0.4 = -4.8
    assert law.shear(0.4, a_f=3.0, m=0.0) == pytest.approx(-4.8, rel=1e-14)
    # v_s >> v_reg: (2.29a) unregularised, -a_f K |v_s|^m sign(v_s); v_s = 32, m = 0.2: 32^0.2 = 2
    sharp = ViscoplasticFriction(1e-9, K=2.0, m=0.2)
    assert sharp.shear(32.0, a_f=3.0) == pytest.approx(-12.0, rel=1e-14)
    assert sharp.shear(-32.0, a_f=3.0) == pytest.approx(12.0, rel=1e-14)
    # arrays: element by element
    assert law.shear(np.array([0.4, -0.4, 0.0]), a_f=3.0) == pytest.approx(
        [-4.178642703821396, 4.178642703821396, 0.0], rel=1e-13)


def test_tresca_law_by_hand():
    law = TrescaFriction(0.3, factor=0.8)
    # |T| = factor k = 0.8 * 2 = 1.6, times v_s / sqrt(v_s^2 + v_reg^2) = 0.4 / 0.5 = 0.8
    assert law.coefficient(0.16, k=2.0) == pytest.approx(3.2, rel=1e-15)      # 1.6 / 0.5
    assert law.shear(0.4, k=2.0) == pytest.approx(-1.28, rel=1e-14)
    assert law.shear(-0.4, k=2.0) == pytest.approx(1.28, rel=1e-14)
    assert law.shear(0.0, k=2.0) == 0.0
    assert law.power_density(0.4, k=2.0) == pytest.approx(0.512, rel=1e-14)   # 3.2 * 0.16
    assert law.power_density(-0.4, k=2.0) == pytest.approx(0.512, rel=1e-14)
    # the pressure plays no part
    assert law.shear(0.4, k=2.0, pressure=-5.0) == pytest.approx(-1.28, rel=1e-14)
    # only the ratio v_s / v_reg counts: v_s = 4, v_reg = 3 -> 4/5 of 1.6 = 1.28 too
    assert TrescaFriction(3.0, factor=0.8).shear(4.0, k=2.0) == pytest.approx(-1.28, rel=1e-14)


def test_coulomb_exact_rounding_on_pythagorean_numbers():
    """limit = smooth_min(mu * smooth_pos(p, d/mu), k, d), d = rounding * k; note
    mu * smooth_pos(p, d/mu) = smooth_pos(mu p, d). mu = 0.5, k = 10, rounding 0.8: d = 8."""
    law = CoulombFriction(3.0, mu=0.5, rounding=0.8)
    # p = 30: mu p = 15, (15 + sqrt(225 + 64))/2 = (15 + 17)/2 = 16; (16 + 10 - sqrt(36 + 64))/2
    # = (26 - 10)/2 = 8; shear at v_s = 4, v_reg = 3: -8 * 4/5 = -6.4
    assert law.limit(pressure=30.0, k=10.0) == pytest.approx(8.0, rel=1e-14)
    assert law.shear(4.0, pressure=30.0, k=10.0) == pytest.approx(-6.4, rel=1e-14)
    assert law.shear(-4.0, pressure=30.0, k=10.0) == pytest.approx(6.4, rel=1e-14)
    assert law.power_density(4.0, pressure=30.0, k=10.0) == pytest.approx(25.6, rel=1e-14)
    # p = 0: (0 + 8)/2 = 4; (4 + 10 - sqrt(36 + 64))/2 = 2
    assert law.limit(pressure=0.0, k=10.0) == pytest.approx(2.0, rel=1e-14)
    assert law.coefficient(16.0, pressure=0.0, k=10.0) == pytest.approx(0.4, rel=1e-14)  # 2/5


def test_coulomb_default_rounding_below_at_and_above_the_kink():
    """mu = 0.5, k = 1, rounding 1 %: d = 0.01, kink at p = k/mu = 2. Values from the closed
    form evaluated to 30 digits (decimal)."""
    law = CoulombFriction(1e-9, mu=0.5)
    k = 1.0
    lim = lambda p: float(law.limit(pressure=p, k=k))   # noqa: E731
    # well below (mu p = 0.5): the two roundings nearly cancel, 0.49999999500149960
    assert lim(1.0) == pytest.approx(0.4999999950014996, rel=1e-12)
    assert abs(lim(1.0) - 0.5) < 1e-8 * k
    # well above (mu p = 5): k - d^2 / (4 * 4) ~ 0.99999375001757804
    assert lim(10.0) == pytest.approx(0.999993750017578, rel=1e-12)
    # at the kink mu p = k: k - d/2 + (lift of the positive part) = 0.99501248406332124,
    # within the docstring's 0.5 % of k of min(mu p, k) = 1
    assert lim(2.0) == pytest.approx(0.9950124840633212, rel=1e-12)
    assert 0.0 < 1.0 - lim(2.0) <= 0.005 * k
    # 1 % around it (mu p = 0.995, 1.005): 0.99192799936872160, 0.99691669428106292
    assert lim(1.99) == pytest.approx(0.9919279993687216, rel=1e-12)
    assert lim(2.01) == pytest.approx(0.9969166942810629, rel=1e-12)
    assert abs(lim(1.99) - 0.995) <= 0.005 * k and abs(lim(2.01) - 1.0) <= 0.005 * k
    # the other kink p = 0: smooth_pos(0, d) = d/2 = 0.005, minus the min's rounding:
    # 0.0049748750062967925 (<= 0.5 % of k)
    assert lim(0.0) == pytest.approx(0.004974875006296793, rel=1e-12)
    # tensile p = -1: 2.4994376124728590e-5, no shear to speak of
    assert lim(-1.0) == pytest.approx(2.499437612472859e-05, rel=1e-9)
    # shear opposes the slip with that magnitude (v_reg = 1e-9 negligible)
    assert law.shear(np.array([0.7, -0.7]), pressure=10.0, k=k) == pytest.approx(
        [-0.999993750017578, 0.999993750017578], rel=1e-12)


# =============================================================================================
# 3. fem/quantities.py
# =============================================================================================
class _Roll:
    """Stand-in for RollPass: the neutral point is centre - R (sin a, cos a)."""

    centre = (1.0, 2.0)
    radius = 0.5


def _straight(n, dx):
    x = dx * np.arange(n)
    return x, np.zeros(n)


def test_exit_corrected_replaces_the_exit_zone_by_the_line():
    # 26 nodes 0.04 apart on y = 0; h = 0.05: zone*h = 0.1, fit*h = 0.3; the distance to the
    # end d = 1 - x: near d in {0, 0.04, 0.08}, reference d in {0.12, ..., 0.28}
    x, y = _straight(26, 0.04)
    line = -100.0 - 50.0 * x
    sn = line.copy()
    sn[-3:] += [30.0, -20.0, 10.0]                  # the oscillation at the exit
    prof = {"x": x, "y": y, "normal_stress": sn.copy()}
    out = exit_corrected(prof, 0.05)
    assert np.allclose(out[-3:], line[-3:], rtol=0, atol=1e-9)   # the line, extrapolated
    assert np.array_equal(out[:-3], sn[:-3])                     # the rest untouched
    assert np.array_equal(prof["normal_stress"], sn)             # input not modified


def test_exit_corrected_measures_distance_along_the_arc():
    # circle R = 0.5, nodes 0.08 rad apart: chords 2R sin(0.04) = 0.0399893; a stress linear
    # in the polyline length s is given back exactly (in x it is not linear: x = R sin)
    th = 0.08 * np.arange(26)
    x, y = 0.5 * np.sin(th), 0.5 * (1.0 - np.cos(th))
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    line = 3.0 + 7.0 * s
    sn = line.copy()
    sn[-3:] += [1.0, -2.0, 0.5]
    out = exit_corrected({"x": x, "y": y, "normal_stress": sn}, 0.05)
    assert np.allclose(out, line, rtol=0, atol=1e-9)


def test_exit_corrected_four_unevenly_spaced_nodes():
    """Four nodes (the fewest corrected) at x = 0, 0.5, 1.25, 1.5: the distance to the end is
    summed from the end, d = 1.5, 1.0, 0.25, 0 (not the forward sums 1.5, 1.25, 0.5). h = 0.3:
    zone*h = 0.6, fit*h = 1.8; reference d = 1.5, 1.0 (values 4, 2): the line 4 (d - 1.5) + 4
    gives -1 at d = 0.25 and -2 at d = 0."""
    x = np.array([0.0, 0.5, 1.25, 1.5])
    prof = {"x": x, "y": np.zeros(4), "normal_stress": np.array([4.0, 2.0, 9.0, -9.0])}
    assert exit_corrected(prof, 0.3) == pytest.approx([4.0, 2.0, -1.0, -2.0], rel=1e-12,
                                                      abs=1e-12)
    # three nodes are returned as they are
    three = {"x": x[:3], "y": np.zeros(3), "normal_stress": np.array([4.0, 2.0, 9.0])}
    assert np.array_equal(exit_corrected(three, 0.3), [4.0, 2.0, 9.0])


def test_exit_corrected_least_squares_fit_and_zone_bounds():
    """Nodes 0.25 apart (exact binary fractions), h = 0.25: zone*h = 0.5, fit*h = 1.5. Distance
    to the end d = 1.75, 1.5, ..., 0. A node at d = 0.5 is a reference node (>=), not corrected;
    d = 1.5 is outside the fit (<)."""
    x, y = _straight(8, 0.25)
    #          d = 1.75   1.5   1.25  1.0  0.75  0.5   0.25   0
    sn = np.array([50.0, 100.0, 4.0, 2.0, 3.0, 1.0, 77.0, -55.0])
    out = exit_corrected({"x": x, "y": y, "normal_stress": sn}, 0.25)
    # least squares through (0.5, 1), (0.75, 3), (1.0, 2), (1.25, 4): means 0.875 and 2.5,
    # Sxx = 0.3125, Sxy = 1.0: slope 3.2, intercept 2.5 - 3.2 * 0.875 = -0.3;
    # at d = 0.25: 0.5, at d = 0: -0.3
    expected = [50.0, 100.0, 4.0, 2.0, 3.0, 1.0, 0.5, -0.3]
    assert out == pytest.approx(expected, rel=1e-12, abs=1e-12)
    # 5 nodes, d = 1, 0.75, 0.5, 0.25, 0; near d < 0.5. fit = 3 (fit*h = 0.75): the only
    # reference node is d = 0.5 -> too few, unchanged. fit = 3.01 (0.7525): d = 0.5 and 0.75
    # (values 1 and 3), exactly two are enough: line 1 + 8 (d - 0.5): -1 at d = 0.25, -3 at 0
    x5, y5 = _straight(5, 0.25)
    sn5 = np.array([9.0, 3.0, 1.0, 77.0, -55.0])          # d = 1, 0.75, 0.5, 0.25, 0
    p5 = {"x": x5, "y": y5, "normal_stress": sn5}
    assert np.array_equal(exit_corrected(p5, 0.25, fit=3.0), sn5)
    assert exit_corrected(p5, 0.25, fit=3.01) == pytest.approx([9.0, 3.0, 1.0, -1.0, -3.0],
                                                               rel=1e-12, abs=1e-12)


def test_exit_corrected_fallbacks_return_the_input():
    # fewer than 4 nodes: with h = 0.04 (zone 0.08, fit 0.24) d = 0.2, 0.1 would be reference
    # nodes and d = 0 corrected to 9 (the line through (0.2, 1), (0.1, 5)); raw instead
    p3 = {"x": np.array([0.0, 0.1, 0.2]), "y": np.zeros(3), "normal_stress": [1.0, 5.0, -3.0]}
    assert np.array_equal(exit_corrected(p3, 0.04), [1.0, 5.0, -3.0])
    # too few reference nodes: 5 nodes 0.04 apart, h = 0.07 (zone 0.14, fit 0.42): reference
    # d = 0.16 only
    x, y = _straight(5, 0.04)
    sn = np.array([1.0, 2.0, 30.0, -4.0, 50.0])
    assert np.array_equal(exit_corrected({"x": x, "y": y, "normal_stress": sn}, 0.07), sn)
    # zone = 0: nothing near the exit to correct
    x, y = _straight(26, 0.04)
    sn = np.sin(np.arange(26.0))
    assert np.array_equal(exit_corrected({"x": x, "y": y, "normal_stress": sn}, 0.05,
                                         zone=0.0), sn)


def _zigzag(n):
    """Nodes with segments (0.375, +-0.5): 0.625 long along the polyline, 0.375 in x (exact
    binary fractions): s_i = 0.625 i, x_i = 0.375 i."""
    i = np.arange(n)
    return {"x": 0.375 * i, "y": 0.5 * (i % 2)}


def test_contact_loss_stretches_measured_along_the_arc():
    prof = _zigzag(10)
    neg = -np.ones(10)
    assert contact_loss(prof, neg, 0.1) == []                       # no tensile stretch
    # at the start, nodes 0..2: arc 1.25, x extent 0.75
    sn = neg.copy()
    sn[0:3] = 2.0
    assert contact_loss(prof, sn, 1.25) == [[0.0, 0.75]]            # 1.25 >= 1.25: kept
    assert contact_loss(prof, sn, 1.0) == [[0.0, 0.75]]             # 1.25 along the arc
    assert contact_loss(prof, sn, 1.2500001) == []                  # shorter than asked
    # in the middle, nodes 4..5: arc 0.625 (x 1.5 .. 1.875)
    sn = neg.copy()
    sn[4:6] = 1.0
    assert contact_loss(prof, sn, 0.625) == [[1.5, 1.875]]
    assert contact_loss(prof, sn, 0.7) == []
    # at the end, nodes 7..9: x 2.625 .. 3.375, arc 1.25
    sn = neg.copy()
    sn[7:] = 3.0
    assert contact_loss(prof, sn, 1.25) == [[2.625, 3.375]]
    # two stretches, start and end
    sn = neg.copy()
    sn[0:3] = 2.0
    sn[7:] = 3.0
    assert contact_loss(prof, sn, 1.0) == [[0.0, 0.75], [2.625, 3.375]]
    # the same with the middle one too short (0.625 < 1) dropped
    sn[4:6] = 1.0
    assert contact_loss(prof, sn, 1.0) == [[0.0, 0.75], [2.625, 3.375]]
    assert contact_loss(prof, sn, 0.625) == [[0.0, 0.75], [1.5, 1.875], [2.625, 3.375]]
    # a zero stress is not tensile: it ends the stretch (0..2 stays 1.25 long, not 1.875)
    sn = neg.copy()
    sn[0:3] = 2.0
    sn[3] = 0.0
    assert contact_loss(prof, sn, 1.25) == [[0.0, 0.75]]
    assert contact_loss(prof, sn, 1.3) == []
    # ... nor does it start one: a zero before nodes 4..5 leaves the stretch at x 1.5 .. 1.875
    sn = neg.copy()
    sn[3] = 0.0
    sn[4:6] = 1.0
    assert contact_loss(prof, sn, 0.625) == [[1.5, 1.875]]
    # a lone zero is no stretch even of zero length
    sn = neg.copy()
    sn[5] = 0.0
    assert contact_loss(prof, sn, 0.0) == []
    # a single tensile node has zero length: only with min_length 0
    sn = neg.copy()
    sn[5] = 1.0
    assert contact_loss(prof, sn, 0.0) == [[1.875, 1.875]]
    assert contact_loss(prof, sn, 1e-12) == []
    # all tensile: one stretch over the whole arc 9 * 0.625 = 5.625
    assert contact_loss(prof, np.ones(10), 5.625) == [[0.0, 3.375]]
    # two tensile nodes are a stretch 0.625 long (x 0 .. 0.375); fewer than two nodes: nothing
    assert contact_loss(_zigzag(2), [1.0, 2.0], 0.5) == [[0.0, 0.375]]
    assert contact_loss({"x": [0.0], "y": [0.0]}, [5.0], 0.0) == []


def test_neutral_index_minimises_the_misclassified_count():
    # clean sign change: split before the first positive node
    assert neutral_index(np.array([-3.0, -2.0, -1.0, 1.0, 2.0])) == 3
    # noise in a sticking zone: costs k=3: 0 + 3 (nodes 4, 5, 8); k=6: 1 (node 3) + 1 (node 8)
    # = 2; k=9: 3 + 0 = 3; k=6 is the unique minimum (not the first sign change at 3)
    v = np.array([-3, -2, -1, 0.1, -1, -1, 1, 2, -0.1, 3, 4])
    assert neutral_index(v) == 6
    # all positive: 0; all negative: n; empty: 0
    assert neutral_index(np.array([1.0, 2.0, 0.5])) == 0
    assert neutral_index(np.array([-1.0, -2.0, -0.5])) == 3
    assert neutral_index(np.zeros(0)) == 0
    # zeros count on neither side: [0, 0, -1, 1] costs 1, 1, 1, 0, 1 -> 3 (if zeros counted as
    # forward slip, k = 3 would cost 2 and k = 0 win)
    assert neutral_index(np.array([0.0, 0.0, -1.0, 1.0])) == 3
    # a zero slip is neither backward nor forward: trailing zeros do not pull the split past
    # them (counted as backward, the split would move to 4)
    assert neutral_index(np.array([-1.0, 1.0, 0.0, 0.0])) == 1
    # weights: [-1, 1, -1, 1] unweighted ties at k = 1 and 3 (cost 1) -> 1; with weights
    # [1, 1, 5, 1]: costs 6, 5, 6, 1, 2 -> 3
    v = np.array([-1.0, 1.0, -1.0, 1.0])
    assert neutral_index(v) == 1
    assert neutral_index(v, np.array([1.0, 1.0, 5.0, 1.0])) == 3


def test_neutral_point_interpolates_the_zero_crossing():
    rp = _Roll()
    # split between nodes 2 and 3: v_s = -1 at angle 0.2, +3 at 0.1; zero at s = -1/(-1-3)
    # = 0.25 of the way: 0.2 + 0.25 * (0.1 - 0.2) = 0.175
    prof = {"angle": np.array([0.4, 0.3, 0.2, 0.1, 0.0]),
            "v_slip": np.array([-3.0, -2.0, -1.0, 3.0, 5.0])}
    (xn, yn), a = neutral_point(prof, rp)
    assert a == pytest.approx(0.175, rel=1e-14)
    # on the roll: centre (1, 2) - 0.5 (sin 0.175, cos 0.175), sin 0.175 = 0.17410813759,
    # cos 0.175 = 0.98472653890
    assert xn == pytest.approx(1.0 - 0.5 * 0.17410813759, rel=1e-10)
    assert yn == pytest.approx(2.0 - 0.5 * 0.98472653890, rel=1e-10)
    # a zero slip node is the neutral point itself: [-1, 0, 1] splits at 1, s = -1/(-1 - 0) = 1
    prof = {"angle": np.array([0.3, 0.2, 0.1]), "v_slip": np.array([-1.0, 0.0, 1.0])}
    assert neutral_point(prof, rp)[1] == pytest.approx(0.2, rel=1e-14)
    # a spike at the first touching node is outvoted: [+5, -1, -1, -1, 1, 1], angles 1.0 ..
    # 0.5: split at 4, between 0.7 and 0.6 half way: 0.65
    prof = {"angle": np.array([1.0, 0.9, 0.8, 0.7, 0.6, 0.5]),
            "v_slip": np.array([5.0, -1.0, -1.0, -1.0, 1.0, 1.0])}
    assert neutral_point(prof, rp)[1] == pytest.approx(0.65, rel=1e-14)


def test_neutral_point_weights_nodes_by_their_arc_spacing():
    # angles [1, 0.99, 0.98, 0.5, 0]: |gradient| = [0.01, 0.01, 0.245, 0.49, 0.5];
    # v_s = [-1, 1, 1, -1, 1]: weighted costs 0.5, 0.49, 0.5, 0.745, 0.255, 0.755 -> split 4,
    # half way between 0.5 and 0: 0.25 (unweighted, the split would be 1 and the angle 0.995)
    prof = {"angle": np.array([1.0, 0.99, 0.98, 0.5, 0.0]),
            "v_slip": np.array([-1.0, 1.0, 1.0, -1.0, 1.0])}
    assert neutral_point(prof, _Roll())[1] == pytest.approx(0.25, rel=1e-14)


def test_neutral_point_one_signed_and_empty_profiles():
    rp = _Roll()
    ang = np.array([0.4, 0.3, 0.2])
    # all forward slip: the first node; all backward: the last node
    assert neutral_point({"angle": ang, "v_slip": np.array([1.0, 2.0, 3.0])}, rp)[1] == 0.4
    assert neutral_point({"angle": ang, "v_slip": -np.array([1.0, 2.0, 3.0])}, rp)[1] == 0.2
    # single node either way: its angle
    one = np.array([0.3])
    assert neutral_point({"angle": one, "v_slip": np.array([2.0])}, rp)[1] == 0.3
    assert neutral_point({"angle": one, "v_slip": np.array([-2.0])}, rp)[1] == 0.3
    # no contact: nan everywhere
    (xn, yn), a = neutral_point({"angle": np.zeros(0), "v_slip": np.zeros(0)}, rp)
    assert math.isnan(xn) and math.isnan(yn) and math.isnan(a)


def test_smoothed_single_edge_by_hand():
    # one P2 edge of length L = 2 (x 0, 1, 2); P1 mass matrix L/6 [[2, 1], [1, 2]], load
    # L [ya/6 + ym/3, ym/3 + yb/6]
    prof = {"x": np.array([0.0, 1.0, 2.0]), "y": np.zeros(3), "vertex": [1, 0, 1]}
    # the bubble 4t(1-t) (0, 1, 0): symmetric, the constant 2/3 (its mean)
    assert smoothed(prof, np.array([0.0, 1.0, 0.0])) == pytest.approx([2 / 3] * 3, rel=1e-13)
    # the quadratic 2t^2 - t (0, 0, 1): loads [0, 1/6] (L = 1 units), c0/3 + c1/6 = 0,
    # c0/6 + c1/3 = 1/6 -> c1 = 2/3, c0 = -1/3; midpoint the mean 1/6
    assert smoothed(prof, np.array([0.0, 0.0, 1.0])) == pytest.approx([-1 / 3, 1 / 6, 2 / 3],
                                                                      rel=1e-13)
    # no "vertex" key: the alternation is assumed, same answer
    prof2 = {"x": prof["x"], "y": prof["y"]}
    assert smoothed(prof2, np.array([0.0, 0.0, 1.0])) == pytest.approx([-1 / 3, 1 / 6, 2 / 3],
                                                                       rel=1e-13)


def test_smoothed_keeps_the_resultant_on_uneven_edges():
    """Two edges whose midpoints are not halfway (the report's scheme moves the nodes): an
    edge's length is the sum of its two halves, and the projection keeps the resultant along
    the arc, sum L (ya + 4 ym + yb) / 6 (Simpson on each edge), exactly."""
    x = np.array([0.0, 0.3, 1.0, 1.9, 2.5])            # halves 0.3 + 0.7 and 0.9 + 0.6
    prof = {"x": x, "y": np.zeros(5), "vertex": [1, 0, 1, 0, 1]}
    y = np.array([1.0, 3.0, 2.0, 5.0, 0.5])
    out = smoothed(prof, y)
    L = np.array([1.0, 1.5])
    simpson = np.sum(L * (y[0:-1:2] + 4 * y[1::2] + y[2::2]) / 6.0)
    assert np.sum(L * 0.5 * (out[0:-1:2] + out[2::2])) == pytest.approx(simpson, rel=1e-13)


def test_smoothed_falls_back_to_the_raw_values():
    zig = np.array([0.0, 1.0, 0.0, 1.0, 0.0])
    t = np.arange(5.0)
    prof = {"x": t, "y": np.zeros(5), "vertex": [1, 0, 1, 0, 1]}
    assert not np.allclose(smoothed(prof, zig), zig)                 # alternating: smoothed
    # the vertex pattern does not alternate (a contact vertex without its edge)
    bad = dict(prof, vertex=[1, 1, 0, 1, 0])
    out = smoothed(bad, zig)
    assert np.array_equal(out, zig) and out is not zig
    # even length (a half edge): raw
    p4 = {"x": t[:4], "y": np.zeros(4), "vertex": [1, 0, 1, 0]}
    assert np.array_equal(smoothed(p4, zig[:4]), zig[:4])
    p4 = {"x": t[:4], "y": np.zeros(4)}
    assert np.array_equal(smoothed(p4, zig[:4]), zig[:4])
    # fewer than 3 nodes: raw
    assert np.array_equal(smoothed({"x": t[:1], "y": np.zeros(1)}, np.array([7.0])), [7.0])
    # a raw copy, not the caller's array
    out[0] = 99.0
    assert zig[0] == 0.0


# =============================================================================================
# 4. results/engineering.py
# =============================================================================================
def test_display_scales_and_units():
    # N/m -> MN/m at >= 1e6: 1.23e6 N/m = 1.23 MN/m
    assert display("roll_force", 1.23e6) == ("1.23", "MN/m")
    assert display("roll_force", -2.5e6) == ("-2.5", "MN/m")         # |value| decides
    assert display("roll_force", 1e6) == ("1", "MN/m")               # threshold included
    assert display("roll_force", 999_000.0) == ("999000", "N/m")     # below: SI, 6 digits
    assert display("roll_force", 2_000_000) == ("2", "MN/m")         # ints too
    assert display("roll_force", 1.23456e6) == ("1.235", "MN/m")     # 4 significant digits
    # N m/m -> kN m/m at >= 1e3: 4.56e4 = 45.6; W/m -> kW/m: 7.89e5 = 789
    assert display("roll_torque", 4.56e4) == ("45.6", "kN m/m")
    assert display("roll_torque", 999.0) == ("999", "N m/m")
    assert display("roll_power", 7.89e5) == ("789", "kW/m")
    # whole-width figures: N -> MN, N m -> kN m, W -> kW
    assert display("roll_force_total", 3.2e7) == ("32", "MN")
    assert display("roll_torque_total", 5e5) == ("500", "kN m")
    assert display("mill_power", 1.234e6) == ("1234", "kW")
    # Pa -> MPa at >= 1e6: 1.5e8 Pa = 150 MPa; 5e5 Pa stays in Pa
    assert display("mean_pressure", 1.5e8) == ("150", "MPa")
    # every threshold included, exactly at 1e6 (N, Pa) and 1e3 (N m, N m/m, W, W/m)
    assert display("roll_force_total", 1e6) == ("1", "MN")
    assert display("mean_pressure", 1e6) == ("1", "MPa")
    assert display("roll_torque", 1e3) == ("1", "kN m/m")
    assert display("roll_torque_total", 1e3) == ("1", "kN m")
    assert display("roll_power", 1e3) == ("1", "kW/m")
    assert display("mill_power", 1e3) == ("1", "kW")
    assert display("back_tension", 5e5) == ("500000", "Pa")
    # units without a scale: 6 significant digits
    assert display("forward_slip", 0.0123456789) == ("0.0123457", "-")
    assert display("K", 2.0e8) == ("2e+08", "Pa s^m")
    assert display("unknown_key", 123.456789) == ("123.457", "")
    # not a finite number: no text, the unit still
    for v in (None, "1e6", True, math.nan, math.inf, [1.0]):
        assert display("roll_force", v) == (None, "N/m")


def test_units_of_the_main_figures():
    assert UNITS["roll_force"] == "N/m" and UNITS["roll_torque"] == "N m/m"
    assert UNITS["roll_power"] == "W/m" and UNITS["mill_power"] == "W"
    assert UNITS["roll_force_total"] == "N" and UNITS["neutral_angle"] == "rad"
    assert UNITS["mean_flow_stress"] == "Pa" and UNITS["mean_strain_rate"] == "1/s"


def test_width_totals_by_hand():
    s = {"roll_force": 2.0e6, "roll_torque": 3.0e5, "roll_power": 4.0e5}
    t = width_totals(s, 1.5)
    # per unit width x 1.5 m; the mill power both rolls: 2 x 4e5 x 1.5 = 1.2e6 W
    assert t == {"width": 1.5, "roll_force_total": pytest.approx(3.0e6, rel=1e-15),
                 "roll_torque_total": pytest.approx(4.5e5, rel=1e-15),
                 "roll_power_total": pytest.approx(6.0e5, rel=1e-15),
                 "mill_power": pytest.approx(1.2e6, rel=1e-15)}
    assert width_totals(s, None) == {"width": None}


# =============================================================================================
# 5. algorithms: continuation path, default lengths, steady test scales; runner helpers
# =============================================================================================
class _Pass:
    def __init__(self, contact_length=0.1, half_entry=0.05, half_exit=0.04, radius=0.6,
                 u_roll=1.0):
        self.contact_length, self.half_entry, self.half_exit = contact_length, half_entry, half_exit
        self.radius, self.u_roll = radius, u_roll


def test_continuation_path_by_hand():
    from hotroll.solvers.steady_settings import continuation_path

    # n = ceil(log2(1/m)) geometric steps 1 -> m (each at most a factor 2)
    assert continuation_path(0.5) == pytest.approx([0.5], rel=1e-14)              # n = 1
    assert continuation_path(0.25) == pytest.approx([0.5, 0.25], rel=1e-14)       # n = 2
    assert continuation_path(0.6) == pytest.approx([0.6], rel=1e-14)              # n = 1
    # m = 0.2: log2 5 = 2.32 -> n = 3: 0.2^(1/3) = 0.584804, 0.2^(2/3) = 0.341995, 0.2
    assert continuation_path(0.2) == pytest.approx([0.5848035476, 0.3419951893, 0.2],
                                                   rel=1e-9)
    # m = 0.1: log2 10 = 3.32 -> n = 4: 0.1^(1/4) = 0.562341, 0.1^(1/2), 0.1^(3/4), 0.1
    assert continuation_path(0.1) == pytest.approx([0.5623413252, 0.3162277660, 0.1778279410,
                                                    0.1], rel=1e-9)
    # m >= 1: no continuation
    assert continuation_path(1.0) == [1.0]
    assert continuation_path(1.5) == [1.5]


def test_default_lengths_by_hand():
    from hotroll.solvers.steady_settings import default_lengths

    # max(l_c, 4 h0/2), max(l_c, 4 h1/2): a long contact wins both
    assert default_lengths(_Pass(0.2, 0.01, 0.008)) == pytest.approx((0.2, 0.2))
    # a thick strip: 4 * 0.05 = 0.2 and 4 * 0.04 = 0.16
    assert default_lengths(_Pass(0.1, 0.05, 0.04)) == pytest.approx((0.2, 0.16))


def test_runner_contact_tolerance_and_end_time():
    from hotroll.workflows.runner import contact_tolerance, default_end_time

    # R = 0.6, U = 1, dt = 1e-3: drift 10 (1e-3)^2 / 1.2 = 8.333e-6, 6 x = 5e-5 > 1e-5
    assert contact_tolerance(_Pass(radius=0.6, u_roll=1.0), 1e-3) == pytest.approx(5e-5)
    # R = 1.2, U = 1, dt = 1e-4: 6 x 10 x 1e-8 / 2.4 = 2.5e-7 < 1e-5 x 1.2/0.6 = 2e-5
    assert contact_tolerance(_Pass(radius=1.2, u_roll=1.0), 1e-4) == pytest.approx(2e-5)
    # three contact lengths at the roll speed: 3 x 0.1 / 2 = 0.15 s
    assert default_end_time(_Pass(contact_length=0.1, u_roll=2.0)) == pytest.approx(0.15)


def _rows(n_old, n_new, **shift):
    """History rows, constant per window: the keys the steady test reads, the newer window
    shifted by ``shift[key]``."""
    base = {"roll_force": 1.0e6, "roll_torque": 2.0e5, "strain_rate_measure": 3.0,
            "forward_slip": 0.1, "neutral_angle": 0.05}
    old = [dict(base) for _ in range(n_old)]
    new = [{k: v + shift.get(k, 0.0) for k, v in base.items()} for _ in range(n_new)]
    return old + new


def test_steady_reached_scales_per_key():
    from hotroll.solvers.settling import steady_reached

    tol, bite = 1e-3, 0.4
    args = (4, 2, tol, bite)                   # window 4 rows, period 2: no noise here
    assert steady_reached(_rows(4, 4), *args)
    # relative for the force: 1e-3 x 1e6 = 1000 N/m
    assert steady_reached(_rows(4, 4, roll_force=990.0), *args)
    assert not steady_reached(_rows(4, 4, roll_force=1010.0), *args)
    # neutral angle: 1e-3 x 10 x bite angle 0.4 = 4e-3 rad (not relative to 0.05 rad)
    assert steady_reached(_rows(4, 4, neutral_angle=3.9e-3), *args)
    assert not steady_reached(_rows(4, 4, neutral_angle=4.1e-3), *args)
    # forward slip: 1e-3 x (1 + 0.1) = 1.1e-3 (not 1e-3 x 0.1)
    assert steady_reached(_rows(4, 4, forward_slip=1.05e-3), *args)
    assert not steady_reached(_rows(4, 4, forward_slip=1.15e-3), *args)
    # fewer than two windows: not yet
    assert not steady_reached(_rows(4, 3), *args)
    # the bound itself counts as steady: force 1024, tol 2^-10 -> 1 N/m; a change of exactly 1
    # (binary fractions, no rounding) passes, 1 + 2^-40 does not
    def force(shift):
        r = _rows(4, 4)
        for i, row in enumerate(r):
            row["roll_force"] = 1024.0 + (shift if i >= 4 else 0.0)
        return r

    assert steady_reached(force(1.0), 4, 2, 2.0**-10, bite)
    assert not steady_reached(force(1.0 + 2.0**-40), 4, 2, 2.0**-10, bite)


def test_steady_reached_noise_allowance_by_hand():
    from hotroll.solvers.settling import steady_reached

    # period 1, window 4: force batch means older [10, 12, 10, 12], newer the same + 1 (+1.7):
    # sample variances 4/3 each, noise = 2 sqrt((4/3 + 4/3) / 4) = 1.63299; tol x 11 = 0.011
    def rows(shift):
        r = _rows(4, 4)
        for i, row in enumerate(r):
            row["roll_force"] = (10.0 if i % 2 == 0 else 12.0) + (shift if i >= 4 else 0.0)
        return r

    assert steady_reached(rows(1.0), 4, 1, 1e-3, 0.4)        # 1 <= 1.633
    assert steady_reached(rows(1.6), 4, 1, 1e-3, 0.4)        # 1.6 <= 1.633
    assert not steady_reached(rows(1.7), 4, 1, 1e-3, 0.4)    # 1.7 > 1.633


def test_summary_windows_by_hand():
    """Whole projection periods covering 3 h of roll travel (ceil, not round); the steady
    window at least 6 periods; no projection (0) counts as a period of one step."""
    from hotroll.solvers.settling import summary_windows

    # 3 h / (U dt) = 0.06 / (0.2 pi / 300) = 28.65 steps -> 3 periods of 10; steady: 6 periods
    assert summary_windows(0.02, 0.2 * math.pi, 1.0 / 300.0, 10) == (30, 60)
    # 3 x 0.25 / (1 x 0.125) = 6 steps exactly: 1.2 periods of 5 -> 2 (not 1)
    assert summary_windows(0.25, 1.0, 0.125, 5) == (10, 30)
    assert summary_windows(0.25, 1.0, 0.125, 4) == (8, 24)          # 1.5 -> 2 periods of 4
    assert summary_windows(0.25, 1.0, 0.125, 0) == (6, 6)           # period 1: 6 steps
    assert summary_windows(0.25, 1.0, 0.125, 1) == (6, 6)
    # many periods: the steady window is the summary window (not 6 periods)
    assert summary_windows(0.25, 1.0, 0.0078125, 2) == (96, 96)     # 96 steps, 48 periods


def test_transit_time_by_hand():
    """One contact transit l_c / U; with a carried strain, at the entry speed U h1/h0 plus 20 %."""
    from types import SimpleNamespace

    from hotroll.solvers.settling import transit_time

    rp = SimpleNamespace(contact_length=0.1, u_roll=0.5, half_entry=0.25, half_exit=0.2)
    assert transit_time(rp, False) == pytest.approx(0.2, rel=1e-14)
    assert transit_time(rp, True) == pytest.approx(0.2 * 1.2 * 0.25 / 0.2, rel=1e-14)


def test_the_soft_zone_anywhere_along_x():
    """Table 1's penalties at points: 10/h inside the zone I = (lo, hi), 25/h outside and on its
    ends, wherever the roll axis puts the zone (left of x = 0 here, as the steady solver's roll
    frame does)."""
    from hotroll.fem.penalties import PenaltyTable

    pen = PenaltyTable(h=0.1)
    x = np.array([-0.5, -0.3, -0.25, -0.2, -0.1, 0.1, 0.25])
    assert np.array_equal(pen.at_nodes(x, (-0.3, -0.2)),
                          np.array([25.0, 25.0, 10.0, 25.0, 25.0, 25.0, 25.0]) / 0.1)
    assert np.array_equal(pen.at_nodes(x, (0.2, 0.3)),
                          np.array([25.0, 25.0, 25.0, 25.0, 25.0, 25.0, 10.0]) / 0.1)


def test_the_contact_files_vertex_column_is_integer(solved_example1):
    """contact.csv's "vertex" column (1 at a mesh vertex, 0 at an edge midpoint) is written as
    the integers 0 and 1, as its header says (a flag, not a measurement)."""
    import csv
    import json

    with open(solved_example1 / "contact.csv", newline="") as fh:
        column = [row["vertex"] for row in csv.DictReader(fh)]
    assert set(column) == {"0", "1"}
    # (the unilateral default: the summary says so)
    assert json.loads((solved_example1 / "summary.json").read_text())["unilateral"] is True


def test_the_p1_space_is_made_once_per_mesh_and_sets_as_a_new_one():
    """``p1_space``: the same space for the same mesh, a new one for another mesh; a field set
    on it has the values a field on a space of its own gets."""
    from netgen.geom2d import unit_square
    from ngsolve import H1, GridFunction, Mesh, x, y

    from hotroll.fem.quantities import p1_space

    a, b = Mesh(unit_square.GenerateMesh(maxh=0.3)), Mesh(unit_square.GenerateMesh(maxh=0.2))
    fa = p1_space(a)
    assert p1_space(a) is fa and p1_space(b) is not fa and p1_space(b).mesh.nv == b.nv
    cf = x * x + 3 * y
    kept, own = GridFunction(p1_space(a)), GridFunction(H1(a, order=1))
    kept.Set(cf)
    own.Set(cf)
    assert np.array_equal(kept.vec.FV().NumPy(), own.vec.FV().NumPy())
