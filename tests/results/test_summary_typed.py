"""The typed summary (hotroll/results/summary.py): every key summary.json holds is declared
once with its unit. The summaries are those the code wrote before the re-cut (commit 88591b2,
tests/data/before_recut: an isothermal pass, a thermal pass, a schedule pass with a width), an
independent record of which keys a run writes and with which units."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from hotroll.results.run_dir import RunDir
from hotroll.results.summary import ABSENT, Summary, summary_keys_markdown
from hotroll.results.units import UNITS

BEFORE = Path(__file__).resolve().parents[1] / "data" / "before_recut"
WRITTEN = sorted(BEFORE.rglob("summary.json"))
pytestmark = pytest.mark.mutation


@pytest.mark.parametrize("path", WRITTEN, ids=lambda p: p.parent.name)
def test_every_written_key_is_declared_with_the_unit_it_was_written_with(path):
    data = json.loads(path.read_text())
    s = Summary.from_dict(data)                       # strict: no undeclared, none missing
    assert s.to_dict() == data                        # the same keys and values back
    assert {k: u for k, u in Summary.units_map().items() if k in data} == data["units"]
    assert s.roll_force == data["roll_force"] == s["roll_force"]


def test_conditional_keys_are_absent_not_null():
    """Thermal figures only with [thermal], whole-width ones only with a width."""
    runs = {p.parent.name: json.loads(p.read_text()) for p in WRITTEN}
    iso, thermal, width = runs["2"], runs["hot_strip_finishing_thermal"], runs["02_F2"]
    assert "exit_temperature_mean" not in Summary.from_dict(iso)
    assert Summary.from_dict(iso).get("exit_temperature_mean", "none") == "none"
    assert Summary.from_dict(iso).exit_temperature_mean is ABSENT
    assert Summary.from_dict(thermal)["exit_temperature_mean"] > 273.15
    assert "roll_force_total" not in Summary.from_dict(iso)
    s = Summary.from_dict(width)
    assert s["roll_force_total"] == pytest.approx(s["roll_force"] * s["width"], rel=1e-12)


def test_a_typo_or_a_missing_key_is_refused_by_name():
    """The message names the key and where keys are declared (written out here)."""
    data = json.loads(WRITTEN[0].read_text())
    with pytest.raises(ValueError, match="roll_forc") as typo:
        Summary.from_dict({**data, "roll_forc": 1.0})
    assert str(typo.value) == ("summary: undeclared keys ['roll_forc'], missing keys [] "
                               "(hotroll/results/summary.py declares each key)")
    del data["roll_torque"]
    with pytest.raises(ValueError, match="roll_torque"):
        Summary.from_dict(data)


def test_reading_keeps_what_another_version_wrote(tmp_path):
    data = json.loads(WRITTEN[0].read_text())
    del data["roll_torque"]
    data["a_future_key"] = 3.0
    (tmp_path / "summary.json").write_text(json.dumps(data))
    s = RunDir(tmp_path).summary()
    assert s["a_future_key"] == 3.0 and "roll_torque" not in s
    assert dict(s) == data and isinstance(s, Summary)
    assert RunDir(tmp_path / "none").summary(strict=False) == {}


def test_units_table_and_reference_page_come_from_the_declaration():
    """One definition: the unit table holds the declared units; docs/reference/summary.md
    holds the generated table (run ``python scripts/reference_docs.py`` when it is stale)."""
    assert all(UNITS[k] == u for k, u in Summary.units_map().items())
    page = (Path(__file__).resolve().parents[2] / "docs" / "reference" / "summary.md").read_text()
    assert summary_keys_markdown() in page
    for key in Summary.keys_declared():
        assert f"| `{key}` |" in page


def test_a_run_writes_exactly_the_declared_keys(solved_example1):
    """The summary a run writes now (the suite's cached solved case) reads back strictly: no
    undeclared key, none missing, the units map that of the declaration."""
    data = json.loads((solved_example1 / "summary.json").read_text())
    s = Summary.from_dict(data)
    assert data["units"] == {k: u for k, u in Summary.units_map().items() if k in data}
    assert s.method == "steady" and s.exit_code == 0


def test_the_declaration_helpers_at_call_time():
    """What the class body and the page's module build at import, called again here (the
    mutation run cannot switch a mutant on before an import): a field's metadata and default,
    the labels and the page's groups by hand."""
    from hotroll.results.summary import _f

    f = _f("N", "a label", "a meaning", group="Pass", when="width")
    assert f.default is ABSENT
    assert dict(f.metadata) == {"unit": "N", "label": "a label", "meaning": "a meaning",
                                "group": "Pass", "when": "width"}
    labels = Summary.labels()
    assert labels["roll_force"] == "roll force, one roll" and labels["K"] == "consistency K"
    assert len(labels) == len(Summary.keys_declared())
    groups = Summary.groups()
    assert list(groups) == ["Pass", "Width and spread", "Temperature and heat", "Checks", "Solver"]
    assert groups["Width and spread"][:3] == ("exit_width", "spread", "edge_bulge")
    assert groups["Solver"] == ("h_contact", "dofs", "steps", "time", "dt", "newton_solves",
                                "coupling_updates", "nonlinear_iterations",
                                "iterations_per_step", "averaged_over_steps", "wall_time_s",
                                "gauge_solves")
    assert groups["Pass"][:3] == ("roll_force", "roll_force_total", "roll_torque")
    rows = {r[0]: r for r in Summary.reference_rows()}
    assert rows["roll_force_total"] == ("roll_force_total", "N", "roll force, whole width",
                                        "one roll's force over the whole width: "
                                        "`roll_force` x `width`, with `[spread]` the 3D "
                                        "pass's; with `[pass] width`")
    assert rows["spread"] == ("spread", "m", "spread", "exit width - `width`; with `[spread]` "
                              "(the 3D pass across the width)")
    assert rows["case_name"] == ("case_name", "", "case", "the case's name")
    assert "_other" not in rows
