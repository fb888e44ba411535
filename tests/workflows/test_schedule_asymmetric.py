"""A schedule with an asymmetric pass (issue 52 item 4): tests/data/asymmetric_schedule.toml, the
bundled asymmetric_plate's pass (speed ratio 1.1) on a coarse mesh, then a symmetric pass.

Labels: [id] identities between schedule.csv/schedule.json and the pass's own summary.json
(they catch a table that drops, scales or swaps a figure, not a wrong solve:
tests/workflows/test_asymmetric_run.py and tests/solvers/test_full_strip.py check the solve);
[hand] numbers the file gives or a hand formula; [refusal] a bad schedule refused naming the
pass and the key, before any computation."""
from __future__ import annotations

import csv
import json
import math
import tomllib
from pathlib import Path

import pytest

from hotroll.config.case import CaseError
from hotroll.config.schedule import schedule_from_dict
from hotroll.results.units import UNITS

DATA = Path(__file__).resolve().parents[1] / "data" / "asymmetric_schedule.toml"
PER_ROLL = ("roll_force", "roll_torque", "roll_power")


def _data() -> dict:
    return tomllib.loads(DATA.read_text())


@pytest.fixture(scope="module")
def rolled(tmp_path_factory):
    """The two passes rolled (two FE solves, ~5 s): (rows, schedule.json, csv rows, out)."""
    from hotroll.workflows.schedule import run_schedule

    out = tmp_path_factory.mktemp("asym_schedule")
    rows = run_schedule(schedule_from_dict(_data()), out, figure=False)
    with open(out / "schedule.csv", newline="") as fh:
        table = list(csv.DictReader(fh))
    return rows, json.loads((out / "schedule.json").read_text()), table, out


def _summary(out: Path, row: dict) -> dict:
    return json.loads((out / row["case"] / "summary.json").read_text())


def test_the_asymmetric_row_is_its_pass_summary(rolled):
    """[id] the asymmetric pass's curvature, angle, speed ratio, cross-shear length and each
    roll's radius, speed, force, torque and power in schedule.json and schedule.csv equal its
    summary.json's (``rolls``: upper, then lower)."""
    rows, sj, table, out = rolled
    s = _summary(out, rows[0])
    assert s["exit_curvature"] != 0.0 and math.isfinite(s["exit_curvature"])
    for key in ("exit_curvature", "exit_angle", "speed_ratio", "cross_shear_length"):
        assert sj["passes"][0][key] == s[key], key
        assert float(table[0][key]) == pytest.approx(s[key], rel=1e-12), key
    for entry in s["rolls"]:
        side = entry["side"]
        for key in PER_ROLL:
            assert sj["passes"][0][f"{side}_{key}"] == entry[key], (side, key)
            assert float(table[0][f"{side}_{key}"]) == pytest.approx(entry[key], rel=1e-12)
        assert sj["passes"][0][f"{side}_roll_radius"] == entry["radius"] == 0.4
        assert sj["passes"][0][f"{side}_roll_surface_speed"] == entry["surface_speed"]
    # [hand] the rolls the file gives: omega R = 2 m/s upper, 2/1.1 lower
    assert sj["passes"][0]["upper_roll_surface_speed"] == pytest.approx(2.0, rel=1e-12)
    assert sj["passes"][0]["lower_roll_surface_speed"] == pytest.approx(2.0 / 1.1, rel=1e-12)
    assert s["rolls"][0]["roll_torque"] != pytest.approx(s["rolls"][1]["roll_torque"])


def test_the_symmetric_row_is_straight_and_has_no_roll_columns(rolled):
    """[id] the symmetric pass: curvature and angle 0 (the half model's symmetry plane), the
    per-roll columns empty, its force its summary's own."""
    rows, sj, table, out = rolled
    p2 = sj["passes"][1]
    assert p2["exit_curvature"] == 0.0 and p2["exit_angle"] == 0.0
    assert "speed_ratio" not in p2 and table[1]["upper_roll_torque"] == ""
    assert p2["roll_force"] == _summary(out, rows[1])["roll_force"]


def test_the_units_are_written(rolled):
    """[id] every new column's unit in schedule.json's units (and the table of units)."""
    _, sj, _, _ = rolled
    want = {"exit_curvature": "1/m", "exit_angle": "rad", "cross_shear_length": "m",
            "upper_roll_force": "N/m", "lower_roll_torque": "N m/m", "upper_roll_power": "W/m",
            "lower_roll_radius": "m", "upper_roll_surface_speed": "m/s", "speed_ratio": "-"}
    for key, unit in want.items():
        assert sj["units"][key] == UNITS[key] == unit, key


def test_the_strip_state_carries_over(rolled):
    """[id] the symmetric pass enters with the asymmetric pass's measured exit thickness and
    its mean strain (no exit profile: the homogeneous entry + 2/sqrt3 ln(h0/h1), h1 the set
    exit thickness [hand]); the
    isothermal pass hands on its entry temperature, which the transport cools."""
    rows, sj, _, out = rolled
    s1 = _summary(out, rows[0])
    assert rows[1]["entry_thickness"] == s1["exit_thickness"] == rows[0]["exit_thickness"]
    assert rows[0]["exit_strain_mean"] == pytest.approx(
        2 / math.sqrt(3) * math.log(0.025 / 0.02), rel=1e-12)
    assert rows[1]["entry_strain_mean"] == pytest.approx(rows[0]["exit_strain_mean"], rel=1e-12)
    assert rows[0]["outlet_temperature_mean"] == pytest.approx(1373.15, rel=1e-12)
    assert rows[1]["entry_temperature_mean"] == pytest.approx(
        rows[0]["next_entry_temperature_mean"], rel=1e-9)
    assert rows[1]["entry_temperature_mean"] < 1373.15 - 1.0


