"""The command line tells the summary's one story (issue 51 follow-ups): the run's table prints
the neutral story in words (``neutral``: a point in degrees and radians, or none and the
sticking zone) and not its parts; a steady solve's progress prints its words alone and a time
step's progress no neutral angle of its own; the plausibility warnings a run went on with
(the summary's ``warnings``) are printed once each on stderr after the run, by ``run``,
``example``, ``sweep``, ``compare`` and ``schedule`` (stdout stays the csv or json table), and
``validate`` of a case lists them as ``# warning:`` comment lines after the derived line."""
from __future__ import annotations

import csv
import io
import json
import math
import subprocess
import sys

import pytest
from casebuild import EXAMPLE1_COARSE, build_case
from typer.testing import CliRunner

from hotroll.cli import app, passes, runs
from hotroll.config.case import case_from_toml
from hotroll.examples import example_path

#: The neutral story's parts the table printed before ``neutral`` told it in words.
PARTS = ("neutral_point", "neutral_angle", "neutral_angle_reason", "sticking_zone")

#: Two warnings as config/plausibility.py words them (the texts are the test's own).
NONDIM = ("material: the flow stress at the pass's estimated state is 1.79 Pa, below any "
          "metal's hot flow stress (100000 Pa): a nondimensional case")
COLD = ("plate.temperature: 1000 K (726.85 degC) is below 1073.15 K (800 degC), where steel is "
        "no longer austenite (Ghosh and Olson); if you meant 1000 degC, write \"1000 degC\"")


def _cli(*args: str):
    return CliRunner().invoke(app, [str(a) for a in args])


def _rows(text: str) -> dict[str, list[str]]:
    """A printed rich table's rows by their first cell."""
    rows = [[c.strip() for c in line.strip("│").split("│")]
            for line in text.splitlines() if line.startswith("│")]
    return {r[0]: r[1:] for r in rows}


def _warnings(text: str) -> list[str]:
    return [line for line in text.splitlines() if line.startswith("warning: ")]


# ------------------------------------------------------------------ the neutral story
STICKING = {"exit_code": 0, "status": "steady", "roll_force": 0.536,
            "neutral": "none: sticking zone from 22.11° to 1.881° (0.386 to 0.03284 rad)",
            "neutral_point": None, "neutral_angle": None, "sticking_zone": [0.386, 0.03284],
            "neutral_angle_reason": "the slip changes sign 10 times in the sticking zone",
            "neutral_angle_flux": 0.1}


@pytest.mark.parametrize("fmt", ["table", "json"])
def test_the_run_table_prints_the_neutral_story_not_its_parts(tmp_path, monkeypatch, fmt):
    """A sticking arc: one row ``neutral`` with the summary's words; no neutral angle, point,
    reason or zone of its own, nor the flux angle (not the neutral point)."""
    monkeypatch.setattr(passes, "run_case", lambda *a, **k: dict(STICKING))
    r = _cli("run", "thin_strip", "--out", tmp_path, "--format", fmt)
    assert r.exit_code == 0, r.output
    if fmt == "json":
        (table,) = json.loads(r.stdout)
        rows = {x["quantity"]: [x["value"], x["unit"]] for x in table["rows"]}
    else:
        rows = _rows(r.stdout)
    assert rows["neutral"][0] == STICKING["neutral"]
    assert not set(PARTS) & set(rows) and "neutral_angle_flux" not in rows
    assert "roll_force" in rows


def test_the_sweep_table_has_the_neutral_story(tmp_path, monkeypatch):
    """sweep.csv: ``neutral`` beside ``neutral_angle`` (empty where no point is neutral)."""
    monkeypatch.setattr(passes, "_Progress", lambda **k: None)
    monkeypatch.setattr(passes, "run_case", lambda *a, **k: dict(STICKING))
    r = _cli("sweep", "example1", "--param", "material.m", "--values", "0.2",
             "--out", tmp_path)
    assert r.exit_code == 0, r.output
    (row,) = csv.DictReader(io.StringIO((tmp_path / "sweep.csv").read_text()))
    assert row["neutral"] == STICKING["neutral"] and row["neutral_angle"] == ""


# ------------------------------------------------------------------ progress
def test_a_steady_report_prints_its_words_alone(monkeypatch):
    """The steady solver's report (results only in ``message`` of PROGRESS_KEYS): the words,
    no ``message=``; a plain line with a message keeps its step."""
    lines = []
    monkeypatch.setattr(passes.console, "print", lambda text, **k: lines.append(str(text)))
    p = passes._Progress(every=0.0)
    words = ("Newton solve 1 at m = 0.2: converged after 21 iterations, residual norm "
             "1.19e-09, last update 5.21e-06 of the roll speed")
    p({"stage": "newton", "newton_solve": 1, "newton_iterations": 21,
       "newton_residual": 1.19e-9, "newton_converged": True, "message": words})
    p({"step": 3, "message": "mesh refined"})
    assert lines == ["  " + words, "  step=3  message=mesh refined"]


