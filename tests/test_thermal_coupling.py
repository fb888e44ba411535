"""The coupled steady pass (issue 16, in progress): the thermal figures of summary.json against
independent numbers. The case is scripts/cases/thermal_pass.toml (R = 0.3 m, 100 -> 80 mm,
Hensel-Spittel with a temperature term, rho c = 7600 x 650 J/(m^3 K)), auto mesh."""
from __future__ import annotations

from pathlib import Path

import pytest

from hotroll.app.config import load_case
from hotroll.app.runner import run_case

CASE = Path(__file__).resolve().parent.parent / "scripts" / "cases" / "thermal_pass.toml"
RHO_C = 7600.0 * 650.0
T_ENTRY = 1373.15


@pytest.fixture(scope="module")
def adiabatic(tmp_path_factory):
    """No heat transfer to the roll or the air, Coulomb mu = 0.3 (friction heat too)."""
    case = load_case(CASE).with_overrides(**{
        "thermal.htc_contact": 0.0, "thermal.htc_air": 0.0, "thermal.emissivity": 0.0,
        "friction.law": "coulomb", "friction.mu": 0.3, "friction.a_f": None})
    return run_case(case, tmp_path_factory.mktemp("adiabatic"))


def test_adiabatic_exit_temperature_rise(adiabatic):
    """Adiabatic limit: the mixing-cup exit temperature rises by (beta x plastic power +
    f_s x friction power) / (rho c Q), Q the exit flux (measured 0.05 % apart; the issue's
    bound is 1 %). The heat sources are the mechanics' powers: plastic heat = 0.9 x plastic
    power (measured 0.05 % apart: the quadrature), friction heat = 0.5 x friction power
    (measured 2.3 %: k projected onto P1 for the heat flux)."""
    s = adiabatic
    rise = (s["plastic_heat"] + s["friction_heat_to_strip"]) / (RHO_C * s["mass_flux_out"])
    assert s["exit_temperature_mean"] - T_ENTRY == pytest.approx(rise, rel=5e-3)
    assert s["plastic_heat"] == pytest.approx(0.9 * s["plastic_power"], rel=3e-3)
    assert s["friction_heat_to_strip"] == pytest.approx(0.5 * s["friction_power"], rel=0.06)
    assert s["heat_to_roll"] == 0.0 and s["heat_to_air"] == 0.0


def test_heat_balance_and_roll_chill(tmp_path_factory):
    """With a cold roll (20 kW/(m^2 K), 350 K), air and radiation: enthalpy out - in = plastic
    + friction heat - heat to the roll - heat to the air + the inlet's conduction, recomputed
    from the summary's terms (measured 1.9e-6 of the heat to the roll). The roll chills the
    strip: exit mean below the entry temperature, the exit surface below the mean, and the
    colder strip needs more force than the isothermal pass at the entry temperature (measured
    +3.7 %, Hensel-Spittel m1 = -0.0025 1/degC)."""
    case = load_case(CASE)
    s = run_case(case, tmp_path_factory.mktemp("chill"))
    gap = (s["advected_out"] - s["advected_in"] - s["conducted_in"]
           - (s["plastic_heat"] + s["friction_heat_to_strip"] - s["heat_to_roll"]
              - s["heat_to_air"]))
    assert abs(gap) < 1e-4 * s["heat_to_roll"]
    # the reported error is that identity without the inlet's conduction, over the larger of
    # the heat gained and the heat lost
    gain = s["plastic_heat"] + s["friction_heat_to_strip"]
    lost = s["heat_to_roll"] + s["heat_to_air"]
    assert s["heat_balance_error"] == pytest.approx(
        abs(s["advected_out"] - s["advected_in"] - (gain - lost)) / max(gain, lost), rel=1e-6)
    assert s["heat_balance_error"] < 1e-3
    assert s["exit_temperature_surface"] < s["exit_temperature_mean"] < T_ENTRY
    iso = run_case(case.with_overrides(thermal=None), tmp_path_factory.mktemp("iso"))
    assert s["roll_force"] > 1.02 * iso["roll_force"]
