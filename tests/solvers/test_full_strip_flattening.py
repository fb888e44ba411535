"""Flattening rolls on the full-thickness strip (issue 52: the couplings loop over the rolls):
each roll is the half model's ``FlatteningRoll`` on its own side, updated from its own
contact's tractions in its own frame (solvers/full_steady.py ``roll_models``).

The pass is the bundled asymmetric_plate (R = 0.4 m, 25 -> 20 mm, Tresca 0.8, Norton-Hoff
K = 48 MPa s^m) on a coarse mesh (h = 2.5 mm). Labels: identities of the discrete problem
(equal rolls against the half model, the mirror) and Hitchcock's formula by hand."""
from __future__ import annotations

import math
from dataclasses import replace

import pytest

from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.model.roll_elastic import RollElasticity
from hotroll.solvers.full_steady import FullSteadyRun
from hotroll.solvers.steady import SteadyRun
from hotroll.workflows.build import build_model, steady_settings

COARSE = {"mesh.h_contact": 0.0025, "pass.speed_ratio": None}


def _case(kind: str, **extra):
    return load_case(example_path("asymmetric_plate"), {**COARSE, "roll.model": kind, **extra})


def _tight(st):
    """The couplings' tolerances / 100 (the traced tops', the roll's, Newton's): the equal
    rolls' identity then holds to the fixed point's limit, not to the two runs' paths."""
    return replace(st, surface_tol=st.surface_tol / 100, roll_tol=st.roll_tol / 100,
                   tol=st.tol / 100)


def _full(kind: str, speeds=(1.0, 1.0), swap=False, tight=False):
    """The full strip with both rolls flattening by ``kind`` at ``speeds`` x the case's."""
    case = _case(kind)
    problem, _ = build_model(case)
    rigid = replace(problem, roll=None, rp=case.pass_.roll_pass())
    rp = rigid.rp
    rolls = {1: replace(rp, omega=rp.omega * speeds[0]),
             -1: replace(rp, omega=rp.omega * speeds[1])}
    if swap:
        rolls = {1: rolls[-1], -1: rolls[1]}
    el = RollElasticity(case.roll.youngs_modulus, case.roll.poissons_ratio)
    models = {s: (kind, el, case.roll.relaxation, 1e-3 * rp.half_exit) for s in (1, -1)}
    st = _tight(steady_settings(case)) if tight else steady_settings(case)
    run = FullSteadyRun(rigid, st, case.plate.length, rolls,
                        {1: problem.friction, -1: problem.friction}, roll_models=models)
    sol = run.run()
    return run, sol.status, sol.history[-1]


def _half(kind: str):
    case = _case(kind)
    problem, _ = build_model(case)
    run = SteadyRun(problem, _tight(steady_settings(case)), case.plate.length)
    sol = run.run()
    return run, sol.status, sol.history[-1]


@pytest.fixture(scope="module")
def runs():
    return {"half_h": _half("hitchcock"), "equal_h": _full("hitchcock", tight=True),
            "r110_h": _full("hitchcock", (1.1, 1.0)),
            "r110_h_swapped": _full("hitchcock", (1.1, 1.0), swap=True),
            "half_e": _half("elastic"), "equal_e": _full("elastic", tight=True)}


def test_every_run_settles(runs):
    for name, (_, status, _) in runs.items():
        assert status == "steady", name


@pytest.mark.parametrize("kind", ["h", "e"])
def test_equal_flattening_rolls_give_the_half_model(runs, kind):
    """Identity: two equal flattening rolls are the half model's discrete problem twice (the
    same roll updates from the same tractions): force, torque and slip equal to the fixed
    point's tolerance, both solved with the couplings' tolerances / 100 (``_tight``: at the
    defaults the two runs' paths (the full strip tightens its coupling threshold, moves its
    end every round) leave each 1-2e-5 from the fixed point's limit in force, and at 16x
    on opposite sides: the elastic disc 3.3e-5 apart, against 5e-7 at 1x where both erred
    alike; /10 3.6e-6, /100 1.3e-7), each roll's surface the half model's."""
    hrun, _, half = runs[f"half_{kind}"]
    frun, _, full = runs[f"equal_{kind}"]
    for side in ("upper", "lower"):
        assert full[f"{side}_roll_force"] == pytest.approx(half["roll_force"], rel=1e-5)
        assert full[f"{side}_roll_torque"] == pytest.approx(half["roll_torque"], rel=1e-4)
        assert full[f"{side}_forward_slip"] == pytest.approx(half["forward_slip"], abs=1e-5)
    theta = 0.9 * hrun.problem.rp.bite_angle
    w_half = float(hrun.problem.roll.shape.offset(theta))
    for roll in frun.flattening.values():
        assert float(roll.shape.offset(theta)) == pytest.approx(w_half, rel=2e-4)
    assert abs(w_half) > 1e-6                    # it did flatten


def test_swapping_flattening_rolls_mirrors_them(runs):
    """Identity: the swapped stand is the mirror image: each roll's force, torque and
    flattened surface trade places (measured 1e-12: the same discrete problem mirrored)."""
    a_run, _, a = runs["r110_h"]
    b_run, _, b = runs["r110_h_swapped"]
    for key in ("roll_force", "roll_torque"):
        assert b[f"upper_{key}"] == pytest.approx(a[f"lower_{key}"], rel=1e-9)
        assert b[f"lower_{key}"] == pytest.approx(a[f"upper_{key}"], rel=1e-9)
    theta = 0.5 * a_run.rolls[1].bite_angle
    assert float(b_run.flattening[1].shape.offset(theta)) == pytest.approx(
        float(a_run.flattening[-1].shape.offset(theta)), rel=1e-9)


def test_each_roll_is_hitchcocks_circle_of_its_own_force(runs):
    """By hand (Hitchcock 1935): each roll's flattened radius R' = R (1 + C F'/dh), C =
    16 (1 - nu^2)/(pi E), with its own roll force F' (per unit width) and dh twice its own
    arc's draft (the pass's 5 mm here: equal radii), to the coupling's tolerance (the roll is
    updated from the force of the flow before the last Newton steps: measured 3e-7 and 2e-6
    in w at 0.8 of the bite angle; R'/R = 1.032)."""
    run, _, row = runs["r110_h"]
    E, nu = 2.1e11, 0.3                  # the case's [roll] defaults
    C = 16.0 * (1.0 - nu**2) / (math.pi * E)
    for side, name in ((1, "upper"), (-1, "lower")):
        rp = run.rolls[side]
        ratio = 1.0 + C * row[f"{name}_roll_force"] / (2.0 * rp.draft)
        # the circle of radius R' through the rigid roll's lowest point, seen from the rigid
        # centre at angle theta: r = -D cos t + sqrt(R'^2 - D^2 sin^2 t), D = R' - R
        theta = 0.8 * rp.rigid_bite_angle
        R = rp.radius
        D = (ratio - 1.0) * R
        w = -D * math.cos(theta) + math.sqrt((R + D) ** 2 - (D * math.sin(theta)) ** 2) - R
        assert float(run.flattening[side].shape.offset(theta)) == pytest.approx(w, rel=1e-4), \
            name
