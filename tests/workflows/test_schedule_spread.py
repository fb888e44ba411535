"""A schedule with [spread] (issue 53): each pass also on the 3D strip across its width, the
width carried from pass to pass. Two coarse isothermal passes of a 10 x 10 mm bar
(tests/data/bar_spread_schedule.toml), one width layer each.

Labels: [identity] the hand-off; [reference] the spread formulas' band; [plumb] the columns."""
from __future__ import annotations

import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

from hotroll.config.schedule import load_schedule
from hotroll.theory.spread import hill, sparling, wusatowski
from hotroll.workflows.schedule import run_schedule

DATA = Path(__file__).resolve().parents[1] / "data" / "bar_spread_schedule.toml"


@pytest.fixture(scope="module")
def rolled(tmp_path_factory):
    out = tmp_path_factory.mktemp("bar_schedule")
    rows = run_schedule(load_schedule(DATA), out)
    return rows, out


def test_the_next_pass_enters_with_the_last_ones_exit_width(rolled):
    """[identity] pass 2's case has the width pass 1's 3D pass leaves with; each row's exit
    width is its entry width plus its spread; the width grows pass by pass."""
    rows, out = rolled
    cases = [tomllib.loads((out / r["case"] / "case.toml").read_text()) for r in rows]
    assert cases[0]["pass"]["width"] == 0.01 and "spread" in cases[1]
    assert cases[1]["pass"]["width"] == pytest.approx(rows[0]["exit_width"], rel=1e-12)
    for r in rows:
        assert r["exit_width"] == pytest.approx(r["entry_width"] + r["spread"], rel=1e-12)
    assert 0.01 < rows[0]["exit_width"] < rows[1]["exit_width"]


def test_each_passs_spread_lies_in_the_formulas_band(rolled):
    """[reference] each pass's spread inside Hill / Sparling / Wusatowski for the width and
    thickness it enters with."""
    rows, out = rolled
    for r in rows:
        b0, h0, h1 = r["entry_width"], r["entry_thickness"], r["exit_thickness"]
        band = [float(f(b0, h0, h1, 0.25)) - b0 for f in (hill, sparling, wusatowski)]
        assert min(band) <= r["spread"] <= max(band)


def test_the_schedule_table_has_the_width_columns_with_units(rolled):
    """[plumb] schedule.csv's width columns and their units in schedule.json."""
    rows, out = rolled
    table = np.genfromtxt(out / "schedule.csv", delimiter=",", names=True, dtype=None,
                          encoding=None)
    for key in ("entry_width", "exit_width", "spread"):
        assert key in table.dtype.names
    units = json.loads((out / "schedule.json").read_text())["units"]
    assert units["entry_width"] == units["exit_width"] == units["spread"] == "m"


@pytest.mark.parametrize("key, value", [("speeds", "mass_flow"), ("tensions", "from_speeds")])
def test_a_tandem_matched_by_flux_is_refused_with_spread(key, value):
    """[plumb] a tandem's stands matched by their flux per unit width: refused with [spread]
    (the width changes from stand to stand), naming the key, before any computation."""
    import tomllib

    from hotroll.config.case import CaseError
    from hotroll.config.schedule import schedule_from_dict

    data = tomllib.loads(DATA.read_text())
    data["mill"] = {key: value}
    with pytest.raises(CaseError, match=f'mill.{key}: "{value}" not with \\[spread\\]'):
        schedule_from_dict(data)


def test_an_entry_temperature_across_the_width_is_refused_in_a_schedule():
    """[plumb] ``spread.temperature_profile`` names one pass's entry temperature; a schedule's
    passes enter at their own: refused naming the key, before any computation."""
    import tomllib

    from hotroll.config.case import CaseError
    from hotroll.config.schedule import schedule_from_dict

    data = tomllib.loads(DATA.read_text())
    data["spread"] = {**data.get("spread", {}),
                      "temperature_profile": [[0.0, 1373.15], [1.0, 1273.15]]}
    with pytest.raises(CaseError, match="spread.temperature_profile: not in a schedule"):
        schedule_from_dict(data)
