"""The error lines of a schedule or study file (hotroll/config/base.py: problem_lines), each
written out by hand: the key path with the pass counted from 1, pydantic's message with its
first letter lowered and the value given, "unknown key" and "missing required key", and a
section's own lines (a law's checks) as they are, under the pass they belong to."""
from __future__ import annotations

import tomllib

import pytest
from conftest import DATA

from hotroll.config.base import CaseError
from hotroll.config.schedule import schedule_from_dict

pytestmark = pytest.mark.mutation


def _problems(edit) -> list[str]:
    d = tomllib.loads((DATA / "two_pass_schedule.toml").read_text())
    edit(d)
    with pytest.raises(CaseError) as e:
        schedule_from_dict(d, "s.toml")
    return e.value.problems


def test_unknown_and_missing_keys_are_named_with_their_pass():
    def edit(d):
        d["pass"][1]["colour"] = "red"              # unknown, in the second pass
        del d["pass"][0]["roll_radius"]             # missing, in the first
    assert sorted(_problems(edit)) == ["pass[1].roll_radius: missing required key",
                                       "pass[2].colour: unknown key"]


def test_a_bad_value_gives_the_rule_and_the_value():
    def edit(d):
        d["pass"][1]["transport"] = {"duration": -3.0}
    assert _problems(edit) == ["pass[2].transport.duration: input should be greater than 0, "
                               "got -3.0"]


def test_a_sections_own_lines_come_as_they_are():
    """A model validator's lines (the friction law's check) are not reworded."""
    def edit(d):
        d["friction"] = {"law": "coulomb"}
    assert _problems(edit) == ['friction.mu: required for law = "coulomb" (allowed: in (0, 2])']


def test_a_passes_own_lines_are_put_under_that_pass():
    def edit(d):
        d["pass"][0]["transport"]["distance"] = 5.0     # and its duration: two of one
    assert _problems(edit) == ["pass[1].transport: give exactly one of duration (s) and "
                               "distance (m)"]


def test_every_problem_is_kept_in_order():
    """A section's own lines between pydantic's: none lost, none repeated."""
    def edit(d):
        d["pass"][0]["colour"] = "red"
        d["pass"][0]["transport"]["distance"] = 5.0
        d["pass"][1]["roll_radius"] = "big"
    assert _problems(edit) == [
        "pass[1].transport: give exactly one of duration (s) and distance (m)",
        "pass[1].colour: unknown key",
        "pass[2].roll_radius: numbers, got 'big'"]      # the validator's words, once


def test_a_pass_that_is_not_a_table():
    def edit(d):
        d["pass"][1] = 5
    (line,) = _problems(edit)
    assert line.startswith("pass[2]: input should be a valid dictionary") and line.endswith(
        "got 5")


def test_a_passes_case_problems_say_which_pass():
    """A pass's own case refused (config/schedule.py: _pass_problem): its pass.* keys under
    pass[k], the mesh rules (which depend on the pass's size) with "(in pass[k])"."""
    def thin_roll(d):
        d["pass"][1]["roll_radius"] = 0.001
    assert _problems(thin_roll) == [
        "pass[2].roll_radius: must exceed the draft per side (entry - exit)/2 = 0.0075 m, "
        "otherwise the roll cannot bite the plate; allowed: roll_radius > 0.0075 m, got 0.001 m"]

    def coarse(d):
        d["mesh"]["h_contact"] = 0.05
    lines = _problems(coarse)
    assert [line.endswith("(in pass[1])") for line in lines] == [True, True, False, False]
    assert [line.endswith("(in pass[2])") for line in lines] == [False, False, True, True]
    assert lines[0] == ("mesh.h_contact: must be < contact_length/4 = 0.0192029 m, got 0.05 m "
                        "(in pass[1])")
