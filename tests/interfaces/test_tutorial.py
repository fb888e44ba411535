"""docs/tutorial.md runs as written: its Python blocks, in order, in one namespace, in a
temporary directory (issue 18: the API tutorial executed by a test)."""
from __future__ import annotations

import os
import re
from pathlib import Path

TUTORIAL = Path(__file__).resolve().parents[2] / "docs" / "tutorial.md"


def test_the_tutorial_runs(tmp_path, capsys):
    blocks = re.findall(r"```python\n(.*?)```", TUTORIAL.read_text(), re.S)
    assert len(blocks) >= 4
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        ns: dict = {}
        for block in blocks:
            exec(compile(block, str(TUTORIAL), "exec"), ns)
    finally:
        os.chdir(cwd)
    out = capsys.readouterr().out
    assert "pass.exit_thickness" in out            # the refused value names its field
    assert (tmp_path / "contact.png").stat().st_size > 1000
    assert (tmp_path / "study_out" / "study.parquet").exists()
    res = ns["res"]
    assert res.units["roll_force"] == "N/m" and 0.4 < res.roll_force < 0.7
    # the result is what the run wrote: summary.json and contact.csv, read here on their own
    import csv
    import json

    import numpy as np

    written = json.loads((res.out / "summary.json").read_text())
    for key in ("roll_force", "roll_torque", "forward_slip"):
        assert getattr(res, key) == written[key]
    with open(res.out / "contact.csv", newline="") as fh:
        sn = [float(row["normal_stress"]) for row in csv.DictReader(fh)]
    assert np.array_equal(res.contact["normal_stress"], np.array(sn))
    rows = ns["rows"]
    for row in rows:
        case_summary = json.loads((tmp_path / "study_out" / "cases" / row["case"] /
                                   "summary.json").read_text())
        assert row["roll_force"] == case_summary["roll_force"]


def test_the_api_names_are_not_shadowed_by_packages():
    """``hotroll.study`` and ``hotroll.roll_schedule`` stay the API's functions after the
    packages behind them are imported (a package attribute would shadow a function of the
    same name)."""
    import hotroll
    import hotroll.workflows.schedule  # noqa: F401
    import hotroll.workflows.study  # noqa: F401

    assert callable(hotroll.study) and callable(hotroll.roll_schedule)
    assert hotroll.study.__module__ == "hotroll.api"
