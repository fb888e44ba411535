"""The command line's side of ``hotroll schedule`` and ``hotroll study`` (hotroll/cli/runs.py),
with the rolling itself faked: what each command hands over, the table it prints from the rows
it gets back (units and scales by hand), its exit code and its refusals. The real runs are in
tests/workflows (schedules, studies on a cluster, the faults)."""
from __future__ import annotations

import pytest
from typer.testing import CliRunner

from hotroll.cli import app, runs
from hotroll.workflows.schedule import ScheduleError

ROW = {"name": "F1", "entry_thickness": 0.035, "exit_thickness": 0.0215,
       "roll_surface_speed": 1.234, "roll_force": 8.5e6, "roll_torque": 3.2e5,
       "exit_temperature_mean": 1301.25, "exit_strain_mean": 0.5617, "fe_solves": 3,
       "wall_time": 4.56}


def _cells(output: str, first: str) -> list[str]:
    line = next(x for x in output.splitlines() if x.startswith(f"│ {first}"))
    return [c.strip() for c in line.strip("│").split("│")]


@pytest.fixture
def wide(monkeypatch):
    monkeypatch.setattr(runs.console, "width", 300)       # rich: no line wrapped


def test_schedule_prints_its_rows_with_the_whole_width(tmp_path, monkeypatch, wide):
    """finishing_mill has a width (1.5 m): force and torque of the whole width, MN and kN m."""
    seen = {}

    def run_schedule(sch, out, *, resume, figure, progress):
        seen.update(sch=sch, out=out, resume=resume, figure=figure)
        progress("pass F1 done")
        return [ROW]

    monkeypatch.setattr(runs, "run_schedule", run_schedule)
    r = CliRunner().invoke(app, ["schedule", "finishing_mill", "--out", str(tmp_path),
                                 "--no-figures", "--no-resume"])
    assert r.exit_code == 0, r.output
    assert seen["out"] == tmp_path and seen["resume"] is False and seen["figure"] is False
    assert seen["sch"].output.figures is False
    assert f"rolling finishing_mill: 6 passes -> {tmp_path}" in r.output
    assert "  pass F1 done" in r.output
    head = next(x for x in r.output.splitlines() if "pass" in x and "┃" in x)
    assert [c.strip() for c in head.strip("┃").split("┃")] == [
        "pass", "h mm", "U m/s", "F MN", "M kNm", "T out K", "strain", "FE", "s"]
    # 8.5e6 N/m x 1.5 m = 12.75 MN; 3.2e5 N m/m x 1.5 m = 480 kN m
    assert _cells(r.output, "F1") == ["F1", "35.0>21.5", "1.23", "12.75", "480", "1301.2",
                                      "0.562", "3", "4.6"]
    assert "force and torque per roll, whole width;" in r.output
    assert f"{tmp_path / 'schedule.csv'}" in r.output and f"{tmp_path / 'schedule.png'}" in r.output


def test_schedule_without_a_width_is_per_metre(tmp_path, monkeypatch, wide):
    from hotroll.config.schedule import load_schedule
    from hotroll.examples import schedule_path

    sch = load_schedule(schedule_path("finishing_mill"))
    sch.strip.width = None
    path = tmp_path / "s.toml"
    monkeypatch.setattr(runs, "load_schedule", lambda f: sch)
    monkeypatch.setattr(runs, "run_schedule", lambda *a, **k: [ROW])
    path.write_text("")
    r = CliRunner().invoke(app, ["schedule", str(path), "--out", str(tmp_path / "o")])
    assert r.exit_code == 0, r.output
    head = next(x for x in r.output.splitlines() if "pass" in x and "┃" in x)
    assert "F MN/m" in head and "M kNm/m" in head
    assert _cells(r.output, "F1")[3:5] == ["8.50", "320"]
    assert "force and torque per roll; exit" in r.output


def test_a_failing_pass_ends_the_schedule_with_its_exit_code(tmp_path, monkeypatch, wide):
    def failing(*a, **k):
        raise ScheduleError(1, "F2", {"exit_code": 4, "status": "failed"})

    monkeypatch.setattr(runs, "run_schedule", failing)
    r = CliRunner().invoke(app, ["schedule", "finishing_mill", "--out", str(tmp_path)])
    assert r.exit_code == 4
    assert "pass 2 (F2) ended with exit code 4" in " ".join(r.output.split())


