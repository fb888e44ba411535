"""Interpass cooling across the width (hotroll/model/interpass_section.py, issue 53) and the
cross-section field it works on (hotroll/model/section.py).

Labels: [exact] a closed form the discretisation must approach (the product of two slabs'
Fourier series: with constant properties and a linear surface law the rectangle's
(T - T_a)/(T0 - T_a) is the product of the two slabs', Carslaw and Jaeger 6.3) or hold
exactly (a bilinear field); [identity] the energy balance of the scheme; [limit] a strip far
wider than the heat's reach is the 1D model at mid-width."""
from __future__ import annotations

import numpy as np
import pytest
from test_interpass import ALPHA, STEEL, slab_series  # the same directory

from hotroll.model.heat_transfer import ConvectionRadiation
from hotroll.model.interpass import cool
from hotroll.model.interpass_section import cool_section, width_nodes
from hotroll.model.profile import ProfileError
from hotroll.model.section import SectionProfile
from hotroll.model.thermal_properties import ThermalInputError, ThermalProperties

T0, TA = 1373.15, 300.0


def uniform(T: float) -> SectionProfile:
    return SectionProfile((0.0, 1.0), (0.0, 1.0), ((T, T), (T, T)))


def test_a_rectangle_cools_as_the_product_of_two_slabs():
    """[exact] H = 20 mm, B = 30 mm, h = 700 W/(m^2 K) (Bi 0.5 through the thickness, 0.75
    across), Fo = 0.5 on H: the section within 1e-3 of the drop of the product of the slabs'
    series (measured 3.6e-4 on 40 intervals), and the error falls by more than 1.7 when the
    steps and the thickness intervals double (first order in time)."""
    H, B, k = 0.02, 0.03, 28.0
    h = 0.5 * k / H
    t = 0.5 * H * H / ALPHA
    errors = []
    for n, steps in ((20, 100), (40, 200)):
        r = cool_section(uniform(T0), H, B, t, STEEL, ConvectionRadiation(h, 0.0), TA,
                         intervals=n, steps=steps)
        eta, zeta = np.asarray(r.section.eta), np.asarray(r.section.zeta)
        exact = TA + (T0 - TA) * np.outer(slab_series(h * H / k, t * ALPHA / H**2, eta),
                                          slab_series(h * B / k, t * ALPHA / B**2, zeta))
        errors.append(np.max(np.abs(r.section.array - exact)) / (T0 - TA))
        assert r.balance_error < 1e-9
    assert errors[1] < 1e-3
    assert errors[0] / errors[1] > 1.7


def test_a_wide_strip_is_the_1d_model_at_mid_width():
    """[limit] B = 1 m against H = 4 mm, 8 s in air (convection and radiation): the heat
    from the edge reaches ~10 mm, so the mid-width column is the 1D model's on the same
    thickness grid and steps to 1e-9 K/K, and the edge is colder than mid-width."""
    H, B, t = 0.004, 1.0, 8.0
    law = ConvectionRadiation(20.0, 0.8)
    r = cool_section(uniform(T0), H, B, t, STEEL, law, TA, intervals=20, steps=100)
    one = cool([0.0], [T0], H, t, STEEL, None, None, TA, intervals=20, steps=100, surface=law)
    v = r.section.array
    assert np.max(np.abs(v[:, 0] - one.temperature)) <= 1e-9 * T0
    assert np.all(v[:, -1] < v[:, 0] - 1.0)


def test_the_heat_lost_is_the_enthalpy_given_up_with_tables_and_radiation():
    """[identity] the enthalpy change over the section equals the heat lost through the top
    and the edge to 1e-9, with temperature tables, radiation and a profile to start from."""
    props = ThermalProperties(7800.0, ((900.0, 600.0), (1400.0, 700.0)),
                              ((900.0, 25.0), (1400.0, 32.0)))
    start = SectionProfile((0.0, 0.5, 1.0), (0.0, 1.0),
                           ((1400.0, 1350.0), (1390.0, 1340.0), (1350.0, 1300.0)))
    r = cool_section(start, 0.01, 0.02, 5.0, props, ConvectionRadiation(30.0, 0.85), TA)
    assert r.heat_lost > 0.0 and r.balance_error < 1e-9
    assert r.mean < 1390.0


def test_the_width_grid_is_fine_at_the_edge_and_ends_at_both_planes():
    """[hand] the first interval at the edge as asked, growing x1.2, at most B/40, ending
    exactly at 0 and B."""
    z = width_nodes(0.8, 0.001)
    d = np.diff(z)[::-1]                        # from the edge inwards
    assert z[0] == 0.0 and z[-1] == 0.8
    assert d[0] == pytest.approx(0.001) and d[1] == pytest.approx(0.0012)
    assert np.max(d) <= 0.8 / 40 * 1.5 and np.all(d > 0)


def test_a_bilinear_field_is_held_exactly():
    """[exact] values a + b eta + c zeta + d eta zeta on any tensor grid: reproduced at any
    point; mid-width's profile and the offset across the width by hand."""
    eta, zeta = (0.0, 0.3, 1.0), (0.0, 0.6, 0.9, 1.0)
    f = lambda e, z: 1000.0 + 20.0 * e - 50.0 * z + 7.0 * e * z    # noqa: E731
    s = SectionProfile(eta, zeta, tuple(tuple(f(e, z) for z in zeta) for e in eta))
    e, z = np.random.default_rng(1).random((2, 50))
    assert np.max(np.abs(s(e, z) - f(e, z))) <= 1e-9
    assert s.mid_width()(e) == pytest.approx(f(e, 0.0))
    assert s.offset(e, z) == pytest.approx(-50.0 * z + 7.0 * e * z)
    assert SectionProfile.from_dict(s.to_dict()) == s
    assert not s.is_uniform_across() and uniform(T0).is_uniform_across()


@pytest.mark.parametrize("bad", [dict(eta=(0.0, 0.5)), dict(zeta=(0.1, 1.0)),
                                 dict(values=((1.0, 1.0),))])
def test_a_malformed_section_is_refused(bad):
    args = dict(eta=(0.0, 1.0), zeta=(0.0, 1.0), values=((1.0, 1.0), (1.0, 1.0))) | bad
    with pytest.raises(ProfileError):
        SectionProfile(**args)


def test_bad_transport_input_names_the_field():
    with pytest.raises(ThermalInputError, match="half_width"):
        cool_section(uniform(T0), 0.01, 0.0, 1.0, STEEL, ConvectionRadiation(20.0, 0.8), TA)


def test_no_time_no_change():
    """[exact] a transport of 0 s hands the section on as it is, nothing lost."""
    start = SectionProfile((0.0, 1.0), (0.0, 1.0), ((1300.0, 1250.0), (1280.0, 1200.0)))
    r = cool_section(start, 0.005, 0.005, 0.0, STEEL, ConvectionRadiation(20.0, 0.8), TA)
    assert r.section == start and r.heat_lost == 0.0