def test_a_time_steps_progress_tells_no_neutral_angle(monkeypatch):
    """A time step's line: its figures, not the step's own neutral angle (noise on a
    sticking arc; the run's story is the summary's ``neutral``)."""
    lines = []
    monkeypatch.setattr(passes.console, "print", lambda text, **k: lines.append(str(text)))
    passes._Progress(every=0.0)({"step": 7, "time": 0.0123, "roll_force": 2.5e6,
                                 "neutral_angle": 0.0421, "forward_slip": 0.037})
    (line,) = lines
    assert "step=7" in line and "roll_force=2.5e+06 N/m" in line and "forward_slip=0.037" in line
    assert "neutral" not in line and "0.0421" not in line


# ------------------------------------------------------------------ warnings after a run
def test_a_run_prints_its_warnings_on_stderr_after_the_table(tmp_path, monkeypatch):
    monkeypatch.setattr(passes, "run_case",
                        lambda *a, **k: {**STICKING, "warnings": [NONDIM, COLD]})
    r = _cli("run", "thin_strip", "--out", tmp_path)
    assert r.exit_code == 0, r.output
    assert _warnings(r.stderr) == [f"warning: {NONDIM}", f"warning: {COLD}"]
    assert "warning:" not in r.stdout
    assert r.output.index("warning: ") > r.output.index("│ roll_force")     # after the run


@pytest.mark.parametrize("fmt", ["csv", "json"])
def test_with_csv_or_json_the_warnings_go_to_stderr_only(tmp_path, monkeypatch, fmt):
    monkeypatch.setattr(passes, "run_case", lambda *a, **k: {**STICKING, "warnings": [NONDIM]})
    r = _cli("example", "1", "--out", tmp_path, "--format", fmt)
    assert r.exit_code == 0, r.output
    assert _warnings(r.stderr) == [f"warning: {NONDIM}"]
    assert "warning:" not in r.stdout
    if fmt == "json":
        (table,) = json.loads(r.stdout)
        assert {x["quantity"] for x in table["rows"]} >= {"neutral", "roll_force"}
    else:
        assert {x["quantity"] for x in csv.DictReader(io.StringIO(r.stdout))} >= {"neutral"}


def test_a_sweep_prints_each_warning_once(tmp_path, monkeypatch):
    """Three runs with the same warning: printed once, after the last run; a warning of one
    run names it."""
    seen = []

    def run_case(case, out, **k):
        seen.append(case.name)
        return {**STICKING, "warnings": [NONDIM] + ([COLD] if len(seen) == 2 else [])}

    monkeypatch.setattr(passes, "_Progress", lambda **k: None)
    monkeypatch.setattr(passes, "run_case", run_case)
    r = _cli("sweep", "example1", "--param", "material.m", "--values", "0.1,0.2,0.3",
             "--out", tmp_path)
    assert r.exit_code == 0, r.output
    assert _warnings(r.stderr) == [f"warning: {NONDIM}",
                                   f"warning: {COLD} (example1 material.m=0.2)"]
    assert seen[1] == "example1 material.m=0.2"


def test_a_schedule_prints_its_passes_warnings_once_with_the_passes(tmp_path, monkeypatch):
    """The passes' summaries (OUT/<case>/summary.json) read back: a warning of every pass once,
    one of some passes with their names; the table on stdout untouched."""
    from hotroll.config.schedule import load_schedule
    from hotroll.examples import schedule_path

    sch = load_schedule(schedule_path("finishing_mill"))
    names = [sch.pass_name(k) for k in range(2)]
    rows = []
    for k, name in enumerate(names):
        d = tmp_path / f"0{k + 1}_{name}"
        d.mkdir()
        warnings = [NONDIM] + ([COLD] if k == 1 else [])
        (d / "summary.json").write_text(json.dumps({"warnings": warnings}))
        rows.append({"name": name, "case": d.name, "entry_thickness": 0.03,
                     "exit_thickness": 0.02, "roll_surface_speed": 1.0, "roll_force": 1e7,
                     "roll_torque": 2e5, "exit_temperature_mean": 1300.0,
                     "exit_strain_mean": 0.4, "fe_solves": 1, "wall_time": 1.0})
    monkeypatch.setattr(runs, "load_schedule", lambda f: sch)
    monkeypatch.setattr(runs, "run_schedule", lambda *a, **k: rows)
    for fmt in ("table", "csv"):
        r = _cli("schedule", "finishing_mill", "--out", tmp_path, "--format", fmt)
        assert r.exit_code == 0, r.output
        assert _warnings(r.stderr) == [f"warning: {NONDIM}", f"warning: {COLD} ({names[1]})"]
        assert "warning:" not in r.stdout


