"""Study files (issue 18): ranges, a table of cases, base overrides, the plot section, the
bundled studies; no solve here (the runs are in test_study.py)."""
from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from hotroll.config.case import CaseError
from hotroll.config.study import expand, key_unit, label, load_study

BASE = """
[pass]
roll_radius = 0.6
entry_thickness = 0.5
exit_thickness = 0.4
roll_angular_velocity = 1.0
[plate]
length = 4.0
[material]
K = 1.0
m = 0.2
[friction]
law = "viscoplastic"
[mesh]
h_contact = 0.03
[solver]
method = "transient"
"""


def _study(tmp_path, text: str, top: str = ""):
    """A study of base.toml: ``top`` (keys before any table), then [base] and ``text``."""
    (tmp_path / "base.toml").write_text(BASE)
    (tmp_path / "s.toml").write_text(top + '[base]\nfile = "base.toml"\n' + text)
    return load_study(tmp_path / "s.toml")


def test_ranges_are_evenly_spaced_and_include_both_ends(tmp_path):
    st, _ = _study(tmp_path, '[vary]\n"material.m" = { start = 0.1, stop = 0.3, num = 5 }\n'
                   '"material.K" = { start = 1e3, stop = 1e6, num = 4, scale = "log" }\n'
                   '"pass.roll_angular_velocity" = { start = 0.5, stop = 2.0, step = 0.5 }\n')
    assert st.vary["material.m"] == pytest.approx([0.1, 0.15, 0.2, 0.25, 0.3], rel=1e-12)
    assert st.vary["material.K"] == pytest.approx([1e3, 1e4, 1e5, 1e6], rel=1e-12)
    assert st.vary["pass.roll_angular_velocity"] == pytest.approx([0.5, 1.0, 1.5, 2.0])
    combos = st.combinations()
    assert len(combos) == 5 * 4 * 4
    assert len({tuple(c.values()) for c in combos}) == 80           # all distinct


def test_a_table_of_cases_times_the_grid_and_base_overrides(tmp_path):
    st, base = _study(tmp_path, 'set = { "solver.method" = "steady", "material.K" = 2.0 }\n'
                      '[vary]\n"material.m" = [0.15, 0.25]\n'
                      '[[cases]]\n"pass.exit_thickness" = 0.45\n"friction.law" = "tresca"\n'
                      '"friction.factor" = 0.8\n'
                      '[[cases]]\n"pass.exit_thickness" = 0.35\n')
    assert base["solver"]["method"] == "steady" and base["material"]["K"] == 2.0
    combos = st.combinations()
    assert [(c["pass.exit_thickness"], c["material.m"]) for c in combos] == [
        (0.45, 0.15), (0.45, 0.25), (0.35, 0.15), (0.35, 0.25)]
    cases = expand(st, base)
    assert [c.case.pass_.exit_thickness for c in cases] == [0.45, 0.45, 0.35, 0.35]
    assert [c.case.friction.law for c in cases] == ["tresca", "tresca", "viscoplastic",
                                                   "viscoplastic"]
    assert all(c.case.solver.method == "steady" and c.case.material.K == 2.0 for c in cases)


def test_cases_from_a_csv_file(tmp_path):
    (tmp_path / "cases.csv").write_text("material.m,pass.roll_angular_velocity,friction.law\n"
                                        "0.15,1.0,viscoplastic\n0.3,2,coulomb\n")
    st, base = _study(tmp_path, "", top='cases_file = "cases.csv"\n')
    assert st.combinations() == [
        {"material.m": 0.15, "pass.roll_angular_velocity": 1.0, "friction.law": "viscoplastic"},
        {"material.m": 0.3, "pass.roll_angular_velocity": 2, "friction.law": "coulomb"}]
    cases = expand(st, base)
    assert cases[0].case is not None and cases[0].case.material.m == 0.15
    assert cases[1].case is None and "friction" in cases[1].problem      # coulomb needs its mu


