"""A study's page writes each case's own page first, without drawing figures for it
(results/report.py's write_report: "figures not drawn"; a case page draws only when written
on its own): the figure drawing is spied on and never called, the case's page is written
and linked."""
from __future__ import annotations

import json

from hotroll.results import report


def test_a_studys_case_pages_are_written_without_drawn_figures(tmp_path, monkeypatch):
    d = tmp_path / "study"
    (d / "cases" / "m0.2").mkdir(parents=True)
    (d / "study.csv").write_text("index,case,material.m,status,exit_code,reason,roll_force\n"
                                 "0,m0.2,0.2,done,0,,1000000.0\n")
    (d / "cases" / "m0.2" / "summary.json").write_text(json.dumps(
        {"case_name": "m0.2", "status": "steady", "exit_code": 0, "converged": True,
         "roll_force": 1e6, "units": {"roll_force": "N/m"}}))
    drawn = []
    monkeypatch.setattr(report, "_drawn", lambda run_dir, names: drawn.append(run_dir) or [])
    report.write_report(d)
    assert drawn == []
    assert (d / "cases" / "m0.2" / "report.html").is_file()
    assert 'href="cases/m0.2/report.html"' in (d / "report.html").read_text()
    report.write_report(d / "cases" / "m0.2")           # on its own it draws
    assert drawn == [d / "cases" / "m0.2"]
