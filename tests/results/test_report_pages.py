"""The report's pages from hand-written output directories (no solve, a few ms each): what a
reader of the page must see, checked against the files written here (summary.json,
schedule.json, study.csv, compare.json, case.toml) and the conversions worked out by hand;
the comparison's Markdown (compare.md) from a hand-written result; ``hotroll report --open``
without a browser and the study's page that cannot be written. The pages of real runs and
studies are tests/results/test_report.py."""
from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace

from typer.testing import CliRunner

from hotroll.results import report, report_run, report_table
from hotroll.results.compare_table import COLUMNS, law_text, md_text

#: A settled, converged run's summary (the figures a page shows first), SI units.
SETTLED = {"case_name": "hand", "status": "steady", "exit_code": 0, "converged": True,
           "steady_state": True, "roll_force": 2.5e6, "roll_torque": 1.2e5,
           "forward_slip": 0.05, "units": {"roll_force": "N/m", "roll_torque": "N m/m"}}


def _write(path: Path, data) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data) if not isinstance(data, str) else data)
    return path


def _flat(text: str) -> str:
    """Printed text with the console's line breaks undone."""
    return " ".join(text.split())


# ------------------------------------------------------------------------------ run page
def test_warnings_of_a_run_that_did_not_settle_or_converge():
    """The texts a reader gets for each failure, written out here: an unsettled fixed point
    (with its last move when the summary has it, nothing after it when not), a run that did
    not converge (its status and exit code), one unconverged step of the averaging window."""
    base = {"roll_force": 1e6}
    assert report_run.run_warnings({**base, "fixed_point_settled": False}) == [
        {"level": "error", "text": "free surface not settled: the steady solver's "
                                   "free-surface/a_f fixed point did not settle"}]
    assert report_run.run_warnings({**base, "fixed_point_settled": False,
                                    "surface_residual_h": 0.0123})[0]["text"].endswith(
        "did not settle (last move 0.0123 h)")
    assert report_run.run_warnings({**base, "converged": False, "status": "max_iterations",
                                    "exit_code": 3}) == [
        {"level": "error", "text": "not converged (status 'max_iterations', exit code 3)"}]
    assert report_run.run_warnings({**base, "unconverged_steps_in_window": 1}) == [
        {"level": "warn", "text": "1 step(s) of the averaging window did not converge (left "
                                  "out of the means)"}]
    assert report_run.run_warnings({**base, "unconverged_steps_in_window": 0}) == []


def test_shown_values_in_the_engineers_unit():
    """1273.15 K is 1000 degC (minus 273.15 by hand); a length below 1 m in mm (0.0995 m =
    99.5 mm), one of 1.5 m stays in m; the SI value beside it unchanged."""
    t = report_run.show("exit_temperature_mean", 1273.15, "K")
    assert (t["text"], t["unit"], t["si"], t["si_unit"]) == ("1000", "°C", "1273.15", "K")
    short = report_run.show("contact_length", 0.0995, "m")
    assert (short["text"], short["unit"]) == ("99.5", "mm")
    long = report_run.show("contact_length", 1.5, "m")
    assert (long["text"], long["unit"]) == ("1.5", "m")


def test_summary_groups_leave_the_material_out_and_put_the_rest_under_other():
    """The material's K and m are inputs (the case's table shows them), not results: not in
    any group; a number of no declared group is listed under "Other" (the module's rule)."""
    s = {"roll_force": 1e6, "K": 1.0, "m": 0.2, "odd_figure": 2.5, "units": {}}
    groups = dict(report_run.summary_groups(s))
    assert list(groups) == ["Pass", "Other"]
    assert [r["key"] for r in groups["Other"]] == ["odd_figure"]
    assert [r["key"] for r in groups["Pass"]] == ["roll_force"]


def test_run_page_headline_facts_and_inputs(tmp_path):
    """A run directory written here: the headline starts with the roll force in MN/m (2.5e6
    N/m), the facts say the run had a temperature field, and the case file's description
    loses its "(omit: ...)" prefix (what omitting the key means is not what it is)."""
    d = tmp_path / "run"
    _write(d / "summary.json", {**SETTLED, "thermal": True})
    _write(d / "case.toml", 'name = "hand"\n[friction]\n'
           "a_f = 5.0     # (omit: estimate) viscoplastic friction coefficient [-]; "
           "allowed: > 0\n")
    ctx = report_run.run_context(d)
    assert [(r["key"], r["text"], r["unit"]) for r in ctx["headline"][:1]] == [
        ("roll_force", "2.5", "MN/m")]
    assert ("thermal", "yes") in ctx["facts"]
    (sec, rows), = ctx["inputs"]
    assert sec == "friction" and rows == [{"key": "a_f", "value": "5", "num": True, "unit": "-",
                                          "text": "viscoplastic friction coefficient"}]
    assert ctx["ok"] and ctx["warnings"] == []


