"""The heat balance's relative error (TemperatureField.balance) is measured against the heat
gained when no heat leaves (an adiabatic pass: no roll contact, no air): on the adiabatic
plug flow of tests/fem/test_thermal.py the only imbalance is the inlet's reaction
``conducted_in`` (the docstring's closure), so the error is |conducted_in| / (plastic +
friction heat), the heat worked out by hand there (1.44e5 W/m)."""
from __future__ import annotations

import pytest

from hotroll.fem.thermal_field import TemperatureField
from tests.fem.test_thermal import STEEL, boundary, rectangle


def test_the_adiabatic_error_is_the_inlet_reaction_over_the_heat_gained():
    from ngsolve import CF, IfPos, x, y

    H, L, U = 0.01, 0.06, 0.5
    mesh = rectangle(L, H, 48, 8)
    bc = boundary(1200.0, taylor_quinney=0.9, friction_heat_to_strip=0.4)
    q = 4e8 * IfPos(x - 0.02, IfPos(0.04 - x, 1.0, 0.0), 0.0) * (1.0 + y / H)  # W/m^3
    qf = 3e6 * (x / L)                                                        # W/m^2
    field = TemperatureField(mesh, STEEL, bc, top="top")
    field.solve_steady(CF((U, 0.0)), q, qf, 1.0)
    b = field.balance(CF((U, 0.0)), q, qf, 1.0)
    heat = 0.9 * 1.2e5 + 0.4 * 9e4
    assert b["heat_to_roll"] == 0.0 and b["heat_to_air"] == 0.0
    assert b["plastic_heat"] + b["friction_heat_to_strip"] == pytest.approx(heat, rel=1e-9)
    assert b["heat_balance_error"] == pytest.approx(abs(b["conducted_in"]) / heat, rel=1e-6)
    assert b["heat_balance_error"] < 1e-3
