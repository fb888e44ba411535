"""A pass given by its roll gap (workflows/gauge.py): the exit thickness h1 = S + F(h1)/M found
with the force, on Example 1's pass (coarse mesh, Norton-Hoff K = 1 Pa, viscoplastic a_f = 5).
"""
from __future__ import annotations

import pytest

from hotroll.config.case import CaseError, case_from_dict
from hotroll.workflows.gauge import GAUGE_RTOL
from hotroll.workflows.runner import run_case
from tests.casebuild import EXAMPLE1_COARSE, shared_scope

GAP = 0.37          # m: the rigid mill would roll 0.5 -> 0.37 m
#: N/m per m of width: about 0.05 m of stretch under Example 1's ~0.5 N/m
MODULUS = 10.0


def _case(name: str, gap=GAP, modulus=MODULUS, K=1.0, **pass_keys):
    rigid = {k: v for k, v in EXAMPLE1_COARSE["pass"].items() if k != "exit_thickness"}
    d = {**EXAMPLE1_COARSE, "name": name,
         "pass": {**rigid, "width": 1.0, "mill_modulus": modulus, "roll_gap": gap, **pass_keys},
         "material": {**EXAMPLE1_COARSE["material"], "K": K}}
    return case_from_dict(d)


@pytest.fixture(scope=shared_scope)
def runs(tmp_path_factory):
    out = tmp_path_factory.mktemp("gauge")
    return {key: run_case(case, out / key) for key, case in {
        "soft": _case("soft"), "stiff": _case("stiff", modulus=4 * MODULUS),
        "scaled": _case("scaled", K=3.0, modulus=3 * MODULUS)}.items()}


def test_the_exit_thickness_is_the_gap_plus_the_stretch(runs):
    """The gaugemeter equation at the solved force, by hand from the summary's whole-width
    force, to the search's tolerance; the summary's own gap to set (results/engineering.py,
    another code path) is the gap given."""
    s = runs["soft"]
    assert s["exit_code"] == 0 and s["roll_gap"] == GAP
    h1 = s["gauge_thickness"]              # the pass's exit thickness (the measured one
    # differs by the mesh's error and, this thick strip leaving the roll before the gap, by its
    # thinning after it: measured 0.37 %)
    assert s["exit_thickness"] == pytest.approx(h1, rel=6e-3)
    assert s["exit_thickness"] < h1 and s["contact_end_kind"] == "separation"
    stretch = s["roll_force_total"] / MODULUS
    assert 0.03 < stretch < 0.1            # the stand does open: the test means something
    assert h1 == pytest.approx(GAP + stretch, abs=5 * GAUGE_RTOL * GAP)
    assert s["gap_setting"] == pytest.approx(GAP, abs=GAUGE_RTOL * GAP)
    assert s["mill_stretch"] == pytest.approx(stretch, rel=1e-12)
    assert 2 <= s["gauge_solves"] <= 8


def test_a_stiffer_mill_rolls_nearer_the_gap(runs):
    """g(h) = h - S - F(h)/M rises with h and falls with M at fixed h, so the root moves
    toward S as M grows, and the thinner strip takes a larger force."""
    soft, stiff = runs["soft"], runs["stiff"]
    assert GAP < stiff["gauge_thickness"] < soft["gauge_thickness"]
    assert stiff["roll_force_total"] > soft["roll_force_total"]
    assert stiff["gauge_thickness"] - GAP == pytest.approx(
        stiff["roll_force_total"] / (4 * MODULUS), abs=5 * GAUGE_RTOL * GAP)


def test_the_gap_pass_scales_exactly_with_the_flow_stress_and_the_modulus(runs):
    """Norton-Hoff with viscoplastic friction: F is proportional to K at a given geometry, so
    K x 3 with M x 3 is the same search, step by step: the same exit thickness (to round-off
    and Newton's tolerance), three times the force (to the contact end's tolerance)."""
    soft, scaled = runs["soft"], runs["scaled"]
    assert scaled["gauge_thickness"] == pytest.approx(soft["gauge_thickness"], rel=1e-7)
    # (the couplings settle to 1e-3 h along the two runs' paths, which part in the last bits:
    # measured 1.9e-6 of the force with the trapezoidal trace, 6.5e-6 with the cubic one)
    assert scaled["roll_force_total"] == pytest.approx(3 * soft["roll_force_total"], rel=2e-5)
    assert scaled["gauge_solves"] == soft["gauge_solves"]


def test_a_gap_needs_a_modulus_a_width_a_steady_solve_and_room_below_the_entry():
    with pytest.raises(CaseError, match="pass.roll_gap: needs pass.mill_modulus"):
        _case("x", modulus=None)
    with pytest.raises(CaseError, match="pass.roll_gap: must be smaller than pass.entry_"):
        _case("x", gap=0.5)
    with pytest.raises(CaseError, match="pass.roll_gap: -0.01 m: a no-load gap <= 0 is a preloaded stand"):
        _case("x", gap=-0.01)
    d = _case("x").to_dict()
    d["solver"] = {"method": "transient"}
    d["contact"] = {"method": "penalty"}
    with pytest.raises(CaseError, match='pass.roll_gap: needs solver.method = "steady"'):
        case_from_dict(d)
    # the exit thickness, if given with the gap, is the search's first guess
    assert _case("x").pass_.exit_thickness == GAP
    assert _case("x", exit_thickness=0.42).pass_.exit_thickness == 0.42
