"""The report's words and numbers a reader gets, from hand-written summaries and run
directories (no solve, a few ms each): the facts, the contact's end, the warnings of the
checks, the inputs' units, compare.json's table and errors, the figures' captions, the
schedule's wall time and the study's figure axis. Each expected text is written out here
from the module's rules (the sample of issue 50 found these unpinned); the pages of real
runs are tests/results/test_report.py."""
from __future__ import annotations

import json
import math
from pathlib import Path

from hotroll.results import report_run, report_table


def _write(path: Path, data) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data) if not isinstance(data, str) else data)
    return path


def test_the_facts_are_the_summarys_words_and_yes_or_no():
    """Text fields as they are (method "steady", free surface "kinematic"), booleans as
    yes/no, in the module's order; a missing key is left out."""
    s = {"method": "steady", "converged": True, "free_surface": "kinematic",
         "thermal": False, "status": None}
    assert report_run._facts(s) == [("method", "steady"), ("converged", "yes"),
                                    ("free surface", "kinematic"), ("thermal", "no")]


def test_the_contact_ends_words_for_each_kind():
    """The recovery's sentence exactly; the held contact's with its pressure in MPa (2.5e6 Pa
    = 2.5 MPa); no kind, no words, even with a pressure."""
    assert report_run.contact_end_text({"contact_end_kind": "recovery"}) == (
        "the strip follows the rising roll past the gap while it recovers elastically; "
        "the contact ends where its pressure falls to zero")
    assert report_run.contact_end_text({"contact_end_kind": "held",
                                        "contact_end_pressure": 2.5e6}) == (
        "bilateral contact: the strip is held to the roll up to the gap; the pressure there "
        "is 2.5 MPa")
    assert report_run.contact_end_text({"contact_end_pressure": 2.5e6}) is None


def test_contact_loss_under_a_held_contact_says_how_to_let_it_go():
    """A tensile stretch (x = 0.01 .. 0.02 m) under bilateral contact: the warning names
    [contact] unilateral; without the held kind it does not."""
    s = {"roll_force": 1e6, "contact_loss": [[0.01, 0.02]]}
    loss = ("contact loss: the normal stress is tensile from x = 0.01 m to 0.02 m; the strip "
            "would leave the roll there")
    assert report_run.run_warnings(s)[0] == {"level": "warn", "text": loss}
    held = report_run.run_warnings({**s, "contact_end_kind": "held"})[0]
    assert held == {"level": "warn", "text": loss + " (bilateral contact holds it: [contact] "
                                                   "unilateral = true lets it go)"}


def test_a_check_above_its_limit_is_a_warning_with_both_in_percent():
    """mass_flux_error 0.025 against its limit 0.01: "2.5 % is above 1 %" (times 100 by
    hand), a warning."""
    w = report_run.run_warnings({"roll_force": 1e6, "mass_flux_error": 0.025})
    assert len(w) == 1 and w[0]["level"] == "warn"
    assert w[0]["text"].endswith(" 2.5 % is above 1 %")


def test_an_angle_is_in_degrees_only_when_its_unit_is_radians():
    """A key with "angle" in its name but a dimensionless unit keeps its value and unit."""
    assert report_run.scale("neutral_angle_share", "-", 0.5) == (1.0, 0.0, "-")
    assert report_run.scale("neutral_angle", "rad", 0.1) == (math.pi / 180.0, 0.0, "°")


def test_a_list_of_values_has_no_single_value():
    """show of two values: both as text, no single "value" to sort by."""
    r = report_run.show("roll_force", [1e6, 2e6], "N/m")
    assert (r["text"], r["unit"], r["value"]) == ("1, 2", "MN/m", "")
    assert report_run.show("roll_force", 1e6, "N/m")["value"] == "1000000.0"


def test_the_headline_shows_the_exit_temperature_in_celsius(tmp_path):
    """exit_temperature_mean 1273.15 K is on the headline as 1000 degC."""
    _write(tmp_path / "summary.json", {"case_name": "hand", "exit_code": 0, "converged": True,
                                       "roll_force": 1e6, "exit_temperature_mean": 1273.15,
                                       "units": {"exit_temperature_mean": "K"}})
    heads = {r["key"]: (r["text"], r["unit"]) for r in report_run.run_context(tmp_path)["headline"]
             if "key" in r}
    assert heads["exit_temperature_mean"] == ("1000", "°C")


def test_a_figure_without_a_caption_is_named_by_its_file(tmp_path):
    """fig_extra_plot.png (not one of plot_all's) is captioned "extra plot"."""
    (tmp_path / "fig_extra_plot.png").write_bytes(b"\x89PNG")
    assert report_run.run_figures(tmp_path) == [("extra plot", tmp_path / "fig_extra_plot.png")]


