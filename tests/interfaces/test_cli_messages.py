"""The command line's lines and exit codes around a run, with the runs faked (no FE): a
report that cannot be written for an OSError ends with exit code 1 (2 is bad input), a
schedule's failed pass is one unbroken line on stderr with the pass's exit code, and a study
with a [plot] names its figure's path."""
from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

import hotroll.cli.runs as runs
from hotroll.cli import app
from hotroll.examples import example_path
from hotroll.workflows.schedule import ScheduleError

runner = CliRunner()
SCHEDULE = Path(__file__).resolve().parents[1] / "data" / "two_pass_schedule.toml"


def test_a_report_that_cannot_be_written_ends_with_exit_code_1(tmp_path, monkeypatch):
    import hotroll.results.report as report

    d = tmp_path / "run"
    d.mkdir()
    (d / "summary.json").write_text(json.dumps({"case_name": "hand", "exit_code": 0,
                                                "roll_force": 1e6}))

    def refuse(directory):
        raise PermissionError(13, "Permission denied", str(directory / "report.html"))

    monkeypatch.setattr(report, "write_report", refuse)
    result = runner.invoke(app, ["report", str(d)])
    assert result.exit_code == 1
    assert f"report: {d}: [Errno 13] Permission denied" in " ".join(result.output.split())


def test_a_failed_pass_is_one_line_with_its_exit_code(tmp_path, monkeypatch):
    def fail(sch, out, **kw):
        raise ScheduleError(1, "R2", {"exit_code": 3, "status": "max_iterations"})

    monkeypatch.setattr(runs, "run_schedule", fail)
    result = runner.invoke(app, ["schedule", str(SCHEDULE), "--out", str(tmp_path)])
    assert result.exit_code == 3
    assert ("pass 2 (R2) ended with exit code 3: failed (status max_iterations); the schedule "
            "stops there, the passes before it are written") in result.output.splitlines()


def test_a_study_with_a_plot_names_its_figure(tmp_path, monkeypatch):
    base = example_path("example1")
    (tmp_path / "s.toml").write_text(f'[base]\nfile = "{base}"\n[vary]\n"material.m" = [0.2]\n'
                                     '[plot]\nx = "material.m"\n')
    out = tmp_path / "out"

    def fake_run_study(st, base, out, **kw):
        out.mkdir(parents=True, exist_ok=True)
        (out / "study.png").write_bytes(b"\x89PNG")
        return [{"index": 0, "case": "m", "status": "done", "exit_code": 0, "reason": None}]

    monkeypatch.setattr(runs, "run_study", fake_run_study)
    monkeypatch.setattr(runs.console, "width", 1000)
    result = runner.invoke(app, ["study", str(tmp_path / "s.toml"), "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert f"figure {out / 'study.png'}" in result.output.splitlines()
