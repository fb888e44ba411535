"""The half strip's symmetry line holds v_y = 0 exactly (fem/forms.py ``fix_dirichlet``):
Newton keeps Dirichlet DOFs at their start, and the start is an element-wise projection of the
kinematic guess, whose error (2e-4 U on Case R) stayed there before; the half strip then
differed from the full strip with two equal rolls by 6e-5 in force on the same shape."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from hotroll.config.case import load_case
from hotroll.solvers.steady import SteadyRun
from hotroll.workflows.build import build_model, steady_settings


def test_the_symmetry_line_holds_v_y_zero_exactly():
    case = load_case("hotroll/examples/cases/example1.toml",
                     {"pass.roll_radius": 0.25, "pass.entry_thickness": 0.01,
                      "pass.exit_thickness": 0.008, "pass.roll_angular_velocity": 4.0,
                      "material.m": 0.05, "friction.law": "tresca", "friction.factor": 0.3,
                      "friction.a_f": None, "mesh.h_contact": 1e-3, "solver.method": "steady",
                      "plate.length": 0.2})
    problem, _ = build_model(case)
    run = SteadyRun(problem, replace(steady_settings(case), max_outer=0), case.plate.length)
    run._cold_start()
    nl = run.form.nonlinear
    fixed = ~nl.free_mask[: nl.n_velocity_dofs()]
    assert fixed.sum() > 10
    assert np.all(nl.gf.vec.FV().NumPy()[: nl.n_velocity_dofs()][fixed] == 0.0)
    run.run()
    assert np.all(nl.gf.vec.FV().NumPy()[: nl.n_velocity_dofs()][fixed] == 0.0)