def test_case_inputs_units_of_numbers_and_of_words(tmp_path):
    """A number keeps its unit; a word keeps a real unit (a temperature written "1000 degC"
    is in K) but not the dimensionless "-"."""
    path = _write(tmp_path / "case.toml",
                  '[plate]\ntemperature = "1000 degC"   # entry temperature [K]\n'
                  'thickness = 0.02   # entry thickness [m]\n'
                  '[solver]\nmethod = "steady"   # the solver [-]\n')
    _, inputs = report_run.case_inputs(path)
    units = {(sec, r["key"]): r["unit"] for sec, rows in inputs for r in rows}
    assert units == {("plate", "temperature"): "K", ("plate", "thickness"): "m",
                     ("solver", "method"): ""}


def test_compare_table_ratio_column_errors_and_a_row_without_a_name(tmp_path):
    """compare.json's FE/slab column with three decimals (0.98765 -> 0.988, where the other
    columns' four digits would give 0.9877), each theory's error under its own name, and a
    row without a quantity named by the empty text."""
    _write(tmp_path / "compare.json", {
        "columns": ["quantity", "unit", "FE", "FE/slab", "note"],
        "rows": [{"quantity": "roll force per unit width [N/m]", "unit": "N/m",
                  "FE": 0.98765, "FE/slab": 0.98765},
                 {"unit": "N/m", "FE": 2.0}],
        "slab_error": "no solution", "sims_error": "too thick"})
    c = report_run.compare_context(tmp_path)
    assert c["rows"][0]["cells"] == ["0.9877", "0.988"]
    assert c["rows"][1]["quantity"] == ""
    assert c["errors"] == ["slab: no solution", "sims: too thick"]


def test_a_legend_value_in_its_columns_unit():
    """A varied temperature of 1273.15 K in a degC column is "1000 degC"; a word stays."""
    col = report_table.column("plate.temperature", [1273.15, 1373.15], "K")
    assert report_table._value(col, 1273.15) == "plate.temperature = 1000 °C"
    assert report_table._value(col, "hot") == "plate.temperature = hot"


def test_a_column_of_words_has_no_unit():
    """No number in the column: no unit shown, the words as cells."""
    col = report_table.column("friction.law", ["tresca", "coulomb"], "-")
    assert (col["unit"], col["cells"]) == ("", ["tresca", "coulomb"])
    assert report_table.column("roll_force", [1e6, None], "N/m")["unit"] == "MN/m"


def test_the_schedules_wall_time_is_schedule_json_s(tmp_path):
    """schedule.json's wall_time (12.5 s) reaches the page; NaN when it has none."""
    _write(tmp_path / "schedule.json", {"name": "one", "wall_time": 12.5, "passes": [
        {"pass": 1, "name": "R1", "entry_thickness": 0.1, "exit_thickness": 0.08}]})
    assert report_table.schedule_context(tmp_path)["wall_time"] == 12.5
    _write(tmp_path / "schedule.json", {"name": "one", "passes": []})
    assert math.isnan(report_table.schedule_context(tmp_path)["wall_time"])


def test_the_study_figure_is_drawn_against_the_first_numeric_varied_key(tmp_path):
    """Varied friction.law (words) and material.m (numbers): the figure's x is material.m."""
    _write(tmp_path / "study.csv",
           "index,case,friction.law,material.m,status,exit_code,reason,roll_force\n"
           "0,a,tresca,0.15,done,0,,1000000.0\n1,b,coulomb,0.25,done,0,,1100000.0\n")
    _write(tmp_path / "study.json", {"name": "s", "varied": ["friction.law", "material.m"],
                                     "units": {"material.m": "-"}})
    assert report_table.study_context(tmp_path)["figure_x"] == "material.m"


def test_a_long_input_grid_shows_its_length_and_ends():
    """[hand] an input list longer than 8 (a cross-section's eta grid) reads as its length,
    its first three values and its last; a table with such rows as its shape and first row;
    short lists and tables of pairs in full."""
    from hotroll.results.report_run import _input_text

    assert _input_text([0.0, 0.5, 1.0]) == "[0, 0.5, 1]"
    assert _input_text([float(i) for i in range(10)]) == "10 values: 0, 1, 2, ..., 9"
    rows = [[float(i)] * 9 for i in range(3)]
    assert _input_text(rows) == "3 rows of 9, the first: 9 values: 0, 0, 0, ..., 0"
    assert _input_text([[0.0, 1.0], [1.0, 2.0]]) == "2 points: (0, 1), (1, 2)"
