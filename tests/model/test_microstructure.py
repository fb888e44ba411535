"""Recrystallisation kinetics (issue 33, model/microstructure): JMAK in isothermal and
non-isothermal holds against closed forms and a quadrature of the additivity integral, the
integrator's order, Hodgson and Gibbs' equations against values worked by hand from the
printed equations, grain growth, the limits, and bad input."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from hotroll.model.microstructure import get_set, sets_for
from hotroll.model.microstructure.base import R
from hotroll.model.microstructure.jmak import fraction, hold, tau_at
from hotroll.model.microstructure.registry import UnknownSet
from hotroll.model.microstructure.softening import (
    KineticsRangeError,
    pass_state,
    soften,
)

HG = get_set("hodgson_gibbs_cmn")
C = 273.15


def test_isothermal_hold_is_jmak_exactly():
    """Constant T: the additive integral is t / t_0.5 at every step, X = 1 - exp(ln 0.5
    (t/t_0.5)^n) to rounding, for n = 1, 1.5, 2 (the table of X at t/t_0.5 = 0.5, 1, 2, 4
    worked by hand: n = 2 gives 0.159, 0.5, 0.9375, 0.99998)."""
    t05 = 0.7
    times = np.linspace(0.0, 4 * t05, 9)
    T = np.full((times.size, 3), 1273.15)
    for n in (1.0, 1.5, 2.0):
        res = hold(times, T, lambda Ti, i: np.full(3, t05), n)
        assert np.allclose(res.X, 1.0 - np.exp(math.log(0.5) * 4.0**n), rtol=0, atol=1e-14)
    x = fraction(np.array([0.5, 1.0, 2.0, 4.0]), 2.0)
    assert np.allclose(x, [0.1591, 0.5, 0.9375, 0.99998], atol=1e-4)
    assert tau_at(0.5, 1.7) == pytest.approx(1.0, rel=1e-14)


def _cooling(t_end=2.0, T0=1000 + C, T1=950 + C):
    return lambda t: T0 + (T1 - T0) * t / t_end


def test_non_isothermal_hold_against_quadrature_and_second_order():
    """Linear cooling 1000 -> 950 degC over 2 s after eps = 0.3, d0 = 100 um (H&G SRX, n = 1):
    tau = int dt / t_0.5(T(t)) by adaptive quadrature (tau = 1.0452, X = 0.5154 by hand).
    The trapezoid steps converge to it at order 2 (the error ratio 4 per halving)."""
    Tt = _cooling()

    def t05(T):
        return float(HG.srx_half_time(0.3, 100e-6, 10.0, T))

    tau_ref = quad(lambda t: 1.0 / t05(Tt(t)), 0.0, 2.0, epsabs=1e-13, epsrel=1e-13)[0]
    assert tau_ref == pytest.approx(1.0452, rel=2e-3)     # by hand with R = 8.314: 1.2e-3
    errors = []
    for n in (4, 8, 16, 32):
        times = np.linspace(0.0, 2.0, n + 1)
        T = Tt(times)[:, None]
        res = hold(times, T, lambda Ti, i: HG.srx_half_time(0.3, 100e-6, 10.0, Ti), 1.0)
        errors.append(abs(res.tau[0] - tau_ref))
    rates = [math.log2(a / b) for a, b in zip(errors[:-1], errors[1:])]
    assert all(1.9 < r < 2.1 for r in rates), rates
    fine = hold(np.linspace(0.0, 2.0, 2001), Tt(np.linspace(0.0, 2.0, 2001))[:, None],
                lambda Ti, i: HG.srx_half_time(0.3, 100e-6, 10.0, Ti), 1.0)
    assert fine.X[0] == pytest.approx(1.0 - 0.5**tau_ref, abs=1e-7)
    assert fine.X[0] == pytest.approx(0.5154, abs=1e-3)


def test_hodgson_gibbs_equations_worked_by_hand():
    """The set's equations at d0 = 100 um, eps = 0.3, edot = 10 1/s, worked by hand from the
    printed equations (shared notes, recrystallisation.md section 3; R = 8.314): a check of the
    transcription (no published table of these values was found)."""
    for TC, Z, t_srx, d_srx, t_md, d_md in ((1000, 2.036e13, 1.275, 56.29, 0.0678, 22.59),
                                            (950, 6.486e13, 3.101, 47.31, 0.0652, 17.31),
                                            (900, 2.280e14, 8.13, 39.18, 0.0625, 12.96)):
        T = TC + C
        z = float(HG.zener(10.0, T))
        assert z == pytest.approx(Z, rel=3e-3)       # R = 8.314 by hand: Z by 1e-3
        assert float(HG.srx_half_time(0.3, 100e-6, 10.0, T)) == pytest.approx(t_srx, rel=3e-3)
        assert float(HG.srx_grain_size(0.3, 100e-6, T)) * 1e6 == pytest.approx(d_srx, rel=1e-3)
        assert float(HG.mdrx_half_time(z, T)) == pytest.approx(t_md, rel=3e-3)
        assert float(HG.mdrx_grain_size(z)) * 1e6 == pytest.approx(d_md, rel=2e-3)
    z = float(HG.zener(10.0, 1000 + C))
    assert float(HG.critical_strain(100e-6, z)) == pytest.approx(0.408, abs=1e-3)


def test_grain_growth_follows_its_law_in_a_hold():
    """Isothermal hold at 1000 degC after full SRX: growth from the finish time t_f (X = 0.95)
    on, d^7 = d_rex^7 + K (t - t_f) exp(-Q/RT) exactly; from 30 um over 1, 5, 20 s (as if
    finished at 0) 35.98, 43.67, 52.81 um by hand."""
    T = 1000 + C
    for t, d in ((1.0, 35.98), (5.0, 43.67), (20.0, 52.81)):
        W = t * math.exp(-400e3 / (R * T))
        assert float(HG.grown(30e-6, W)) * 1e6 == pytest.approx(d, abs=0.02)
    t05 = 0.2
    times = np.linspace(0.0, 10.0, 501)
    res = hold(times, np.full((times.size, 1), T), lambda Ti, i: np.full(1, t05), 1.0,
               HG.growth.rate)
    t_f = t05 * math.log(0.05) / math.log(0.5)
    assert res.t_finished[0] == pytest.approx(t_f, rel=1e-12)
    assert res.W_after[0] == pytest.approx((10.0 - t_f) * math.exp(-400e3 / (R * T)),
                                           rel=1e-3, abs=0.0)     # W is about 3.5e-16 s


def _state(strain, T=1000 + C, d0=100e-6, rate=10.0, n=3):
    eta = np.linspace(0.0, 1.0, n)
    one = np.ones(n)
    return pass_state(HG, eta, strain * one, d0 * one, math.log(rate) * one, one / T, T * one)


def test_long_hot_transport_recrystallises_fully_and_short_cold_one_keeps_the_strain():
    """Limits: 60 s at 1050 degC after eps 0.3: X = 1, retained strain 0, the grain the grown
    d_srx. 1 ms at 900 degC: X below 1e-3, the strain kept (lambda = 1), the grain d0."""
    ps = _state(0.3, T=1050 + C)
    times = np.linspace(0.0, 60.0, 601)
    soft = soften(HG, ps, times, np.full((times.size, 3), 1050 + C))
    assert np.all(soft.fraction == 1.0) and np.all(soft.retained_strain == 0.0)
    assert np.all(soft.finished) and not np.any(soft.metadynamic)
    assert np.all(soft.grain > soft.rex_grain)
    cold = _state(0.3, T=900 + C)
    times = np.linspace(0.0, 1e-3, 11)
    soft = soften(HG, cold, times, np.full((times.size, 3), 900 + C))
    assert np.all(soft.fraction < 1e-3)
    assert np.allclose(soft.retained_strain, 0.3 * (1.0 - soft.fraction), rtol=1e-14)
    assert np.all(soft.retained_strain > 0.2997)
    assert np.allclose(soft.grain, soft.fraction ** (4 / 3) * soft.rex_grain +
                       (1.0 - soft.fraction) ** 2 * 100e-6, rtol=1e-14)


def test_partial_recrystallisation_mixes_the_grain_sizes():
    """X about 0.5 (an isothermal hold of t_0.5): the grain handed on is Beynon and Sellars'
    mix X^(4/3) d_srx + (1 - X)^2 d0, with d_srx at the hold's temperature; the retained strain
    (1 - X) eps; nothing finished, so no growth."""
    T = 1000 + C
    ps = _state(0.3, T=T)
    t05 = float(HG.srx_half_time(0.3, 100e-6, 10.0, T))
    times = np.linspace(0.0, t05, 11)
    soft = soften(HG, ps, times, np.full((times.size, 3), T))
    assert np.allclose(soft.fraction, 0.5, rtol=1e-12) and not np.any(soft.finished)
    d_srx = float(HG.srx_grain_size(0.3, 100e-6, T))
    assert d_srx * 1e6 == pytest.approx(56.29, rel=1e-3)
    assert np.allclose(soft.grain, 0.5 ** (4 / 3) * d_srx + 0.25 * 100e-6, rtol=1e-9)
    assert np.allclose(soft.retained_strain, 0.15, rtol=1e-12)


def test_mechanism_follows_the_critical_strain():
    """eps above eps_c(d0, Z): metadynamic (t_0.5 of Z and T, no strain dependence); below:
    static, t_0.5 proportional to eps^-2.5; lambda scales the retained strain."""
    z = float(HG.zener(10.0, 1000 + C))
    eps_c = float(HG.critical_strain(100e-6, z))
    times = np.linspace(0.0, 0.05, 11)
    T = np.full((times.size, 3), 1000 + C)
    above = soften(HG, _state(1.1 * eps_c), times, T)
    below = soften(HG, _state(0.9 * eps_c), times, T, retained_share=0.5)
    assert np.all(above.metadynamic) and not np.any(below.metadynamic)
    assert above.half_time[0] == pytest.approx(float(HG.mdrx_half_time(z, 1000 + C)))
    assert below.half_time[0] == pytest.approx(
        float(HG.srx_half_time(0.9 * eps_c, 100e-6, 10.0, 1000 + C)))
    assert np.allclose(below.retained_strain, 0.5 * (1 - below.fraction) * 0.9 * eps_c)


def test_bad_input_named():
    with pytest.raises(UnknownSet, match="unknown recrystallisation set 'nope'"):
        get_set("nope")
    assert sets_for("S355J2") == ["hodgson_gibbs_cmn"] and sets_for("Al99.5") == []
    ps = _state(0.3, T=1000 + C)
    times = np.linspace(0.0, 1.0, 3)
    cold = soften(HG, ps, times, np.full((3, 3), 1000.0))   # below 1073.15 K: extrapolated
    assert np.all(cold.extrapolated) and np.all(cold.coldest == 1000.0)
    assert not np.any(soften(HG, ps, times, np.full((3, 3), 1200.0)).extrapolated)
    with pytest.raises(KineticsRangeError, match=r"pass\[2\]\.transport: the cooling history "
                       r"must be finite"):
        soften(HG, ps, times, np.full((3, 3), np.nan), where="pass[2].transport")

    with pytest.raises(ValueError, match="times must increase"):
        hold(np.array([0.0, 0.0]), np.full((2, 1), 1300.0), lambda Ti, i: np.ones(1), 1.0)
