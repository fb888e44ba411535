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
