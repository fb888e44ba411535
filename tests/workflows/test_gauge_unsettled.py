"""A pass given by its roll gap whose exit thickness does not settle within the search's
budget (workflows/gauge.py, GAUGE_MAX_SOLVES cut to one solve here) ends "unsettled" with
exit code 5 ("not settled", results/outcome.py), not converged, the reason named: the soft
stand of tests/workflows/test_gauge_limits.py, which needs several solves."""
from __future__ import annotations

from casebuild import EXAMPLE1_COARSE

import hotroll.workflows.gauge as gauge
from hotroll.config.case import case_from_dict
from hotroll.results.outcome import EXIT_CODES
from hotroll.workflows.runner import run_case


def _gap_case(name: str, gap: float, modulus: float, exit_thickness: float):
    """Example 1's pass (coarse) on a stand of modulus M (N/m per m of width) set to ``gap``."""
    rigid = {k: v for k, v in EXAMPLE1_COARSE["pass"].items() if k != "exit_thickness"}
    return case_from_dict({**EXAMPLE1_COARSE, "name": name, "pass": {
        **rigid, "width": 1.0, "mill_modulus": modulus, "roll_gap": gap,
        "exit_thickness": exit_thickness}})


def test_a_gap_search_out_of_solves_is_unsettled_with_exit_code_5(tmp_path, monkeypatch):
    monkeypatch.setattr(gauge, "GAUGE_MAX_SOLVES", 1)
    s = run_case(_gap_case("tiny", 0.001, 1.2, 0.42), tmp_path / "tiny")
    assert (s["status"], s["exit_code"], s["converged"]) == ("unsettled", 5, False)
    assert EXIT_CODES[5] == "not settled"
    assert s["failure"].startswith("the exit thickness did not settle")