def test_a_finished_asymmetric_pass_is_resumed(rolled):
    """[plumb] run again into the same directory: both passes reused, no FE solve."""
    from hotroll.workflows.schedule import run_schedule

    _, _, _, out = rolled
    rows = run_schedule(schedule_from_dict(_data()), out, figure=False)
    assert [r["fe_solves"] for r in rows] == [0, 0]


def _refused(over_pass: dict | None = None, **top) -> list[str]:
    d = _data()
    if over_pass:
        d["pass"][0].update(over_pass)
    d.update(top)
    with pytest.raises(CaseError) as e:
        schedule_from_dict(d)
    return e.value.problems


REFUSED = [
    ({}, {"microstructure": {"model": "hodgson_gibbs_cmn", "grain_size": 100e-6}},
     "pass[1].isothermal: "),
    ({"friction": {"law": "viscoplastic", "a_f": "estimate"}}, {}, "pass[1].friction.a_f: "),
    ({"upper": {"roll_radius": 0.001}}, {}, "pass[1].upper.roll_radius: "),
    ({"lower": {"roll_surface_speed": 1.5}}, {}, "pass[1].speed_ratio: conflicts"),
]


@pytest.mark.parametrize("over,top,start", REFUSED, ids=[s for _, _, s in REFUSED])
def test_refusals_name_the_pass_and_key(over, top, start, monkeypatch):
    """[refusal] each a problem line naming pass[1] (the asymmetric pass) and its key, from the
    schedule's checks: no FE object is built (a solve would fail the test)."""
    import hotroll.workflows.runner as runner

    monkeypatch.setattr(runner, "run_case", lambda *a, **k: pytest.fail("computed"))
    problems = _refused(over, **top)
    hits = [p for p in problems if p.startswith(start)]
    assert hits, problems
    assert all("pass[1]" in p for p in hits), hits


def test_a_mass_flow_tandem_is_refused_with_an_asymmetric_pass():
    """[refusal] mill.speeds = "mass_flow": the full strip searches no stand speed (its solve
    ignores the mass flux); refused naming pass[1], not silently run at the guessed speed."""
    d = _data()
    d["mill"] = {"speeds": "mass_flow"}
    del d["pass"][1]["roll_angular_velocity"]
    with pytest.raises(CaseError) as e:
        schedule_from_dict(d)
    assert any(p.startswith('mill.speeds: "mass_flow" cannot set pass[1]')
               for p in e.value.problems), e.value.problems


def test_a_tension_search_is_refused_with_an_asymmetric_pass():
    """[refusal] mill.tensions = "from_speeds": the full strip's flux is the whole thickness's
    and it searches no tension; refused naming pass[1]."""
    problems = _refused(mill={"tensions": "from_speeds"})
    assert any(p.startswith('mill.tensions: "from_speeds" cannot take pass[1]')
               for p in problems), problems


def test_a_symmetric_schedule_takes_no_asymmetric_check():
    """[refusal] the same file without speed_ratio: both passes symmetric, valid with a thermal
    pass and a tandem's mass flow (the checks apply to asymmetric passes only)."""
    d = _data()
    del d["pass"][0]["speed_ratio"]
    d["pass"][0]["isothermal"] = False
    d["mill"] = {"speeds": "mass_flow"}
    del d["pass"][1]["roll_angular_velocity"]
    schedule_from_dict(d)


@pytest.fixture(scope="module")
def rolled_thermal(tmp_path_factory):
    """The same two passes with the asymmetric one's temperature solved (``isothermal =
    false``): (rows, out)."""
    from hotroll.workflows.schedule import run_schedule

    d = _data()
    d["pass"][0]["isothermal"] = False
    out = tmp_path_factory.mktemp("asym_schedule_thermal")
    return run_schedule(schedule_from_dict(d), out, figure=False), out


def test_a_thermal_asymmetric_pass_hands_on_its_folded_profile(rolled_thermal):
    """[id] the asymmetric pass's temperature solved over the whole thickness (eta -1..1 in
    its summary's exit_profile, both surfaces chilled by their rolls) is handed on folded
    about the middle: the schedule's outlet mean is the whole profile's section mean
    (constant rho c: the enthalpy mean is the temperature's; ``ThicknessProfile.fold`` keeps
    it exactly), and the next pass enters with the transport's result of it."""
    import numpy as np

    rows, out = rolled_thermal
    s = _summary(out, rows[0])
    prof = s["exit_profile"]
    eta, T = np.asarray(prof["eta"]), np.asarray(prof["temperature"])
    assert eta[0] == -1.0 and eta[-1] == 1.0 and len(prof["shear_strain"]) == len(eta)
    assert max(T[0], T[-1]) < s["exit_temperature_mean"] - 50.0
    whole = float(np.sum(0.5 * (T[1:] + T[:-1]) * np.diff(eta))) / 2.0
    assert rows[0]["outlet_temperature_mean"] == pytest.approx(whole, rel=1e-9)
    # not the entry temperature an isothermal pass hands on (here the plastic heat outweighs
    # the chill: +0.9 K)
    assert abs(rows[0]["outlet_temperature_mean"] - 1373.15) > 0.1
    assert rows[1]["entry_temperature_mean"] == pytest.approx(
        rows[0]["next_entry_temperature_mean"], rel=1e-9)
