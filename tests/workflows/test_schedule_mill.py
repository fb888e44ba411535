"""A schedule on a mill (issue 32): flattening rolls in every stand (``[roll]``), a stand given
by its no-load roll gap and mill modulus (``pass.roll_gap``, ``pass.mill_modulus``), on the
coarse two-pass schedule of tests/data/two_pass_schedule.toml (about 6 s)."""
from __future__ import annotations

import tomllib
from pathlib import Path

import pytest
from casebuild import assert_schedule_refused, shared_scope

from hotroll.config.schedule import schedule_from_dict
from hotroll.model.roll_elastic import RollElasticity
from hotroll.workflows.gauge import GAUGE_RTOL
from hotroll.workflows.schedule import run_schedule

DATA = Path(__file__).resolve().parents[1] / "data" / "two_pass_schedule.toml"
GAP, MODULUS = 0.065, 3e9          # m, N/m: pass 2's stand


def _data() -> dict:
    d = tomllib.loads(DATA.read_text())
    d["roll"] = {"model": "hitchcock"}
    d["pass"][0]["mill_modulus"] = MODULUS
    p2 = d["pass"][1]
    p2.pop("exit_thickness")
    p2.update(roll_gap=GAP, mill_modulus=MODULUS)
    return d


@pytest.fixture(scope=shared_scope)
def rows(tmp_path_factory):
    out = tmp_path_factory.mktemp("mill")
    rows = run_schedule(schedule_from_dict(_data()), out, figure=False)
    for r in rows:          # the exit thickness each pass was solved for (its case file)
        r["set_exit"] = tomllib.loads((out / r["case"] / "case.toml").read_text())["pass"].get(
            "exit_thickness")
    return rows


def test_the_gap_stand_rolls_to_the_gap_plus_its_stretch(rows):
    """Pass 2's exit thickness is S + F/M at its own whole-width force (by hand from the row),
    and pass 1's set-up gap is its exit thickness less its stretch. Each pass enters with the
    thickness the one before leaves with (its solve's, within 0.5 % of the one set)."""
    r1, r2 = rows
    stretch = r2["roll_force_total"] / MODULUS
    assert 1e-4 < stretch < 1e-3
    assert r2["gauge_thickness"] == pytest.approx(GAP + stretch, abs=5 * GAUGE_RTOL * GAP)
    assert abs(r2["exit_thickness"] / r2["gauge_thickness"] - 1.0) < 5e-3
    assert r2["roll_gap"] == GAP and r2["entry_thickness"] == r1["exit_thickness"]
    assert r1["set_exit"] == 0.08 and abs(r1["exit_thickness"] / 0.08 - 1.0) < 5e-3
    assert r2["reduction"] == pytest.approx(1 - r2["exit_thickness"] / r2["entry_thickness"],
                                            rel=1e-12)
    assert r1["gap_setting"] == pytest.approx(0.08 - r1["roll_force_total"] / MODULUS,
                                              rel=1e-12)
    assert r2["fe_solves"] >= 2          # at least one trial thickness before the last


def test_every_stand_flattens_its_rolls_by_hitchcock(rows):
    """[roll] reaches every pass: Hitchcock's R' = R (1 + C F'/dh) at each stand's force per
    width and the draft it was solved for, to the coupling's tolerance."""
    for r in rows:
        dh = r["entry_thickness"] - r.get("gauge_thickness", r["set_exit"])
        ratio = RollElasticity().hitchcock_ratio(r["roll_force"], dh)
        assert r["roll_equivalent_radius"] / 0.3 == pytest.approx(ratio, rel=1e-3)
        assert r["roll_flattening"] > 0.0


@pytest.mark.parametrize("change,field", [
    (lambda d: d["pass"][1].pop("mill_modulus"), "pass[2].roll_gap: needs pass[2].mill_modulus"),
    (lambda d: d["pass"][1].update(exit_thickness=0.066), "pass[2]: give exactly one of"),
    (lambda d: d["pass"][1].pop("roll_gap"), "pass[2]: give exactly one of"),
    (lambda d: d["pass"][1].update(roll_gap=0.08), "pass[2].roll_gap: must be < the entry"),
    (lambda d: d["strip"].pop("width"), "pass[1].mill_modulus: needs strip.width"),
    (lambda d: d["roll"].update(model="soft"), "roll.model"),
])
def test_bad_mill_schedules_name_the_field(change, field):
    d = _data()
    change(d)
    assert_schedule_refused(d, field)
