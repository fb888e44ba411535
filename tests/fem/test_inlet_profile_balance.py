"""The heat the flow carries in through the inlet (TemperatureField.balance's
``advected_in``) when the inlet's temperature is a profile (a schedule's pass after the
first: ``ThermalBoundary.entry_profile``) rather than the entry temperature the enthalpy is
measured from: int rho c (T(y) - T_entry) U dy, by hand for a linear profile 1200 -> 1250 K
over H = 10 mm at U = 0.5 m/s: rho c U 25 K H (no sources, insulated faces)."""
from __future__ import annotations

import pytest

from hotroll.fem.thermal_field import TemperatureField
from hotroll.model.profile import ThicknessProfile
from tests.fem.test_thermal import RHO, STEEL, C, boundary, rectangle


def test_the_heat_carried_in_through_a_profiled_inlet():
    from ngsolve import CF

    H, L, U = 0.01, 0.06, 0.5
    mesh = rectangle(L, H, 24, 8)
    bc = boundary(1200.0, entry_profile=ThicknessProfile((0.0, 1.0), (1200.0, 1250.0)))
    field = TemperatureField(mesh, STEEL, bc, top="top")
    v = CF((U, 0.0))
    field.solve_steady(v, 0.0, 0.0, 1.0)
    b = field.balance(v, 0.0, 0.0, 1.0)
    assert b["advected_in"] == pytest.approx(RHO * C * U * 25.0 * H, rel=1e-9)