def test_a_failed_schedule_prints_the_warnings_of_its_passes(tmp_path, monkeypatch):
    from hotroll.config.schedule import load_schedule
    from hotroll.examples import schedule_path
    from hotroll.workflows.schedule import ScheduleError

    sch = load_schedule(schedule_path("finishing_mill"))

    def fail(*a, **k):
        raise ScheduleError(0, "x", {"exit_code": 4, "status": "unsettled",
                                     "warnings": [COLD]})

    monkeypatch.setattr(runs, "load_schedule", lambda f: sch)
    monkeypatch.setattr(runs, "run_schedule", fail)
    r = _cli("schedule", "finishing_mill", "--out", tmp_path)
    assert r.exit_code == 4, r.output
    assert _warnings(r.stderr) == [f"warning: {COLD}"]


def test_compare_prints_the_fe_runs_warnings(tmp_path, monkeypatch):
    def fake_compare(case, out, progress=None):
        (out / "fe").mkdir(parents=True)
        (out / "fe" / "summary.json").write_text(json.dumps({"warnings": [NONDIM]}))
        return {"rows": []}

    monkeypatch.setattr(passes, "run_compare", fake_compare)
    r = _cli("compare", "example1", "--out", tmp_path)
    assert r.exit_code == 0, r.output
    assert _warnings(r.stderr) == [f"warning: {NONDIM}"]


# ------------------------------------------------------------------ validate
def _after_derived(text: str) -> list[str]:
    lines = text.splitlines()
    k = next(i for i, line in enumerate(lines) if line.startswith("# derived: "))
    return lines[k + 1:]


def test_validate_example1_lists_its_nondimensional_warning():
    """Example 1 (K = 1 Pa): the nondimensional warning as a comment after the derived line;
    the output still the case as TOML."""
    r = _cli("validate", "example1")
    assert r.exit_code == 0, r.output
    after = _after_derived(r.stdout)
    assert len(after) == 1 and after[0].startswith(f"# warning: {NONDIM}"), after
    assert case_from_toml(r.stdout).name == "example1"


def test_validate_a_steel_at_1000_kelvin_asks_for_degc(tmp_path):
    """hot_strip_finishing (S355J2) given plate.temperature = 1000: 1000 K is 726.85 degC
    (1000 - 273.15, by hand), below 800 degC = 1073.15 K: the warning says to write
    "1000 degC"."""
    text = example_path("hot_strip_finishing").read_text()
    lines = [("temperature = 1000" if line.startswith("temperature =") else line)
             for line in text.splitlines()]
    assert lines != text.splitlines()
    case = tmp_path / "cold.toml"
    case.write_text("\n".join(lines) + "\n")
    r = _cli("validate", case)
    assert r.exit_code == 0, r.output
    after = _after_derived(r.stdout)
    assert f"# warning: {COLD}" in after, after
    assert all(line.startswith("# warning: ") for line in after)
    assert case_from_toml(r.stdout).plate.temperature == 1000.0


# ------------------------------------------------------------------ a real run
def test_a_real_example1_run_tells_the_story_and_warns_once(tmp_path):
    """``hotroll run`` of the coarse Example 1 (a_f = 5: a neutral point), stdout a pipe:
    the ``neutral`` row is the summary's angle in degrees and radians (formatted here from
    summary.json's ``neutral_angle``), no part of the story has a row of its own, the steady
    solve's progress lines are words (no ``message=``), and the nondimensional warning (K = 1
    Pa) is on stderr once, after the table."""
    case = tmp_path / "ex1.toml"
    case.write_text(build_case(EXAMPLE1_COARSE).to_toml())
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "hotroll.cli", "run", str(case), "--out",
                           str(out)], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    summary = json.loads((out / "summary.json").read_text())
    ang = summary["neutral_angle"]
    rows = _rows(proc.stdout)
    assert rows["neutral"][0].startswith(f"{math.degrees(ang):.4g}° ({ang:.4g} rad)")
    assert rows["neutral"][0] == summary["neutral"]
    assert not set(PARTS) & set(rows)
    assert "message=" not in proc.stdout and "  Newton solve 1 at m = 0.2: " in proc.stdout
    (warning,) = _warnings(proc.stderr)
    assert warning.startswith(f"warning: {NONDIM}")
    assert summary["warnings"] == [warning.removeprefix("warning: ")]