def test_slab_table_notes_and_a_compare_file_without_columns(tmp_path):
    """compare.json's regimes note reaches the page; a compare.json without a column list
    (another version's) gives a table of no number columns, not a failure."""
    _write(tmp_path / "compare.json", {
        "rows": [{"quantity": "roll force per unit width [N/m]", "unit": "N/m", "FE": 1e6,
                  "slab (Orowan)": 0.9e6, "FE/slab": 1.1111}],
        "regimes": "Sims for thin strips", "slab_friction": "sticking"})
    c = report_run.compare_context(tmp_path)
    assert c["columns"] == [] and c["rows"][0]["cells"] == []
    assert c["rows"][0]["quantity"] == "roll force per unit width"
    assert c["regimes"] == "Sims for thin strips" and c["friction"] == "sticking"
    assert c["force_ratio"] == "1.111"


def test_unit_markup():
    """A unit for HTML: the exponent raised, "-" the dimensionless dash, no unit nothing."""
    assert str(report._unit("m^2/s")) == "m<sup>2</sup>/s"
    assert 'class="dimless"' in str(report._unit("-"))
    assert str(report._unit("")) == "" and str(report._unit(None)) == ""


# ------------------------------------------------------------------------- schedule page
def _schedule(d: Path) -> Path:
    """Two passes of 1.2 m wide strip: R1 converged with its own report, R2 not converged."""
    passes = [{"pass": 1, "name": "R1", "case": "01_R1", "entry_thickness": 0.1,
               "exit_thickness": 0.08, "roll_force": 4e6, "roll_torque": 1e5,
               "roll_force_total": 4.8e6, "roll_torque_total": 1.2e5, "fe_solves": 3,
               "wall_time": 2.0},
              {"pass": 2, "name": "R2", "case": "02_R2", "entry_thickness": 0.08,
               "exit_thickness": 0.065, "roll_force": 5e6, "roll_torque": 1.1e5,
               "roll_force_total": 6e6, "roll_torque_total": 1.32e5, "fe_solves": 4,
               "wall_time": 3.0}]
    _write(d / "schedule.json", {"name": "two", "passes": passes, "wall_time": 5.0,
                                 "fe_solves": 7, "units": {"roll_force_total": "N",
                                                           "roll_torque_total": "N m"}})
    _write(d / "01_R1" / "summary.json", SETTLED)
    _write(d / "01_R1" / "report.html", "<html></html>")
    _write(d / "02_R2" / "summary.json", {**SETTLED, "converged": False, "exit_code": 3,
                                          "status": "max_iterations"})
    (d / "schedule.png").write_bytes(b"\x89PNG")
    return d


def test_schedule_page(tmp_path):
    """A schedule's page from schedule.json and its passes' summaries: the whole width's
    force and torque replace the per-width ones (headed "roll force", "roll torque"); the
    pass that did not converge is a failed row and a warning naming it; the converged pass
    links to its own report; the status counts passes and FE solves; the schedule's plot."""
    d = _schedule(tmp_path / "sch")
    assert report.kind(d) == "schedule"
    ctx = report_table.schedule_context(d)
    assert [c["key"] for c in ctx["columns"]] == ["entry_thickness", "exit_thickness",
                                                 "roll_force_total", "roll_torque_total",
                                                 "fe_solves", "wall_time"]
    assert [c["label"] for c in ctx["columns"]][2:4] == ["roll force", "roll torque"]
    assert ctx["status"] == "2 passes, 7 FE solves" and not ctx["ok"]
    assert [(t["case"], t["status"], t["failed"], t["link"]) for t in ctx["table"]] == [
        ("R1", "ok", False, "01_R1/report.html"), ("R2", "warnings", True, None)]
    assert ctx["warnings"] == [{"level": "error", "text": "pass R2: not converged (status "
                                                          "'max_iterations', exit code 3)"}]
    assert ctx["figures"] == [("The schedule pass by pass", d / "schedule.png")]
    page = _flat(report.render(report.context(d)))
    assert "pass R2: not converged (status &#39;max_iterations&#39;, exit code 3)" in page
    assert '<a href="01_R1/report.html">R1</a>' in page


# ---------------------------------------------------------------------------- study page
def test_study_page_of_an_unfinished_study(tmp_path):
    """A study still running (study.csv has cases 0 and 2; study.json, as written at the
    start, has the varied key's unit only): the rows keep study.csv's numbers, the
    iterations column is dimensionless ("-", results/units.py's rule for counts), and the
    study's own contact-profile figure is on the page with its caption."""
    d = tmp_path / "study"
    _write(d / "study.csv", "index,case,material.m,status,exit_code,reason,nonlinear_iterations\n"
                            "0,m0.15,0.15,done,0,,12\n"
                            "2,m0.35,0.35,bad_input,2,too large,\n")
    _write(d / "study.json", {"name": "m", "varied": ["material.m"],
                              "units": {"material.m": "-"}})
    (d / "study_profiles.png").write_bytes(b"\x89PNG")
    ctx = report_table.study_context(d)
    assert [t["index"] for t in ctx["table"]] == [0, 2]
    assert "#2" in ctx["warnings"][0]["text"]
    cols = {c["key"]: c for c in ctx["columns"]}
    assert cols["nonlinear_iterations"]["unit"] == "-"
    assert cols["nonlinear_iterations"]["cells"] == ["12", "-"]
    caps = [cap for cap, _ in report.context(d)["figures"]]
    assert caps == ["Contact profiles of the cases"]


