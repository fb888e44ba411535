"""A temperature field of order 2 (``TemperatureField(order=2)``: its SUPG residual has the
conduction term k tr(hesse T), which order 1 does not) meets the adiabatic plug flow's exit
rise worked out by hand in tests/fem/test_thermal.py, as order 1 does: heat / (rho c U H)
(measured 2.4e-4 below it on 24 x 4 elements; the inlet reaction is the gap, as for order 1)."""
from __future__ import annotations

import pytest

from hotroll.fem.thermal_field import TemperatureField
from tests.fem.test_thermal import RHO, STEEL, C, boundary, rectangle


def test_an_order_2_field_meets_the_adiabatic_exit_rise():
    from ngsolve import CF, IfPos, x, y

    H, L, U = 0.01, 0.06, 0.5
    mesh = rectangle(L, H, 24, 4)
    bc = boundary(1200.0, taylor_quinney=0.9, friction_heat_to_strip=0.4)
    q = 4e8 * IfPos(x - 0.02, IfPos(0.04 - x, 1.0, 0.0), 0.0) * (1.0 + y / H)  # W/m^3
    qf = 3e6 * (x / L)                                                        # W/m^2
    field = TemperatureField(mesh, STEEL, bc, top="top", order=2)
    field.solve_steady(CF((U, 0.0)), q, qf, 1.0)
    heat = 0.9 * 1.2e5 + 0.4 * 9e4                 # W/m, by hand (test_thermal.py)
    rise = heat / (RHO * C * U * H)                # 5.680 K
    measured = field.face_mean("out", CF((U, 0.0))) - 1200.0
    assert measured == pytest.approx(rise, rel=1e-3)
