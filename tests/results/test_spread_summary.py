"""The 3D pass's record to summary keys and outcome (results/spread_summary.py,
model/spread_result.py), without FE: a record made by hand."""
from __future__ import annotations

import numpy as np
import pytest

from hotroll.config.case import load_case
from hotroll.model.spread_result import SpreadResult
from hotroll.results.outcome import conservation_problem, exit_code
from hotroll.results.spread_summary import (
    formula_warning,
    spread_figures,
    unsettled,
    zone_warning,
)

CASE = {"pass.roll_radius": 0.25, "pass.entry_thickness": 0.01, "pass.exit_thickness": 0.008,
        "pass.roll_angular_velocity": 4.0, "mesh.h_contact": 1e-3, "solver.method": "steady",
        "plate.length": 0.2, "pass.width": 0.01, "spread.max_rounds": 7}


def record(**kw) -> SpreadResult:
    base = dict(stock_width=0.01, exit_width=0.0112,
                exit_section={"y": np.array([0.001, 0.003]), "half_width": np.array([0.0057, 0.0055])},
                exit_thickness={"z": np.array([0.0, 0.005]), "thickness": np.array([0.008, 0.0079])},
                width_along={"x": np.zeros(2), "centre": np.zeros(2), "surface": np.zeros(2)},
                contact_map={}, roll_force=8.0e4, roll_torque=900.0, roll_power=3600.0,
                flux_in=2.0e-4, flux_out=1.99e-4, flux_edge=0.5e-6, midplane={
                    "midplane_pressure_rms_deviation": 0.1,
                    "midplane_contact_pressure_rms_deviation": 0.02,
                    "midplane_contact_pressure_l2_deviation": 0.015,
                    "midplane_stress_l2_deviation": 0.08,
                    "midplane_bite_stress_l2_deviation": 0.01}, power_balance_error=1e-4,
                settled=True, rounds=3, newton_iterations=17, dofs=18000, layers=2,
                edge_layer=0.0025, wall_time=9.0)
    return SpreadResult(**{**base, **kw})


def test_the_records_figures_by_hand():
    """[hand] spread = exit - stock width; the edge bulge the section's largest minus smallest
    half width; the mass flux error (out + edge - in) / in; the summary's whole-width force,
    torque and power the 3D pass's, plane strain x width beside them, the mill both rolls'."""
    case = load_case("hotroll/examples/cases/example1.toml", CASE)
    r = record()
    assert r.spread == pytest.approx(0.0012, rel=1e-12)
    assert r.edge_bulge == pytest.approx(0.0002, rel=1e-9)
    assert r.edge_drop == pytest.approx(0.0001, rel=1e-9)
    assert r.mass_flux_error == pytest.approx((1.99e-4 + 0.5e-6 - 2.0e-4) / 2.0e-4, rel=1e-12)
    s = spread_figures(case, r, roll_force=9.0e6)
    assert s["roll_force_total"] == 8.0e4 and s["roll_torque_total"] == 900.0
    assert s["plane_strain_roll_force_total"] == pytest.approx(9.0e4, rel=1e-12)
    assert s["mill_power"] == 7200.0 and s["spread"] == r.spread
    assert unsettled(r, 7) is None


