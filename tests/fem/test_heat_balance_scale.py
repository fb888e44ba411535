"""The heat balance's relative error (TemperatureField.balance) is measured against the heat
gained when no heat leaves (an adiabatic pass: no roll contact, no air): on the adiabatic
plug flow of tests/fem/test_thermal.py the only imbalance is the inlet's reaction
``conducted_in`` (the docstring's closure), so the error is |conducted_in| / (plastic +
friction heat), the heat worked out by hand there (1.44e5 W/m)."""
from __future__ import annotations

import pytest

from tests.fem.test_thermal import adiabatic_plug


def test_the_adiabatic_error_is_the_inlet_reaction_over_the_heat_gained():
    from ngsolve import CF

    field, q, qf, U, _ = adiabatic_plug()
    b = field.balance(CF((U, 0.0)), q, qf, 1.0)
    heat = 0.9 * 1.2e5 + 0.4 * 9e4
    assert b["heat_to_roll"] == 0.0 and b["heat_to_air"] == 0.0
    assert b["plastic_heat"] + b["friction_heat_to_strip"] == pytest.approx(heat, rel=1e-9)
    assert b["heat_balance_error"] == pytest.approx(abs(b["conducted_in"]) / heat, rel=1e-6)
    assert b["heat_balance_error"] < 1e-3
