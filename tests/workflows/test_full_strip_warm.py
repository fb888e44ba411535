"""Warm starts of the full strip between two rolls (issue 52 session 3): a sweep's neighbour on
the same mesh starts an asymmetric case (a study over the speed ratio), as the half model's
neighbours do (workflows/sweep.py), and its state survives a study's restart (warm_state.npz).

Labels: [fixed point] a warm and a cold start of the same case end at the same solution to
the coupled iteration's tolerances (any converged solve of the discrete problem does);
[plumb] what is written and read back."""
from __future__ import annotations

import numpy as np
import pytest

from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.solvers.steady_settings import FullWarmStart
from hotroll.workflows.runner import run_case
from hotroll.workflows.sweep import Sweep
from hotroll.workflows.warm_state import load_warm, save_warm

COARSE = {"mesh.h_contact": 0.0025, "output.figures": False}


def _case(ratio: float):
    return load_case(example_path("asymmetric_plate"), {**COARSE, "pass.speed_ratio": ratio})


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """r = 1.1 (its strip wraps the slower roll) cold, and warm from r = 1.05 in a sweep."""
    tmp = tmp_path_factory.mktemp("warm")
    cold = run_case(_case(1.1), tmp / "cold", resume=False)
    sweep = Sweep(similar=True, history=False)
    run_case(_case(1.05), tmp / "first", resume=False, sweep=sweep)
    warm = run_case(_case(1.1), tmp / "warm", resume=False, sweep=sweep)
    return cold, warm, sweep


def test_a_warm_start_reaches_the_cold_solution(runs):
    """[fixed point] the warm-started pass: the neighbour named, not solved again cold, exit 0,
    and each roll's force, torque and contact end, the curl and the cross-shear zone those of
    the cold start to the coupled iteration's tolerances (measured 1.5e-5 in force, 2e-4 in
    curl; the curl and the contact end are the fixed point's own unknowns)."""
    cold, warm, _ = runs
    assert warm["warm_start_from"] == "asymmetric_plate" and warm["warm_start_failed"] is False
    assert cold["exit_code"] == warm["exit_code"] == 0
    for c, w in zip(cold["rolls"], warm["rolls"]):
        assert w["roll_force"] == pytest.approx(c["roll_force"], rel=1e-4)
        assert w["roll_torque"] == pytest.approx(c["roll_torque"], rel=1e-3)
        assert w["contact_end"] == pytest.approx(c["contact_end"], abs=0.05 * COARSE["mesh.h_contact"])
    assert warm["exit_curvature"] == pytest.approx(cold["exit_curvature"], rel=2e-3)
    assert warm["cross_shear_length"] == pytest.approx(cold["cross_shear_length"],
                                                       abs=0.05 * COARSE["mesh.h_contact"])


def test_a_warm_start_saves_newton_iterations(runs):
    """[measured] the wrap's coupling rounds from a neighbour's shapes: 38 Newton iterations
    against 61 cold on this mesh (asserted: fewer)."""
    cold, warm, _ = runs
    assert warm["nonlinear_iterations"] < cold["nonlinear_iterations"]


def test_the_full_strips_state_is_written_and_read_back(runs, tmp_path):
    """[plumb] save_warm / load_warm keep a full strip's vector, both sides' shapes (their
    contact start and end, entry and exit curves), the wrapping sides, m, the reference roll
    speed, the mesh key and the free-surface model exactly."""
    _, _, sweep = runs
    state = sweep.solved[-1][2]
    assert isinstance(state, FullWarmStart) and state.wraps == (-1,)
    save_warm(tmp_path / "warm_state.npz", state)
    back = load_warm(tmp_path / "warm_state.npz")
    assert isinstance(back, FullWarmStart)
    np.testing.assert_array_equal(back.solution, state.solution)
    for side in (1, -1):
        a, b = state.shapes[side], back.shapes[side]
        assert (b.x_c, b.x_e) == (a.x_c, a.x_e)
        for key in ("entry_x", "entry_y", "exit_x", "exit_y"):
            np.testing.assert_array_equal(getattr(b, key), getattr(a, key))
    assert (back.wraps, back.m, back.u_roll, back.mesh_key, back.free_surface) == (
        state.wraps, state.m, state.u_roll, state.mesh_key, state.free_surface)


def test_neighbours_are_ranked_by_each_rolls_speed():
    """[hand] an asymmetric pass's parameters carry each roll's surface speed (upper 2 m/s,
    lower 2/r), so a study over the speed ratio starts r = 1.09 from r = 1.1, not from
    r = 1.02 (with the upper roll's speed alone every ratio lay at distance 0); a symmetric
    pass's parameters are the half model's as before (no per-roll keys)."""
    from hotroll.workflows.sweep import distance, parameters

    p = {r: parameters(_case(r)) for r in (1.02, 1.09, 1.1)}
    assert p[1.1]["u_roll_lower"] == pytest.approx(2.0 / 1.1, rel=1e-12)
    assert p[1.1]["u_roll_upper"] == pytest.approx(2.0, rel=1e-12)
    assert distance(p[1.09], p[1.1]) < distance(p[1.09], p[1.02])
    symmetric = parameters(load_case(example_path("asymmetric_plate"),
                                     {**COARSE, "pass.speed_ratio": None}))
    assert not any(k.endswith(("_upper", "_lower")) for k in symmetric)