def test_an_unsettled_or_leaking_3d_pass_is_not_an_answer():
    """[plumb] an unsettled 3D pass: its reason names spread.max_rounds and the exit code is 5
    (not settled) even where the plane-strain pass converged; a 3D mass flux error of 5 % is
    not conserved (exit code 7)."""
    r = record(settled=False, rounds=7)
    why = unsettled(r, 7)
    assert "did not settle in 7 rounds (spread.max_rounds = 7)" in why
    assert exit_code({"converged": False, "status": "steady", "spread_settled": False,
                      "roll_force": 1.0, "roll_torque": 1.0}) == 5
    # a plane-strain pass that skids keeps its own code (6), whatever its 3D pass did
    assert exit_code({"converged": False, "status": "steady", "spread_settled": False,
                      "outlet_driven": True, "roll_force": 1.0, "roll_torque": 1.0}) == 6
    failed = record(settled=False, rounds=2, failure="a linear solve failed: singular")
    assert unsettled(failed, 7) == ("not settled: the 3D pass across the width stopped after "
                                    "2 rounds: a linear solve failed: singular")
    leak = conservation_problem({"spread_mass_flux_error": 0.05, "contact_method": "multiplier"})
    assert "spread_mass_flux_error = 0.05 above 0.02" in leak
    assert exit_code({"converged": False, "not_conserved": True}) == 7
    assert conservation_problem({"spread_power_balance_error": 0.03,
                                 "contact_method": "multiplier"}) is not None
    assert conservation_problem({"spread_mass_flux_error": 0.01,
                                 "spread_power_balance_error": 0.01,
                                 "contact_method": "multiplier"}) is None


def test_an_edge_zone_is_always_warned_about_and_its_cut_named():
    """[plumb] an edge zone (a cut inside the half width) always warns, naming
    spread.edge_zone, the cut in m and what to do; a whole half width (no cut): none."""
    assert zone_warning(record()) is None
    text = zone_warning(record(zone_cut=0.002))
    assert text.startswith("spread.edge_zone: the interior inside the cut (0.002 m from "
                           "mid-width) is one layer in generalized plane strain")
    assert text.endswith("widen the zone and compare (a study over spread.edge_zone: the "
                         "bundled study edge_zone)")


def test_the_formulas_beside_a_pass_with_tension_are_warned_about():
    """[plumb] Hill's, Sparling's and Wusatowski's spreads have no tension term: with back or
    front tension a warning names them and the tensions in MPa; without, none."""
    assert formula_warning(0.0, 0.0) is None
    text = formula_warning(1e7, 0.0)
    assert text.startswith("spread_hill, spread_sparling, spread_wusatowski: the formulas have "
                           "no tension term; with back and front tension 10 and 0 MPa")
    assert "0 and 20 MPa" in formula_warning(0.0, 2e7)


def test_a_plates_exit_section_is_drawn_at_its_edge(tmp_path, monkeypatch):
    """[hand] fig_spread's exit section: a strip 400 x 32 mm (half width 200 mm over WIDE = 4
    thicknesses) is drawn from 3 thicknesses inside its stock edge, 104 mm, to half a
    thickness past its widest point, 216.5 mm, titled "(the edge)"; one 4.2 thicknesses wide
    (half) at its edge too; a bar 40 mm wide whole."""
    import json

    import hotroll.results.figures.spread as mod
    from hotroll.results.figures import RunFiles
    from hotroll.results.output import write_csv

    drawn = {}
    monkeypatch.setattr(mod, "save_figure", lambda fig, path: drawn.setdefault("fig", fig))
    y = (np.arange(8) + 0.5) * 0.002     # the outlet's midpoints, as written: 16 mm half
    for width, half in ((0.4, 0.2005), (0.2688, 0.1349), (0.04, 0.0205)):
        out = tmp_path / str(width)
        out.mkdir()
        (out / "summary.json").write_text(json.dumps({"width": width, "case_name": "x"}))
        write_csv(out / "exit_section.csv", {"y": y, "half_width": np.full(y.size, half)})
        drawn.clear()
        mod.fig_spread(RunFiles(out), out / "f.png")
        ax = drawn["fig"].axes[0]
        if width == 0.4:
            assert ax.get_xlim() == pytest.approx((104.0, 216.5), rel=1e-12)
            assert ax.get_title().endswith("(the edge)")
        elif width > 0.2:
            assert ax.get_title().endswith("(the edge)")
        else:
            assert ax.get_xlim()[0] < -20.5 and not ax.get_title().endswith("(the edge)")
