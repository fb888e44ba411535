"""docs/tutorial.md runs as written: its Python blocks, in order, in one namespace, in a
temporary directory (issue 18: the API tutorial executed by a test)."""
from __future__ import annotations

import os
import re
from pathlib import Path

TUTORIAL = Path(__file__).resolve().parents[1] / "docs" / "tutorial.md"


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


def test_the_api_names_are_not_shadowed_by_packages():
    """``hotroll.study`` and ``hotroll.roll_schedule`` stay the API's functions after the
    packages behind them are imported (a package attribute would shadow a function of the
    same name)."""
    import hotroll
    import hotroll.schedule.run  # noqa: F401
    import hotroll.studies.run  # noqa: F401

    assert callable(hotroll.study) and callable(hotroll.roll_schedule)
    assert hotroll.study.__module__ == "hotroll.api"
