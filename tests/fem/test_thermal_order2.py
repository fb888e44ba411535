"""A temperature field of order 2 (``TemperatureField(order=2)``: its SUPG residual has the
conduction term k tr(hesse T), which order 1 does not) meets the adiabatic plug flow's exit
rise worked out by hand in tests/fem/test_thermal.py, as order 1 does: heat / (rho c U H)
(measured 2.4e-4 below it on 24 x 4 elements; the inlet reaction is the gap, as for order 1)."""
from __future__ import annotations

import pytest

from tests.fem.test_thermal import RHO, C, adiabatic_plug


def test_an_order_2_field_meets_the_adiabatic_exit_rise():
    from ngsolve import CF

    field, q, qf, U, H = adiabatic_plug(24, 4, order=2)
    heat = 0.9 * 1.2e5 + 0.4 * 9e4                 # W/m, by hand (test_thermal.py)
    rise = heat / (RHO * C * U * H)                # 5.680 K
    measured = field.face_mean("out", CF((U, 0.0))) - 1200.0
    assert measured == pytest.approx(rise, rel=1e-3)
