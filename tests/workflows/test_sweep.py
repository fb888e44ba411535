"""A sweep keeps one steady run per mesh and solves each case from its nearest solved
neighbour (``workflows/sweep.py``): each case must still be solved with its own settings."""
from __future__ import annotations

import pytest
from casebuild import example1_coarse

from hotroll.config.case import case_from_dict
from hotroll.workflows.runner import run_case
from hotroll.workflows.sweep import Sweep


def test_a_kept_run_takes_each_cases_friction_rule(tmp_path):
    """Example 1 (coarse) with a_f = 5, then with a_f estimated by (3.15), through one sweep:
    the second case estimates a_f (about 1e4 here: the arc sticks) as a cold run of it does
    (a run kept from the first case once went on with a_f = 5's couplings: caught by the
    before/after comparison of the bundled a_f study, docs/validation/recut.md). [self] warm
    against cold, to the coupling tolerance (a_f settles to 1 %)."""
    fixed = case_from_dict(example1_coarse("af5", friction={"law": "viscoplastic", "a_f": 5.0}))
    estimated = case_from_dict(example1_coarse("est"))
    sweep = Sweep()
    first = run_case(fixed, tmp_path / "af5", sweep=sweep)
    warm = run_case(estimated, tmp_path / "est", sweep=sweep)
    cold = run_case(estimated, tmp_path / "cold")
    assert first["a_f"] == 5.0 and warm["exit_code"] == 0 and cold["exit_code"] == 0
    assert cold["a_f"] > 1e3
    assert warm["a_f"] == pytest.approx(cold["a_f"], rel=2e-2)
    assert warm["roll_force"] == pytest.approx(cold["roll_force"], rel=1e-3)


def test_the_form_key_ignores_what_a_kept_run_may_differ_in():
    """form_key (module docstring): the same for cases differing only in their name, m, K,
    a_f, plate length, solver tolerances or outputs; another for another mesh or geometry."""
    from hotroll.workflows.sweep import form_key

    base = example1_coarse("a")
    key = form_key(case_from_dict(base))
    same = [{"name": "b"}, {"material": {"K": 2.0, "m": 0.3}}, {"plate": {"length": 2.0}},
            {"output": {"figures": True, "vtk": True}},
            {"solver": {"method": "steady", "threads": 2, "tolerance": 1e-6}}]
    for change in same:
        assert form_key(case_from_dict({**base, **change})) == key, change
    other = [{"mesh": {"h_contact": 0.03}},
             {"pass": {**base["pass"], "exit_thickness": 0.42}}]
    for change in other:
        assert form_key(case_from_dict({**base, **change})) != key, change


def test_a_kept_run_is_reused_without_meshing():
    """Sweep.steady_run: a second case differing only in m is given the same SteadyRun, with
    that case's settings and plate length and no meshing time (mesh_time 0, it enters the
    run's wall time); a case on another mesh gets a new run (about 0.5 s of meshing each)."""
    from hotroll.workflows.runner import build_model, steady_settings

    first = case_from_dict(example1_coarse("a"))
    second = case_from_dict(example1_coarse("b", material={"K": 1.0, "m": 0.3},
                                            plate={"length": 2.0}))
    sweep = Sweep()
    run = sweep.steady_run(first, build_model(first)[0])
    assert run.mesh_time > 0.0
    kept = sweep.steady_run(second, build_model(second)[0])
    assert kept is run and kept.mesh_time == 0.0
    assert kept.s == steady_settings(second) and kept.plate_length == 2.0
    other = case_from_dict(example1_coarse("c", mesh={"h_contact": 0.03}))
    assert sweep.steady_run(other, build_model(other)[0]) is not run


def test_a_sweep_with_a_flattening_roll_solves_each_case_on_its_own_roll(tmp_path):
    """The bundled hot strip finishing pass with an elastic roll and a Norton-Hoff strip,
    K = 120 then 130 MPa (a key a kept run may differ in), through one sweep: the second case
    is not solved on the first case's kept run, whose strip map held the first roll's surface
    while the form took the new case's (found in the review of issue 34: 15.5 against 14.3
    MN/m on a variant of Example 1). [self] Its figures are a cold run's, to the couplings'
    tolerances (measured 1e-6 apart). K = 150 MPa was this test's second case until session 6:
    both runs "settled" at 28.87 MN/m, a false stop 4 % below the pass's 30.09 that the roll's
    change measure hid (it did not see the arc move with the roll's axis); measured where the
    strip sees it, that pass ends unsettled after its 30 updates at 30.05-30.14 MN/m, the arc's
    last move 1.4-6.7 tolerances (an open problem of the heavily flattened pass,
    docs/validation/speed.md)."""
    from hotroll.config.case import load_case
    from hotroll.examples import example_path

    base = load_case(example_path("hot_strip_finishing")).with_overrides(
        **{"roll.model": "elastic", "output.figures": False, "output.vtk": False,
           "material.law": "norton-hoff", "material.grade": None, "material.K": 1.2e8,
           "material.m": 0.15})
    harder = base.with_overrides(name="harder", **{"material.K": 1.3e8})
    sweep = Sweep()
    run_case(base, tmp_path / "base", sweep=sweep)
    warm = run_case(harder, tmp_path / "warm", sweep=sweep)
    cold = run_case(harder, tmp_path / "cold")
    assert warm["exit_code"] == 0 and cold["exit_code"] == 0
    assert warm["warm_start_from"] == base.name
    assert warm["roll_force"] == pytest.approx(cold["roll_force"], rel=2e-3)
    assert warm["roll_equivalent_radius"] == pytest.approx(cold["roll_equivalent_radius"],
                                                           rel=1e-3)
