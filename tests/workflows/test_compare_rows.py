"""The comparison's table without an FE run (workflows/compare.py): the FE figures read from
a summary (its roll power), a summary without a forward slip (a run that has none: the row's
FE cell is empty, not a failure), and the Tresca note's words, on the small pass of
tests/workflows/test_compare.py (R 0.3 m, 100 -> 80 mm)."""
from __future__ import annotations

from hotroll.config.case import case_from_dict
from hotroll.workflows.compare import build_table, fe_quantities, map_case, slab_friction

CASE = {"name": "thin_tresca",
        "pass": {"roll_radius": 0.3, "entry_thickness": 0.1, "exit_thickness": 0.08,
                 "roll_angular_velocity": 1.0},
        "plate": {"length": 0.5}, "material": {"K": 1e8, "m": 0.15},
        "friction": {"law": "tresca", "factor": 0.7}, "mesh": {"h_contact": "auto"},
        "solver": {"method": "steady", "threads": 1}, "output": {"figures": False, "vtk": False}}


def test_the_fe_figures_are_the_summarys():
    s = {"roll_force": 2.2e6, "roll_torque": 5.5e4, "roll_power": 1.1e5, "neutral_angle": 0.06,
         "forward_slip": 0.05, "contact_length": 0.11}
    q = fe_quantities(s, None, 0.01)
    assert (q["roll_force"], q["roll_torque"], q["roll_power"], q["neutral_angle"],
            q["forward_slip"], q["contact_arc_length"]) == (2.2e6, 5.5e4, 1.1e5, 0.06, 0.05, 0.11)


def test_a_summary_without_forward_slip_leaves_its_cell_empty():
    case = case_from_dict(CASE)
    fe = fe_quantities({"roll_force": 2e6, "forward_slip": None}, None, 0.01)
    th = {"inputs": map_case(case), "slab": None, "sims": None, "ford_alexander": None,
          "mean_flow_stress": 9e7}
    rows = {r["quantity"]: r for r in build_table(case, fe, th)}
    assert rows["forward slip [%]"]["FE"] is None
    assert rows["roll force per unit width [MN/m]"]["FE"] == 2.0


def test_the_tresca_note_names_the_factor_and_the_fe():
    law, note = slab_friction(case_from_dict(CASE))
    assert law.factor == 0.7
    assert note == "tresca factor = 0.7 (tau = factor k, as the FE)"
