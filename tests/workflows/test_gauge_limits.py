"""A pass given by its roll gap at the search's limits (issue 51 item 7; workflows/gauge.py), on
Example 1's pass (Norton-Hoff K = 1 Pa, viscoplastic a_f = 5; about 10 s), and a negative gap
to set in a schedule: an impossible gap ends with its reason and exit code 3 ("failed",
results/outcome.py), as does a trial the search chose that cannot be set up; a gap far below
the exit thickness settles to the thickness's tolerance; a negative gap to set is reported with
what it means."""
from __future__ import annotations

import json
import tomllib
from pathlib import Path

import pytest
from casebuild import EXAMPLE1_COARSE

from hotroll.config.case import case_from_dict
from hotroll.config.schedule import schedule_from_dict
from hotroll.results.outcome import EXIT_CODES
from hotroll.workflows.gauge import GAUGE_RTOL, negative_gap_warning
from hotroll.workflows.runner import run_case
from hotroll.workflows.schedule import ScheduleError, run_schedule

H0 = 0.5                   # m, Example 1's entry thickness
DATA = Path(__file__).resolve().parents[1] / "data" / "two_pass_schedule.toml"


def _gap_case(name: str, gap: float, modulus: float, **sections):
    rigid = {k: v for k, v in EXAMPLE1_COARSE["pass"].items() if k != "exit_thickness"}
    d = {**EXAMPLE1_COARSE, "name": name,
         "pass": {**rigid, "width": 1.0, "mill_modulus": modulus, "roll_gap": gap}}
    for key, value in sections.items():
        sec, field = key.split("__")
        d[sec] = {**d.get(sec, {}), field: value}
    return case_from_dict(d)


def test_an_impossible_gap_ends_failed_with_the_reason(tmp_path):
    """S = 0.1 m on a stand of M = 0.3 N/m (Example 1's force is about 0.5 N/m): even at the
    search's thinnest draft, 0.98 of the way from the gap to the entry (h = 0.492 m by hand),
    the stretch F/M exceeds the opening h - S, so no h1 = S + F(h1)/M lies between the gap
    and the entry. The first guess is that draft (0.01 m mesh: its contact is short): one
    solve. Before: "did not settle", exit code 5, status unsettled."""
    S, M = 0.1, 0.3
    top = S + 0.98 * (H0 - S)
    s = run_case(_gap_case("impossible", S, M, pass__exit_thickness=top,
                           mesh__h_contact=0.01), tmp_path / "impossible")
    assert s["exit_code"] == 3 and EXIT_CODES[3] == "failed" and s["status"] == "failed"
    assert s["gauge_thickness"] == pytest.approx(top, rel=1e-12)
    stretch = s["roll_force_total"] / M
    assert top - S - stretch < 0.0              # the gaugemeter by hand: the stand opens more
    assert "pass.roll_gap: impossible roll gap" in s["failure"]
    assert f"F/M = {1e3 * stretch:.4g} mm" in s["failure"]
    assert f"h - S = {1e3 * (top - S):.4g} mm" in s["failure"]
    assert json.loads((tmp_path / "impossible" / "summary.json").read_text())["exit_code"] == 3


def test_a_trial_the_mesh_cannot_take_ends_failed_naming_it(tmp_path):
    """S = 0.47 m, M = 10 N/m on the 0.02 m mesh: the first trial (h = S) leaves the stretch
    above the opening (by hand: h - S = 0 < F/M), the slab step asks for a thinner draft whose
    contact is too short for the mesh; the case validation's refusal becomes the pass's
    reason (exit code 3) instead of an exception out of the search."""
    S, M = 0.47, 10.0
    s = run_case(_gap_case("trial", S, M), tmp_path / "trial")
    assert s["exit_code"] == 3 and s["status"] == "failed"
    assert s["gauge_solves"] == 1 and s["gauge_thickness"] == S
    assert s["roll_force_total"] / M > 0.0                      # g(S) = -F/M < 0
    assert "trial 2" in s["failure"] and "could not be set up" in s["failure"]
    assert "mesh.h_contact: must be < contact_length/4" in s["failure"]


def test_a_gap_far_below_the_exit_thickness_settles(tmp_path):
    """S = 1 mm on a stand so soft that the strip leaves at about 0.42 m: the tolerance is the
    exit thickness's (1e-4 h1), not the gap's (1e-4 S = 1e-7 m, 2.4e-7 of h1: before, 12
    solves and "did not settle", exit code 5). The gaugemeter by hand from the force."""
    S, M = 0.001, 1.2
    s = run_case(_gap_case("tiny", S, M, pass__exit_thickness=0.42), tmp_path / "tiny")
    assert s["exit_code"] == 0
    h1 = s["gauge_thickness"]
    assert abs(h1 - S - s["roll_force_total"] / M) <= GAUGE_RTOL * h1
    assert 0.4 < h1 < 0.44


def test_the_negative_gap_warning_says_what_it_means():
    """S = h1 - F/M = 2.0 - 2.48 mm: the rolls pressed 0.48 mm into each other at no load."""
    text = negative_gap_warning(-0.00048, 0.00248)
    for part in ("S = h1 - F/M = -0.480 mm", "F/M = 2.480 mm", "exit thickness h1 = 2.000 mm",
                 "pressed 0.480 mm into each other", "preloaded stand", "pass.roll_gap takes a "
                 "gap > 0 only"):
        assert part in text, part
    assert negative_gap_warning(0.0001, 0.0019) is None
    assert negative_gap_warning(None, None) is None


