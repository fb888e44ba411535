"""The Python API's own code (hotroll/api.py), in process: the example lookup, the study and
schedule calls with the rolling faked (what they hand over), and a result read back from the
suite's cached solved case (attributes, units, repr, fields, refusals). The tutorial test runs
the API as written, in a subprocess."""
from __future__ import annotations

import json

import pytest

import hotroll.api as api
from hotroll.examples import EXAMPLES


def test_example_case_by_name_and_method():
    case = api.example_case("2")
    assert case.solver.method == "steady" and case.name == EXAMPLES["2"][0]
    assert api.example_case("hot_strip_finishing", method="transient").solver.method == \
        "transient"
    with pytest.raises(api.CaseError, match="example '3' has several cases: " +
                       ", ".join(EXAMPLES["3"])):
        api.example_case("3")


def test_study_and_schedule_hand_over_their_options(tmp_path, monkeypatch):
    seen = {}

    def run_study(st, base, out, *, workers, scheduler, serial):
        seen.update(study=st.name, base=base, out=out, workers=workers, scheduler=scheduler,
                    serial=serial)
        return [{"case": "a"}]

    def run_schedule(sch, out, *, figure):
        seen.update(schedule=sch.name, sout=out, figure=figure)
        return [{"name": "F1"}]

    monkeypatch.setattr(api, "run_study", run_study)
    monkeypatch.setattr(api, "run_schedule", run_schedule)
    rows = api.study("af_study", str(tmp_path), workers=3, scheduler="tcp://x:1", serial=True,
                     overrides={"material.m": 0.3})
    assert rows == [{"case": "a"}]
    assert (seen["study"], seen["out"], seen["workers"], seen["scheduler"], seen["serial"]) == (
        "af_study", tmp_path, 3, "tcp://x:1", True)
    assert seen["base"]["material"]["m"] == 0.3
    assert api.roll_schedule("finishing_mill", str(tmp_path / "s"), figure=False) == [
        {"name": "F1"}]
    assert (seen["schedule"], seen["sout"], seen["figure"]) == ("finishing_mill",
                                                                tmp_path / "s", False)


def test_a_result_read_back(solved_example1):
    res = api.open_result(solved_example1)
    s = json.loads((solved_example1 / "summary.json").read_text())
    assert res.roll_force == s["roll_force"] and res.units["roll_force"] == "N/m"
    assert res.converged is True and res.out == solved_example1
    assert res.summary.case_name == s["case_name"]
    assert repr(res) == (f"Result({s['case_name']!r}, status {s['status']!r}, roll_force "
                         f"{s['roll_force']:.6g} N/m, roll_torque {s['roll_torque']:.6g} N m/m, "
                         f"out={str(solved_example1)!r})")
    f = res.fields
    assert f["points"].shape[1] == 2 and len(f["sigma_ef"]) == len(f["points"])
    assert res.contact["x"][0] == pytest.approx(s["contact_start"][0], abs=1e-12)
    with pytest.raises(AttributeError, match="'no_such_figure': not a field of the result"):
        res.no_such_figure
    with pytest.raises(KeyError, match="'velocity': a scalar field is one of "):
        res.plot_field("velocity")


def test_plot_field_covers_the_strip(solved_example1):
    """Result.plot_field draws the field over the strip's own points: the filled contours'
    data span the points' x and y ranges (fields.npz), the colour bar is labelled by the
    field's name."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    res = api.open_result(solved_example1)
    p = res.fields["points"]
    ax = res.plot_field("sigma_ef")
    try:
        lim = ax.dataLim
        assert (lim.x0, lim.x1) == pytest.approx((np.min(p[:, 0]), np.max(p[:, 0])), rel=1e-12)
        assert (lim.y0, lim.y1) == pytest.approx((np.min(p[:, 1]), np.max(p[:, 1])), rel=1e-12)
        assert ax.figure.axes[-1].get_ylabel() == "sigma_ef"
    finally:
        plt.close(ax.figure)
