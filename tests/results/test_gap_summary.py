"""results/gap_summary.py by hand, no FE solve: a window mean leaves out what a row lacks,
and a roll's contact-end pressure is its profile's LAST point's (the exit end)."""
from __future__ import annotations

import math
from types import SimpleNamespace

from hotroll.results.gap_summary import GAP_KEYS, SIDES, _mean, gap_figures
from hotroll.results.summary import ROLL_ENTRY


def test_a_window_mean_leaves_out_missing_and_nan_values():
    rows = [{"a": 1.0}, {"a": None}, {"a": math.nan}, {"a": 3.0}]
    assert _mean(rows, "a") == 2.0
    assert math.isnan(_mean([{"a": None}], "a"))


def test_the_contact_end_pressure_is_the_last_points():
    row = {f"{s}_{k}": 1.0 for s in SIDES for k in ROLL_ENTRY} | {k: 0.5 for k in GAP_KEYS}

    def contact(stress):
        return SimpleNamespace(rp=SimpleNamespace(radius=0.3, u_roll=1.2), overlap=0.0,
                               exact=True, profile={"x": [0.0, 0.01, 0.02],
                                                    "normal_stress": stress})

    figs = gap_figures([row, row], [contact([-5e6, -8e6, -1e6]), contact([-4e6, -7e6, -2e6])],
                       1.1, 0.0)
    assert [r["contact_end_pressure"] for r in figs["rolls"]] == [1e6, 2e6]
    assert figs["speed_ratio"] == 1.1 and figs["exit_curvature"] == 0.5
