"""Interpass cooling (hotroll/model/interpass.py, issue 17) against closed forms: the slab
with a convective surface (the Fourier series of Carslaw and Jaeger 3.11, Heisler's charts),
radiation of a thin strip (lumped: T0 (1 + 3 eps sigma T0^3 t / (rho c H))^(-1/3)), the energy
balance with temperature tables, and bad input."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from hotroll.model.heat_transfer import SIGMA_SB
from hotroll.model.interpass import cool, enthalpy_mean
from hotroll.model.thermal_properties import ThermalInputError, ThermalProperties

pytestmark = pytest.mark.mutation
STEEL = ThermalProperties(7600.0, 650.0, 28.0)
ALPHA = 28.0 / (7600.0 * 650.0)


def slab_series(bi: float, fo: float, x: np.ndarray, terms: int = 60) -> np.ndarray:
    """(T - T_amb)/(T0 - T_amb) in a slab -H < y < H from a uniform T0, surface h (T - T_amb):
    sum C_n exp(-z_n^2 Fo) cos(z_n y/H), z_n tan z_n = Bi, C_n = 4 sin z_n/(2 z_n + sin 2 z_n)."""
    out = np.zeros_like(x, dtype=float)
    for i in range(terms):
        lo, hi = i * math.pi + 1e-12, i * math.pi + math.pi / 2 - 1e-12
        z = brentq(lambda z: z * math.tan(z) - bi, lo, hi)
        c = 4.0 * math.sin(z) / (2.0 * z + math.sin(2.0 * z))
        out += c * math.exp(-z * z * fo) * np.cos(z * x)
    return out


@pytest.mark.parametrize("bi,fo", [(1.0, 0.2), (1.0, 0.8), (10.0, 0.3)])
def test_convective_slab_against_the_series(bi, fo):
    """Bi = h H / k and Fo = alpha t / H^2: the profile within 2e-3 of the drop on 80
    intervals and 800 steps, and the error halves (first order in time) when both double."""
    H, T0, Ta = 0.1, 1373.15, 300.0
    h, t = bi * 28.0 / H, fo * H * H / ALPHA
    errors = []
    for n, steps in ((40, 400), (80, 800)):
        r = cool([0.0], [T0], H, t, STEEL, h, 0.0, Ta, intervals=n, steps=steps)
        exact = Ta + (T0 - Ta) * slab_series(bi, fo, r.y / H)
        errors.append(np.max(np.abs(r.temperature - exact)) / (T0 - Ta))
    assert errors[1] < 2e-3
    assert errors[0] / errors[1] > 1.7
    assert r.balance_error < 1e-9


def test_thin_strip_radiation_is_the_lumped_closed_form():
    """Radiation only, to 0 K, 4 mm half thickness, 10 s (a 55 K drop). With k x 1000 (Bi ~
    5e-5) the mean is the lumped law T0 (1 + 3 eps sigma T0^3 t / (rho c H))^(-1/3) to 0.02 K.
    With steel's k (Bi = 4 eps sigma T^3 H / k ~ 0.05) the surface runs ~ q H / 3k = 5.7 K
    below the mean and radiates less: the mean ends 0-2 K above the lumped value, the
    mid-plane warmer than the mean and the surface cooler."""
    H, T0, eps, t = 0.004, 1273.15, 0.8, 10.0
    lumped = T0 * (1.0 + 3.0 * eps * SIGMA_SB * T0 ** 3 * t / (7600.0 * 650.0 * H)) ** (-1 / 3)
    assert T0 - lumped > 50.0
    conducting = ThermalProperties(7600.0, 650.0, 28.0e3)
    r = cool([0.0, 1.0], [T0, T0], H, t, conducting, 0.0, eps, 1e-9, intervals=20, steps=800)
    assert r.mean == pytest.approx(lumped, abs=0.02)
    assert r.heat_lost == pytest.approx(7600.0 * 650.0 * H * (T0 - r.mean), rel=1e-9)
    r = cool([0.0, 1.0], [T0, T0], H, t, STEEL, 0.0, eps, 1e-9, intervals=20, steps=800)
    assert 0.0 < r.mean - lumped < 2.0
    assert r.surface < r.mean < r.temperature[0]
    assert r.mean - r.surface == pytest.approx(eps * SIGMA_SB * r.surface ** 4 * H / (3 * 28.0),
                                               rel=0.1)


def test_energy_balance_with_tables_and_a_profile():
    """Tables in T for rho, c and k, a hot core and a chilled surface: the enthalpy lost equals
    the heat through the surface (1e-9), and the enthalpy mean lies between the extremes."""
    props = ThermalProperties(((800.0, 7700.0), (1400.0, 7500.0)), ((800.0, 600.0),
                              (1400.0, 700.0)), ((800.0, 25.0), (1400.0, 31.0)))
    y = np.linspace(0.0, 0.02, 11)
    T = 1300.0 - 300.0 * (y / 0.02) ** 4
    r = cool(y, T, 0.02, 6.0, props, 20.0, 0.8, 293.15)
    assert r.balance_error < 1e-9
    assert r.heat_lost > 0.0
    assert r.temperature.min() < r.mean < r.temperature.max()
    # the surface warms first (conduction from the core beats the losses at 1000 K)
    assert r.surface > 1000.0


def test_no_losses_keep_the_profile_mean():
    """h = 0 and eps = 0: no heat leaves; the profile flattens towards its enthalpy mean."""
    y = np.linspace(0.0, 0.01, 6)
    T = np.array([1300.0, 1290.0, 1270.0, 1240.0, 1200.0, 1150.0])
    r = cool(y, T, 0.01, 30.0, STEEL, 0.0, 0.0, 300.0)
    w = np.full(41, 0.01 / 40)
    w[[0, -1]] *= 0.5
    start = enthalpy_mean(STEEL, np.interp(np.linspace(0, 0.01, 41), y, T), w)
    assert r.mean == pytest.approx(start, rel=1e-9)
    assert np.ptp(r.temperature) < 1.0 and r.heat_lost == 0.0


@pytest.mark.parametrize("kw,field", [({"half_thickness": 0.0}, "half_thickness"),
                                      ({"duration": -1.0}, "duration"),
                                      ({"htc": -5.0}, "htc_air"),
                                      ({"emissivity": 1.5}, "emissivity"),
                                      ({"ambient": 0.0}, "ambient_temperature")])
def test_bad_input_names_the_field(kw, field):
    args = dict(half_thickness=0.004, duration=1.0, htc=20.0, emissivity=0.8, ambient=293.15)
    args.update(kw)
    with pytest.raises(ThermalInputError, match=field):
        cool([0.0], [1273.15], props=STEEL, **args)
    with pytest.raises(ThermalInputError, match=r"transport profile: y \(m\) and T \(K\) must be "
                                                r"equal-length arrays"):
        cool([0.0, 1.0], [1273.15], 0.004, 1.0, STEEL, 20.0, 0.8, 293.15)


def test_no_time_no_change():
    """A transport of 0 s hands the profile on (interpolated onto the nodes): the surface is
    its last value, the mean its enthalpy mean, nothing lost."""
    y = np.linspace(0.0, 0.01, 6)
    T = np.array([1300.0, 1290.0, 1270.0, 1240.0, 1200.0, 1150.0])
    r = cool(y, T, 0.01, 0.0, STEEL, 50.0, 0.8, 300.0)
    assert r.surface == 1150.0 and r.heat_lost == 0.0
    assert np.allclose(r.temperature, np.interp(r.y, y, T), rtol=0, atol=1e-12)


def _reference_cool(y, T, H, duration, props, htc, eps, ambient, n=40):
    """The implicit steps as first written: scipy.linalg.solve_banded on the full band, H(T)
    evaluated in every Newton iteration."""
    from scipy.linalg import solve_banded

    from hotroll.model.heat_transfer import ConvectionRadiation
    surface = ConvectionRadiation(htc, eps)
    dy = H / n
    temp = np.interp(np.linspace(0.0, H, n + 1), y * (H / y[-1]), T)
    w = np.full(n + 1, dy)
    w[0] = w[-1] = 0.5 * dy
    alpha = float(np.max(props.k_values(temp) / props.rho_c_values(temp)))
    steps = max(100, math.ceil(duration / (0.1 * H * H / alpha)))
    dt = duration / steps
    for _ in range(steps):
        old_H = props.enthalpy_values(temp)
        new = temp.copy()
        for _ in range(50):
            k = props.k_values(new)
            kf = 0.5 * (k[1:] + k[:-1]) / dy
            flux = kf * (new[1:] - new[:-1])
            res = w * (props.enthalpy_values(new) - old_H) / dt
            res[:-1] -= flux
            res[1:] += flux
            res[-1] += surface.flux(new[-1], ambient)
            diag = w * props.rho_c_values(new) / dt
            diag[:-1] += kf
            diag[1:] += kf
            diag[-1] += surface.dflux(new[-1], ambient)
            band = np.zeros((3, n + 1))
            band[0, 1:], band[1], band[2, :-1] = -kf, diag, -kf
            d = solve_banded((1, 1), band, -res)
            new += d
            if np.max(np.abs(d)) <= 1e-11 * np.max(new):
                break
        temp = new
    return temp


def test_the_steps_are_the_banded_solves_bit_for_bit():
    """The direct LAPACK gtsv (what solve_banded((1, 1), ...) calls) and H(T) reused in a
    step's first iteration change no bit of the result (a speed-up, not a new scheme)."""
    props = ThermalProperties(((800.0, 7700.0), (1400.0, 7500.0)), ((800.0, 600.0),
                              (1400.0, 700.0)), ((800.0, 25.0), (1400.0, 31.0)))
    y = np.linspace(0.0, 1.0, 9)
    T = 1320.0 - 90.0 * y ** 3
    r = cool(y, T, 0.004, 3.0, props, 20.0, 0.8, 293.15)
    assert np.array_equal(r.temperature, _reference_cool(y, T, 0.004, 3.0, props, 20.0, 0.8,
                                                         293.15))