# ------------------------------------------------------------------------- compare.md text
def _result(**errors) -> dict:
    row = {"quantity": "roll force per unit width", "unit": "N/m", "FE": 1e6,
           "slab (Orowan)": 9e5, "Sims": None, "Ford-Alexander": None, "FE/slab": 1.1111,
           "note": ""}
    inputs = {"roll_radius_m": 0.6, "h0_m (full)": 0.5, "h1_m (full)": 0.4,
              "roll_speed_m_per_s (omega R)": 0.6283, "back_tension_Pa": 0.0,
              "front_tension_Pa": 0.0, "flow_stress": {"law": "norton-hoff", "K": 1.0},
              "temperature_K": 1273.0, "entry_strain": 0.0}
    return {"rows": [row], "inputs": inputs, "slab_error": None, "slab_friction": "sticking",
            "fe": {"method": "steady", "status": "steady", "converged": True,
                   "h_contact": 0.02}, **errors}


def test_compare_md_table_errors_and_definitions():
    """compare.md: a Markdown table whose head is the columns between bars, a theory that
    could not be evaluated named with its reason, the definitions under their heading."""
    text = md_text(SimpleNamespace(name="ex1"), _result(sims_error="L/h too small"))
    lines = text.splitlines()
    head = lines.index("| " + " | ".join(COLUMNS) + " |")
    assert lines[head + 1] == "|" + "---|" * len(COLUMNS)
    assert lines[head + 2] == "| roll force per unit width | N/m | 1.0000e+06 | 9.0000e+05 | - | - | 1.111 |  |"
    assert "**sims not evaluated:** L/h too small" in lines
    assert "## Definitions (checked in the code)" in lines
    assert "not evaluated" not in md_text(SimpleNamespace(name="ex1"), _result())


def test_law_text_leaves_out_validity_and_units():
    """The law's parameters as key = value, without its validity ranges and units tables."""
    law = {"law": "hensel-spittel", "A": 1e8, "validity": {"temperature": [900, 1300]},
           "units": {"A": "Pa"}}
    assert law_text(law) == "law = hensel-spittel, A = 100000000.0"
    assert law_text("norton-hoff") == "norton-hoff"


# ------------------------------------------------------------------------- command line
def test_report_open_without_a_browser(tmp_path, monkeypatch):
    """``hotroll report DIR --open`` where no browser opens: the page is written and the
    user told to open it; with a browser nothing more is said."""
    import webbrowser

    from hotroll.cli import app

    d = tmp_path / "run"
    _write(d / "summary.json", SETTLED)
    opened = []
    monkeypatch.setattr(webbrowser, "open", lambda uri: opened.append(uri) or False)
    res = CliRunner().invoke(app, ["report", str(d), "--open"])
    assert res.exit_code == 0, res.output
    assert opened == [(d / "report.html").resolve().as_uri()]
    assert res.output.splitlines()[-1] == "no web browser found: open the file yourself"
    monkeypatch.setattr(webbrowser, "open", lambda uri: True)
    res = CliRunner().invoke(app, ["report", str(d), "--open"])
    assert res.exit_code == 0 and "no web browser" not in res.output


def test_study_report_that_cannot_be_written_names_the_error(tmp_path, capsys):
    """The study's page at the end of ``hotroll study`` on a directory with no study.csv: the
    study goes on, the message names the error's type and text."""
    from hotroll.cli.report import study_report

    study_report(tmp_path, "t")
    out = _flat(capsys.readouterr().out)
    assert "report: not written (ReportError: report:" in out
    assert "is not a hotroll output directory" in out
    assert not (tmp_path / "report.html").exists()


def test_the_cases_plausibility_warnings_are_on_the_page_and_its_inputs_read_units(tmp_path):
    """The summary's ``warnings`` (config/plausibility.py) are listed on the run page, each as
    it is; a case.toml line whose comment leads with the engineer's unit ("= 350 mm; ...")
    keeps its description and SI unit."""
    text = ("plate.temperature: 1000 K (726.85 degC) is below 1073.15 K (800 degC), where steel "
            "is no longer austenite (Ghosh and Olson); if you meant 1000 degC, write "
            "\"1000 degC\"")
    assert {"level": "warn", "text": text} in report_run.run_warnings(
        {"roll_force": 1e6, "warnings": [text]})
    d = tmp_path / "run"
    _write(d / "summary.json", {**SETTLED, "warnings": [text]})
    _write(d / "case.toml", 'name = "hand"\n[pass]\n'
           "roll_radius = 0.35     # = 350 mm; roll radius R [m]; allowed: > 0 and <= 1000\n")
    ctx = report_run.run_context(d)
    (sec, rows), = ctx["inputs"]
    assert rows == [{"key": "roll_radius", "value": "0.35", "num": True, "unit": "m",
                     "text": "roll radius R"}]
    assert text in [w["text"] for w in ctx["warnings"]]