@pytest.mark.parametrize("text, field", [
    ('[vary]\n"material.m" = { start = 0.1, stop = 0.3 }\n', "num"),
    ('[vary]\n"material.m" = { start = 0.1, stop = 0.3, num = 3, step = 0.1 }\n', "num"),
    ('[vary]\n"material.m" = { start = 0.3, stop = 0.1, step = 0.1 }\n', "step"),
    ('[vary]\n"material.K" = { start = 0, stop = 10, num = 3, scale = "log" }\n', "log"),
    ('[vary]\n"material.m" = { start = 0.1, stop = 0.3, num = 1 }\n', "num"),
    ('[vary]\n"material.m" = { start = 0.1, stop = 0.3, nums = 3 }\n', "nums"),
    ('[[cases]]\nm = 0.2\n', "cases"),
    ("", "cases_file: cannot read"),
    ('set = { "solver.method" = "quick" }\n[vary]\n"material.m" = [0.2]\n', "solver.method"),
    ('[vary]\n"material.m" = [0.2]\n[plot]\nx = "material.m"\nlines = "material.K"\n',
     "plot.lines"),
    ('[vary]\n"material.m" = [0.2]\n[plot]\ny = ["roll_force"]\n', "plot.x"),
])
def test_bad_study_files_name_the_field(tmp_path, text, field):
    top = 'cases_file = "nothing.csv"\n' if field.startswith("cases_file") else ""
    with pytest.raises(CaseError) as e:
        _study(tmp_path, text, top)
    assert field in str(e.value)


def test_labels_are_file_names_and_unique():
    long = {f"material.key{i}": 0.123456789 * i for i in range(30)}
    other = {**long, "material.key29": 1.0}
    a, b = label(long), label(other)
    assert len(a) <= 120 and len(b) <= 120 and a != b
    assert label({"mesh.h_contact": "C2", "x.y": "a b/c"}) == "mesh.h_contact=C2,x.y=a_b_c"


def test_units_of_varied_keys_come_from_the_case_schema():
    assert key_unit("pass.roll_angular_velocity") == "rad/s"
    assert key_unit("material.K") == "Pa s^m"
    assert key_unit("pass.exit_thickness") == "m"
    assert key_unit("nothing.there") == "-"
    assert key_unit("plate.temperature") == "K" and key_unit("material.density") == "kg/m^3"


@pytest.mark.parametrize("name, n", [("mesh_table", 6), ("report_examples", 4), ("af_study", 8),
                                     ("edge_zone", 4)])
def test_bundled_studies_are_valid(name, n):
    from hotroll.examples import study_path

    st, base = load_study(study_path(name))
    cases = expand(st, base)
    assert len(cases) == n and all(c.case is not None for c in cases)
    assert all(c.case.solver.method == "steady" for c in cases)
    if name == "mesh_table":
        from hotroll.config.case import MESH_TABLE

        assert [c.case.mesh.h for c in cases] == [MESH_TABLE[k] for k in MESH_TABLE]
    elif name == "edge_zone":     # the last the whole half width: no cut
        assert [c.case.spread.edge_zone for c in cases] == [0.04, 0.08, 0.12, 0.2]
        assert {c.case.pass_.width for c in cases} == {0.4}
    elif name == "af_study":
        assert [c.case.friction.a_f for c in cases] == [1, 2, 5, 10, 20, 50, 100, "estimate"]
        assert st.plot.x == "a_f" and st.plot.xscale == "log"
    else:
        ex = {(c.case.material.m, round(c.case.pass_.roll_angular_velocity, 12))
              for c in cases}
        assert ex == {(0.2, round(math.pi / 3, 12)), (0.2, round(math.pi / 6, 12)),
                      (0.15, round(math.pi / 3, 12)), (0.25, round(math.pi / 3, 12))}


