"""A study's rows from faked runs (workflows/study.py, no FE): a case refused by the memory
estimate is "too_large" with exit code 8 (results/outcome.py's EXIT_CODES: 8 too large, 9 disk
full), a summary's own name is not a column (the row's "case" is its label), and a schedule
case's row: rolled with its finished passes read back (resume), "done" with exit code 0, the
last pass's exit strain and the totals over its passes; a case the cluster gave up on is an
error row under its label."""
from __future__ import annotations

import tomllib
from pathlib import Path

from casebuild import build_case, example1_coarse

import hotroll.workflows.study as study
from hotroll.results.outcome import EXIT_CODES
from hotroll.workflows.estimate import ResourceError

SCHEDULE = Path(__file__).resolve().parents[1] / "data" / "two_pass_schedule.toml"


def _items():
    cases = [build_case(example1_coarse(f"c{i}"), **{"mesh.h_contact": h})
             for i, h in enumerate((0.02, 0.03))]
    return [{"index": i, "label": c.name, "values": {"mesh.h_contact": h}, "case": c.to_dict()}
            for i, (c, h) in enumerate(zip(cases, (0.02, 0.03)))]


def test_a_refused_case_is_too_large_and_a_summarys_name_is_not_a_column(tmp_path, monkeypatch):
    def fake_run_case(case, out, *, resume, sweep):
        if case.name == "c1":
            raise ResourceError("mesh.h_contact: 1 GB over the limit")
        return {"case_name": case.name, "exit_code": 0, "status": "steady", "roll_force": 1.0}

    monkeypatch.setattr(study, "run_case", fake_run_case)
    rows = study.run_group(_items(), str(tmp_path), False)
    assert "case_name" not in rows[0] and rows[0]["case"] == "c0" and rows[0]["roll_force"] == 1.0
    assert (rows[1]["status"], rows[1]["exit_code"], rows[1]["reason"]) == (
        "too_large", 8, "mesh.h_contact: 1 GB over the limit")
    assert EXIT_CODES[8].startswith("too large")


def test_a_schedule_cases_row_is_its_last_pass_and_its_totals(tmp_path, monkeypatch):
    calls = []

    def fake_run_schedule(sch, out, *, resume, figure):
        calls.append((resume, figure))
        return [{"name": "R1", "exit_thickness": 0.08, "exit_strain_mean": 0.2,
                 "roll_force": 4e6, "roll_power": 1e5, "fe_solves": 3, "wall_time": 2.0},
                {"name": "R2", "exit_thickness": 0.065, "exit_strain_mean": 0.45,
                 "roll_force": 5e6, "roll_power": 1.5e5, "fe_solves": 4, "wall_time": 3.0}]

    monkeypatch.setattr(study, "run_schedule", fake_run_schedule)
    row = study.run_schedule_item({"schedule": tomllib.loads(SCHEDULE.read_text())}, tmp_path)
    (resume, figure), = calls
    assert resume is True and not figure     # finished passes read back, no schedule figure
    assert (row["status"], row["exit_code"], row["reason"], row["resumed"]) == (
        "done", 0, None, False)
    assert (row["passes"], row["exit_thickness"], row["exit_strain_mean"]) == (2, 0.065, 0.45)
    assert (row["max_roll_force"], row["total_roll_power"], row["fe_solves"],
            row["wall_time_s"]) == (5e6, 2.5e5, 7, 5.0)
    assert row["R1.exit_strain_mean"] == 0.2 and row["R2.roll_force"] == 5e6


def test_a_case_the_cluster_gave_up_on_is_an_error_row_under_its_label():
    from hotroll.config.study import StudyCase

    c = StudyCase(3, "m0.25", {"material.m": 0.25}, None)
    row = study._lost(c, MemoryError("worker killed"))
    assert row == {"index": 3, "case": "m0.25", "material.m": 0.25, "status": "error",
                   "exit_code": 1, "reason": "the cluster gave up on its group: MemoryError: "
                                             "worker killed", "resumed": False}