def test_an_unknown_schedule_is_refused(tmp_path):
    r = CliRunner().invoke(app, ["schedule", "no_such_mill", "--out", str(tmp_path)])
    assert r.exit_code == 2
    assert "schedule: no_such_mill is neither a file nor a bundled schedule" in " ".join(
        r.output.split())


def test_study_hands_over_its_options_and_counts_the_failed(tmp_path, monkeypatch, wide):
    seen = {}

    def run_study(st, base, out, *, scheduler, workers, serial, progress):
        seen.update(st=st, base=base, out=out, scheduler=scheduler, workers=workers,
                    serial=serial)
        progress({"done": 1, "failed": 1, "running": 0, "remaining_s": float("nan")})
        return [{"case": "a", "status": "done", "reason": None},
                {"case": "b", "status": "not_converged", "reason": "exit code 4"},
                {"case": "c", "status": "error", "reason": "boom"}]

    monkeypatch.setattr(runs, "run_study", run_study)
    monkeypatch.setattr(runs, "study_report", lambda out, name: seen.update(report=name))
    r = CliRunner().invoke(app, ["study", "af_study", "--out", str(tmp_path), "--serial",
                                 "--workers", "3", "--set", "solver.method=transient",
                                 "--set", "material.m = 0.25"])
    assert r.exit_code == 64 + 2, r.output
    assert seen["serial"] is True and seen["workers"] == 3 and seen["scheduler"] is None
    assert seen["base"]["solver"]["method"] == "transient" and seen["base"]["material"]["m"] == 0.25
    assert seen["report"] == "af_study" and seen["out"] == tmp_path
    text = " ".join(r.output.split())
    assert f"study af_study: 8 cases -> {tmp_path}" in text
    assert "b: not_converged: exit code 4" in text and "c: error: boom" in text
    assert f"1 of 3 cases done; table {tmp_path / 'study.csv'} and " \
           f"{tmp_path / 'study.parquet'}" in text


@pytest.mark.parametrize("item", ["solver.method", "method=steady"])
def test_a_bad_set_option_is_named(tmp_path, item):
    r = CliRunner().invoke(app, ["study", "af_study", "--out", str(tmp_path), "--set", item])
    assert r.exit_code == 2
    assert f"--set {item!r}: expected section.key=value" in " ".join(r.output.split())


def test_a_full_disk_and_a_refused_mesh_end_with_their_messages(monkeypatch, capsys):
    """``hotroll``'s entry point: a full disk ends with exit code 9 and the error's own text
    (which names the file and the free space), a mesh over the memory limit with 8 and
    "refused: ..." on stderr, never a traceback."""
    import errno

    import hotroll.cli as cli
    from hotroll.files import DiskFullError
    from hotroll.workflows.estimate import ResourceError

    def full():
        raise DiskFullError(errno.ENOSPC, "disk full: no space left writing out/x.csv (0.0 MB free)")

    monkeypatch.setattr(cli, "app", full)
    with pytest.raises(SystemExit) as e:
        cli.main()
    assert e.value.code == 9
    assert "disk full: no space left writing out/x.csv (0.0 MB free)" in capsys.readouterr().err

    def big():
        raise ResourceError("the mesh needs 40 GB")

    monkeypatch.setattr(cli, "app", big)
    with pytest.raises(SystemExit) as e:
        cli.main()
    assert e.value.code == 8
    assert "refused: the mesh needs 40 GB" in capsys.readouterr().err