def test_the_figure_is_drawn_from_the_table(tmp_path):
    """study.png's curves are the table's done rows, sorted along x, a line per value."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from hotroll.config.study import PlotConfig
    from hotroll.results.study_plot import plot_table

    rows = [{"case": f"c{i}", "status": "done", "material.m": m, "pass.roll_angular_velocity": w,
             "roll_force": 10 * m + w} for i, (m, w) in enumerate(
                 [(0.3, 1.0), (0.1, 1.0), (0.2, 2.0), (0.1, 2.0), (0.2, 1.0)])]
    rows.append({"case": "bad", "status": "error", "material.m": 0.5,
                 "pass.roll_angular_velocity": 1.0, "roll_force": 99.0})
    captured = {}
    real = plt.Figure.savefig

    def grab(fig, *a, **k):
        captured["lines"] = [(ln.get_label(), list(ln.get_xdata()), list(ln.get_ydata()))
                             for ln in fig.axes[0].lines]
        return real(fig, *a, **k)

    plt.Figure.savefig = grab
    try:
        png = plot_table(rows, PlotConfig(x="material.m", y=["roll_force"],
                                          lines="pass.roll_angular_velocity"),
                         tmp_path / "s.png", units={"roll_force": "N/m"})
    finally:
        plt.Figure.savefig = real
    assert png.is_file()
    lines = {lab: (xs, ys) for lab, xs, ys in captured["lines"]}
    assert lines["pass.roll_angular_velocity = 1 rad/s"] == ([0.1, 0.2, 0.3], [2.0, 3.0, 4.0])
    xs, ys = lines["pass.roll_angular_velocity = 2 rad/s"]
    assert xs == [0.1, 0.2] and np.allclose(ys, [3.0, 4.0])


def test_command_line_overrides_go_on_the_base_after_the_files_own(tmp_path):
    from hotroll.cli.runs import _key_values
    from hotroll.examples import study_path

    over = _key_values(["solver.method=transient", "solver.end_time=0.01", "material.m = 0.3"])
    assert over == {"solver.method": "transient", "solver.end_time": 0.01, "material.m": 0.3}
    st, base = load_study(study_path("mesh_table"), overrides=over)
    cases = expand(st, base)
    assert all(c.case.solver.method == "transient" and c.case.material.m == 0.3 for c in cases)


SCHEDULE = Path(__file__).resolve().parents[1] / "data" / "two_pass_schedule.toml"


def _schedule_study(tmp_path, vary: str, set_: str = ""):
    import shutil

    shutil.copy(SCHEDULE, tmp_path / "two_pass.toml")
    (tmp_path / "s.toml").write_text(f'[base]\nschedule = "two_pass.toml"\n{set_}[vary]\n{vary}')
    return load_study(tmp_path / "s.toml")


def test_schedule_keys_set_one_pass_or_every_pass(tmp_path):
    st, base = _schedule_study(tmp_path, '"pass[2].exit_thickness" = [0.064, 0.07]\n',
                               'set = { "pass[*].roll_radius" = 0.45, "strip.strain" = 0.1 }\n')
    cases = expand(st, base)
    assert [c.case.passes[1].exit_thickness for c in cases] == [0.064, 0.07]
    assert all(p.roll_radius == 0.45 for c in cases for p in c.case.passes)
    assert all(c.case.strip.strain == 0.1 for c in cases)
    assert key_unit("pass[2].exit_thickness") == "m" and key_unit("strip.temperature") == "K"


@pytest.mark.parametrize("vary, field", [
    ('"pass[3].exit_thickness" = [0.05]\n', "pass[3].exit_thickness: the schedule has passes"),
    ('"pass[2].exit_thickness" = [0.5]\n', "pass[2].exit_thickness"),
    ('"strip.temperature" = [-1.0]\n', "strip.temperature"),
])
def test_bad_schedule_combinations_are_rows_naming_the_field(tmp_path, vary, field):
    st, base = _schedule_study(tmp_path, vary)
    (c,) = expand(st, base)
    assert c.case is None and field in c.problem


def test_a_schedule_study_row_is_its_schedules_own_table(tmp_path):
    """Each row's per-pass columns = the case directory's schedule.csv; the first case = a
    separate run_schedule of the same schedule; the hotter strip needs less force."""
    from hotroll.config.schedule import load_schedule
    from hotroll.workflows.schedule import run_schedule
    from hotroll.workflows.study import run_study

    st, base = _schedule_study(tmp_path, '"strip.temperature" = [1323.15, 1373.15]\n')
    rows = run_study(st, base, tmp_path / "out", serial=True)
    assert [r["status"] for r in rows] == ["done", "done"]
    for r in rows:
        with open(tmp_path / "out" / "cases" / r["case"] / "schedule.csv", newline="") as f:
            table = list(csv.DictReader(f))
        assert r["passes"] == len(table) == 2
        for p in table:
            for k in ("roll_force", "roll_torque", "forward_slip", "exit_temperature_mean"):
                assert r[f"{p['name']}.{k}"] == float(p[k]), (p["name"], k)
        assert r["max_roll_force"] == max(float(p["roll_force"]) for p in table)
        assert r["total_roll_power"] == pytest.approx(sum(float(p["roll_power"]) for p in table),
                                                      rel=1e-12)
        last = table[-1]
        for k in ("exit_thickness", "outlet_temperature_mean", "exit_strain_mean"):
            assert r[k] == float(last[k]), k
        assert r["fe_solves"] == sum(int(p["fe_solves"]) for p in table)
    assert rows[1]["R1.roll_force"] < rows[0]["R1.roll_force"]
    sch = load_schedule(tmp_path / "two_pass.toml").model_copy(deep=True)
    sch.strip.temperature = 1323.15
    sch.solver.threads = 1
    own = run_schedule(sch, tmp_path / "own", figure=False)
    for p in own:
        assert rows[0][f"{p['name']}.roll_force"] == pytest.approx(p["roll_force"], rel=1e-9)
    from hotroll.results.report import write_report  # each case linked to its schedule's page

    html = write_report(tmp_path / "out").read_text()
    for r in rows:
        assert (tmp_path / "out" / "cases" / r["case"] / "report.html").is_file()
        assert (tmp_path / "out" / "cases" / r["case"] / "R1" / "report.html").is_file() or any(
            (tmp_path / "out" / "cases" / r["case"]).glob("*R1/report.html"))
    assert html.count('href="cases/') == 2


def test_zip_of_a_cases_table_alone_and_unique_labels(tmp_path):
    st, base = _study(tmp_path, '[[cases]]\n"material.m" = 0.2\n[[cases]]\n"material.m" = 0.2\n'
                      '[[cases]]\n"material.m" = 0.2000001\n[run]\ncombine = "zip"\n')
    cases = expand(st, base)
    assert len(cases) == 3
    assert len({c.label for c in cases}) == 3              # equal to 6 digits: made unique


@pytest.mark.parametrize("top, text, field", [
    ("", '[vary]\n"material.m" = [0.2]\n[[cases]]\n"material.m" = 0.3\n', "also in [[cases]]"),
    ('cases_file = "c.csv"\n', "", "line 3 has more cells"),
])
def test_conflicting_or_ragged_cases_are_refused(tmp_path, top, text, field):
    (tmp_path / "c.csv").write_text("material.m\n0.2\n0.3,1\n")
    with pytest.raises(CaseError) as e:
        _study(tmp_path, text, top)
    assert field in str(e.value)


def test_plot_lines_may_name_a_column_of_the_cases_file(tmp_path):
    (tmp_path / "c.csv").write_text("material.m,pass.roll_angular_velocity\n0.2,1\n0.3,2\n")
    st, _ = _study(tmp_path, '[plot]\nx = "material.m"\nlines = "pass.roll_angular_velocity"\n',
                   'cases_file = "c.csv"\n')
    assert st.plot.lines == "pass.roll_angular_velocity" and len(st.combinations()) == 2
    with pytest.raises(CaseError) as e:
        _study(tmp_path, '[plot]\nx = "material.m"\nlines = "material.K"\n',
               'cases_file = "c.csv"\n')
    assert "plot.lines" in str(e.value)


def test_a_figure_against_names_and_a_missing_column(tmp_path):
    from hotroll.config.study import PlotConfig
    from hotroll.results.study_plot import plot_table

    rows = [{"case": "a", "status": "done", "friction.law": "coulomb", "roll_force": 2.0},
            {"case": "b", "status": "done", "friction.law": "tresca", "roll_force": 3.0}]
    assert plot_table(rows, PlotConfig(x="friction.law"), tmp_path / "f.png").is_file()
    with pytest.raises(ValueError, match="roll_torque"):
        plot_table(rows, PlotConfig(x="friction.law", y=["roll_torque"]), tmp_path / "g.png")


def test_the_api_takes_a_bundled_study_and_overrides(tmp_path, monkeypatch):
    import hotroll
    from hotroll import api as run_mod  # where the API calls run_study

    seen = {}
    monkeypatch.setattr(run_mod, "run_study", lambda st, base, out, **k: seen.update(
        st=st, base=base, out=out, **k) or [])
    assert hotroll.study("report_examples", tmp_path, serial=True,
                         overrides={"mesh.h_contact": 0.02}) == []
    assert seen["st"].name == "report_examples" and seen["serial"] is True
    assert seen["base"]["mesh"]["h_contact"] == 0.02
    assert seen["base"]["solver"]["method"] == "steady"          # the file's own base.set


def test_a_schedule_whose_pass_fails_is_a_row_with_the_passes_before(tmp_path, monkeypatch):
    from hotroll.workflows import schedule as runner  # where a schedule calls run_case
    from hotroll.workflows.study import run_study

    real = runner.run_case

    def second_diverges(case, out, **k):
        s = real(case, out, **k)
        return {**s, "exit_code": 4, "status": "failed"} if "R2" in str(out) else s

    monkeypatch.setattr(runner, "run_case", second_diverges)
    st, base = _schedule_study(tmp_path, '"strip.temperature" = [1373.15]\n')
    (row,) = run_study(st, base, tmp_path / "out", serial=True)
    assert row["status"] == "not_converged" and row["exit_code"] == 4
    assert "pass 2 (" in row["reason"]
    assert "R1.roll_force" in row and "R2.roll_force" not in row


def test_groups_are_cut_for_the_workers_a_scheduler_has():
    from distributed import LocalCluster

    from hotroll.workflows.study import _scheduler_workers

    with LocalCluster(n_workers=3, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster:
        assert _scheduler_workers(cluster.scheduler_address) == 3


@pytest.mark.parametrize("csv_text, message", [
    (None, "cases_file: cannot read {p}: No such file or directory"),
    ("material.m,material.K\n", "cases_file: {p} has no rows under its header"),
    ("material.m,K\n0.2,1\n", "cases_file: header ['K']: dotted case keys (section.key)"),
    ("material.m,material.K\n0.2,1\n0.3,1,9\n", "cases_file: {p} line 3 has more cells than "
                                                "the header"),
])
def test_a_bad_cases_file_is_named_exactly(tmp_path, csv_text, message):
    p = tmp_path / "c.csv"
    if csv_text is not None:
        p.write_text(csv_text)
    with pytest.raises(CaseError) as e:
        _study(tmp_path, "", top='cases_file = "c.csv"\n')
    assert e.value.problems == [message.format(p=p)]
    assert e.value.source == str(tmp_path / "s.toml")


def test_a_cell_reads_as_toml_would():
    """parse_value: numbers, booleans in any case, lists and quoted text as TOML reads them;
    anything else is the text itself, stripped. Empty cells of a cases file are left out."""
    from hotroll.config.study import parse_value

    assert parse_value(" 3 ") == 3 and isinstance(parse_value("3"), int)
    assert parse_value("1e3") == 1000.0 and parse_value("-0.5") == -0.5
    assert parse_value("TRUE") is True and parse_value("False") is False
    assert parse_value("[1, 2.5]") == [1, 2.5] and parse_value('"C2"') == "C2"
    assert parse_value(" coulomb ") == "coulomb" and parse_value("a b") == "a b"


def test_empty_cells_of_a_cases_file_are_left_to_the_base(tmp_path):
    (tmp_path / "c.csv").write_text("material.m,material.K\n0.25,\n,3.5\n")
    st, _ = _study(tmp_path, "", top='cases_file = "c.csv"\n')
    assert st.combinations() == [{"material.m": 0.25}, {"material.K": 3.5}]
