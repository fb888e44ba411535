"""Interpass cooling with a surface law whose slope depends on the surroundings (a law a
plugin may add: model/heat_transfer/registry.py): natural convection q = h (T - T_a)^(5/4),
dq/dT = (5/4) h (T - T_a)^(1/4). A thin, very conductive strip (k x 1000: lumped) cools as the
closed form of rho c H dT/dt = -q: (T - T_a)^(-1/4) = (T0 - T_a)^(-1/4) + h t / (4 rho c H)."""
from __future__ import annotations

import pytest

from hotroll.model.heat_transfer.base import HeatTransferLaw
from hotroll.model.interpass import cool
from hotroll.model.thermal_properties import ThermalProperties


class NaturalConvection(HeatTransferLaw):
    name, kind = "natural_convection", "surface"

    def __init__(self, h: float):
        self.h = h

    def flux(self, T, T_env):
        return self.h * (T - T_env) ** 1.25

    def dflux(self, T, T_env):
        return 1.25 * self.h * (T - T_env) ** 0.25


def test_a_law_with_the_surroundings_in_its_slope_cools_as_the_closed_form():
    H, T0, Ta, h, t = 0.004, 1273.15, 300.0, 10.0, 60.0
    rho_c = 7600.0 * 650.0
    props = ThermalProperties(7600.0, 650.0, 28.0e3)
    r = cool([0.0], [T0], H, t, props, None, None, Ta, intervals=10, steps=600,
             surface=NaturalConvection(h))
    lumped = Ta + ((T0 - Ta) ** -0.25 + h * t / (4.0 * rho_c * H)) ** -4.0
    assert T0 - lumped > 100.0                         # a real cooling: 149 K
    assert r.mean == pytest.approx(lumped, abs=0.05)   # measured 0.024 K (600 implicit steps)
