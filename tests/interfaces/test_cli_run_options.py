"""``hotroll run``'s options reach the case, and its lines reach the reader, with the run
faked (no FE): --force sets solver.force, --method the solver's method (steady: example1 is
transient); the line naming the run and its output directory comes first and the run's
progress messages are printed."""
from __future__ import annotations

import pytest
from typer.testing import CliRunner

from hotroll.cli import app, passes
from hotroll.examples import example_path

runner = CliRunner()


@pytest.fixture
def fake_runs(monkeypatch):
    calls = []

    def run_case(case, out, *, resume=True, progress=None, sweep=None):
        calls.append(case)
        if progress is not None:
            progress({"step": 1, "message": "mesh refined"})
        return {"roll_force": 1.25, "converged": True, "steps": 3, "exit_code": 0}

    monkeypatch.setattr(passes, "run_case", run_case)
    monkeypatch.setattr(passes.console, "width", 300)        # rich: no line wrapped
    return calls


def test_force_and_method_reach_the_case(tmp_path, fake_runs):
    result = runner.invoke(app, ["run", str(example_path("example1")), "--out", str(tmp_path),
                                 "--force", "--method", "steady", "--no-resume"])
    assert result.exit_code == 0, result.output
    case, = fake_runs
    assert case.solver.force is True and case.solver.method == "steady"


def test_the_run_is_announced_and_its_progress_printed(tmp_path, fake_runs):
    result = runner.invoke(app, ["run", str(example_path("example1")), "--out", str(tmp_path),
                                 "--no-resume"])
    assert result.exit_code == 0, result.output
    lines = result.output.splitlines()
    assert lines[0].startswith(f"running example1 -> {tmp_path} (")
    assert any("message=mesh refined" in line for line in lines)