def test_run_prints_the_rolls_and_the_mills_figures(tmp_path, monkeypatch):
    """``hotroll run`` of a case with a flattening roll and a mill modulus (the run faked):
    the roll's and the mill's rows with their units; a plain run has none of them."""
    from hotroll.cli import passes
    from hotroll.examples import example_path

    base = {"exit_code": 0, "status": "steady", "converged": True, "roll_force": 7.6e6,
            "contact_length": 0.0141, "units": {"contact_length": "m"}}
    flat = {**base, "roll_model": "hitchcock", "roll_equivalent_radius": 0.4975,
            "roll_flattening": 8.39e-5, "roll_updates": 10, "mill_modulus": 5e9,
            "mill_stretch": 2.29e-3, "gap_setting": -2.9e-4}
    monkeypatch.setattr(passes.console, "width", 300)
    for summary, shown in ((flat, True), (base, False)):
        monkeypatch.setattr(passes, "run_case", lambda *a, s=summary, **k: s)
        r = CliRunner().invoke(app, ["run", str(example_path("thin_strip")), "--out",
                                     str(tmp_path / "o")])
        assert r.exit_code == 0, r.output
        if shown:
            assert _cells(r.output, "roll_equivalent_radius")[1:] == ["0.4975", "m"]
            assert _cells(r.output, "roll_flattening")[1:] == ["8.39e-05", "m"]
            assert _cells(r.output, "mill_stretch")[1:] == ["0.00229", "m"]
            assert _cells(r.output, "gap_setting")[1:] == ["-0.00029", "m"]
            assert _cells(r.output, "contact_length")[1:] == ["0.0141", "m"]
        else:
            assert "roll_equivalent_radius" not in r.output and "contact_length" not in r.output


def test_schedule_on_a_mill_shows_the_flattening_the_gap_and_the_tensions(tmp_path,
                                                                          monkeypatch, wide):
    """finishing_mill_elastic (elastic rolls, stand moduli) with tensions from the speeds (the
    rows faked): R'/R, the gap to set in mm and the front tension in MPa, by hand."""
    row = {**ROW, "roll_radius": 0.35, "roll_equivalent_radius": 0.3549, "gap_setting": 0.0181,
           "front_tension": 12.5e6}
    from hotroll.config.schedule import load_schedule
    from hotroll.examples import schedule_path

    sch = load_schedule(schedule_path("finishing_mill_elastic"))
    sch.mill.tensions = "from_speeds"
    monkeypatch.setattr(runs, "load_schedule", lambda f: sch)
    monkeypatch.setattr(runs, "run_schedule", lambda *a, **k: [row])
    path = tmp_path / "s.toml"
    path.write_text("")
    r = CliRunner().invoke(app, ["schedule", str(path), "--out", str(tmp_path / "o")])
    assert r.exit_code == 0, r.output
    head = next(x for x in r.output.splitlines() if "pass" in x and "┃" in x)
    assert [c.strip() for c in head.strip("┃").split("┃")] == [
        "pass", "h mm", "U m/s", "t front MPa", "F MN", "M kNm", "T out K", "strain", "R'/R",
        "gap mm", "FE", "s"]
    assert _cells(r.output, "F1")[3] == "12.50" and _cells(r.output, "F1")[8:10] == [
        "1.0140", "18.100"]


def test_schedule_with_kinetics_shows_the_microstructure(tmp_path, monkeypatch, wide):
    """finishing_mill_microstructure (the rows faked): where DRX started, and after the
    transport X, the grain size in um and the retained strain; the last pass (no transport)
    has dashes there."""
    rows = [{**ROW, "drx_onset_share": 0.625, "recrystallised_fraction_mean": 0.98765,
             "grain_size_mean": 31.26e-6, "retained_strain_mean": 0.00432},
            {**ROW, "name": "F6", "drx_onset_share": 0.0}]
    monkeypatch.setattr(runs, "run_schedule", lambda *a, **k: rows)
    r = CliRunner().invoke(app, ["schedule", "finishing_mill_microstructure", "--out",
                                 str(tmp_path)])
    assert r.exit_code == 0, r.output
    head = next(x for x in r.output.splitlines() if "pass" in x and "┃" in x)
    assert [c.strip() for c in head.strip("┃").split("┃")][-6:] == [
        "DRX", "X", "d um", "e ret", "FE", "s"]
    assert _cells(r.output, "F1")[-6:-2] == ["0.62", "0.988", "31.3", "0.004"]
    assert _cells(r.output, "F6")[-6:-2] == ["0.00", "-", "-", "-"]
    assert f"{tmp_path / 'microstructure.png'}" in r.output