def _two_pass(**pass2) -> dict:
    d = tomllib.loads(DATA.read_text())
    d["pass"][1].update(pass2)
    return d


def test_a_schedule_reports_a_negative_gap_to_set(tmp_path):
    """Pass 1 on a stand of M = 5e6 N/m: its whole-width force (about 0.9 MN) stretches it
    more than the 0.08 m it rolls to, so its gap to set is negative; pass 2 on a stiff stand
    (5e10 N/m) keeps a positive one. The warning is in the progress lines and schedule.json
    for pass 1 only, and its figures are the row's (gap + stretch = the exit thickness set)."""
    d = _two_pass(mill_modulus=5e10)
    d["pass"][0]["mill_modulus"] = 5e6
    lines: list[str] = []
    rows = run_schedule(schedule_from_dict(d), tmp_path, figure=False, progress=lines.append)
    r1, r2 = rows
    assert r1["gap_setting"] + r1["mill_stretch"] == pytest.approx(0.08, rel=1e-12)
    assert r1["gap_setting"] < 0.0 < r2["gap_setting"]
    warned = [x for x in lines if "WARNING" in x]
    assert len(warned) == 1 and warned[0].startswith("R1: WARNING: the gap to set is negative")
    for figure in (r1["gap_setting"], r1["mill_stretch"], 0.08):
        assert f"{1e3 * figure:.3f} mm" in warned[0]
    js = json.loads((tmp_path / "schedule.json").read_text())
    assert js["warnings"] == [warned[0].replace("WARNING: ", "")]


def test_a_schedule_stand_with_an_impossible_gap_stops_with_the_reason(tmp_path):
    """Pass 2 given by a gap of 73 mm (entry about 80 mm) on a soft 3e7 N/m stand: at h = S the
    stretch (about 24 mm) exceeds the opening, and the slab step's next trial is a draft the
    8 mm mesh cannot take; the schedule stops at pass 2 with exit code 3 and the reason in its
    message (before: an exception out of the search)."""
    d = _two_pass(roll_gap=0.073, mill_modulus=3e7)
    d["pass"][1].pop("exit_thickness")
    with pytest.raises(ScheduleError) as e:
        run_schedule(schedule_from_dict(d), tmp_path, figure=False)
    assert e.value.k == 1 and e.value.summary["exit_code"] == 3
    assert "pass.roll_gap: the gap search's trial" in str(e.value)
    assert e.value.summary["failure"] in str(e.value)


def test_a_single_run_with_a_negative_gap_to_set_warns(tmp_path):
    """Example 1's pass (force about 0.5 N/m) on a stand of M = 1 N/m: the stretch (about 0.5
    m) exceeds the 0.4 m exit thickness; the run's summary carries the warning (its
    ``warnings``, which ``hotroll run`` prints), with the figures of its own gap and stretch."""
    rigid = {k: v for k, v in EXAMPLE1_COARSE["pass"].items()}
    d = {**EXAMPLE1_COARSE, "name": "negative",
         "pass": {**rigid, "width": 1.0, "mill_modulus": 1.0}}
    s = run_case(case_from_dict(d), tmp_path / "negative")
    assert s["gap_setting"] + s["mill_stretch"] == pytest.approx(0.4, rel=1e-12)
    assert s["gap_setting"] < 0.0
    assert (f'pass.mill_modulus: {negative_gap_warning(s["gap_setting"], s["mill_stretch"])}'
            in (s.get("warnings") or []))


@pytest.mark.parametrize("gap", [0.0, -0.00017, "-0.17 mm"])
def test_a_gap_that_does_not_open_is_refused_saying_it_is_a_preloaded_stand(gap):
    """A no-load gap <= 0 (what a run's negative gap to set means) is refused before anything
    runs, in a case and in a schedule, with the reason and the fix (exit_thickness)."""
    import tomllib

    from hotroll.config.case import CaseError
    from hotroll.config.schedule import schedule_from_dict
    from hotroll.examples import example_path, schedule_path

    d = tomllib.loads(example_path("thin_strip").read_text())
    d["pass"].pop("exit_thickness")
    d["pass"].update(roll_gap=gap, mill_modulus=4e9, width=1.0)
    with pytest.raises(CaseError) as e:
        case_from_dict(d)
    assert len(e.value.problems) == 1
    assert e.value.problems[0].startswith("pass.roll_gap: ")
    assert "preloaded stand" in e.value.problems[0] and "exit_thickness" in e.value.problems[0]
    s = tomllib.loads(schedule_path("finishing_mill").read_text())
    s["pass"][1].pop("exit_thickness")
    s["pass"][1].update(roll_gap=gap, mill_modulus=4e9)
    with pytest.raises(CaseError) as e:
        schedule_from_dict(s)
    assert [p.split(":")[0] for p in e.value.problems] == ["pass[2].roll_gap"]
    assert "preloaded stand" in e.value.problems[0]
