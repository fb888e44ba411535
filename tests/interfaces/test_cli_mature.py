"""The command line of a mature tool (issue 51, item 6): ``--version`` and ``-h``, help whose
paragraphs are whole (no line broken where the docstring wraps, no markup eaten), bundled
names wherever a file is taken, ``validate`` of cases, schedules and studies, tables that keep
every figure in a pipe or at 80 columns, ``--format csv|json``, output files created with the
user's umask, and the time left of long runs measured and labelled an estimate."""
from __future__ import annotations

import csv
import inspect
import io
import json
import os
import subprocess
import sys
from decimal import Decimal
from importlib.metadata import version

import pytest
import typer
from casebuild import EX1_COARSE_TOML
from rich.console import Console
from typer.testing import CliRunner

from hotroll.cli import app, passes, runs
from hotroll.cli.validate import file_kind
from hotroll.examples import HERE, schedule_path, study_path
from hotroll.files import atomic

COMMANDS = sorted(typer.main.get_command(app).commands)


def _cli(*args: str, **env: str):
    return CliRunner().invoke(app, list(args), env=env or None)


def _flat(text: str) -> str:
    return " ".join(text.split())


# ------------------------------------------------------------------ --version, -h
def test_version_prints_the_installed_version():
    for flag in ("--version", "-V"):
        r = _cli(flag)
        assert r.exit_code == 0, r.output
        assert r.output == f"hotroll {version('hotroll')}\n"


@pytest.mark.parametrize("args", [[], ["run"], ["validate"], ["study"]])
def test_h_is_the_help(args):
    short, long = _cli(*args, "-h"), _cli(*args, "--help")
    assert short.exit_code == 0 and long.exit_code == 0, short.output
    assert "Usage:" in short.output and short.output == long.output


# ------------------------------------------------------------------ help text
def _paragraphs(text: str | None) -> list[str]:
    """A help text's paragraphs, each as one line of words (what the reader should see)."""
    return [_flat(p) for p in inspect.cleandoc(text or "").split("\n\n") if p.strip()]


def _help(args: list[str], columns: int) -> list[str]:
    r = _cli(*args, "--help", COLUMNS=str(columns))
    assert r.exit_code == 0, r.output
    return [_flat(line.replace("│", " ")) for line in r.output.splitlines()]


@pytest.mark.parametrize("name", COMMANDS)
def test_each_commands_help_keeps_its_paragraphs_whole(name):
    """On a terminal wide enough, every paragraph of the command's docstring and every
    option's help is on one line, word for word: none broken where the source wraps, no
    [section] name eaten as markup (the study's "Study file (TOML): and /[]"), no "[]"."""
    cmd = typer.main.get_command(app).commands[name]
    lines = _help([name], 3000)
    texts = _paragraphs(cmd.help) + [_flat(p.help) for p in cmd.params
                                     if getattr(p, "help", None)]
    assert texts
    for text in texts:
        assert any(text in line for line in lines), (name, text)
    assert not any("[]" in line for line in lines)


def test_the_apps_help_lists_each_commands_first_paragraph_whole():
    lines = _help([], 3000)
    for name, cmd in typer.main.get_command(app).commands.items():
        first = _paragraphs(cmd.help)[0]
        assert any(line.startswith(f"{name} {first}") for line in lines), (name, first)


@pytest.mark.parametrize("name", COMMANDS)
def test_help_at_80_columns_loses_no_word(name):
    cmd = typer.main.get_command(app).commands[name]
    shown = set(" ".join(_help([name], 80)).split())
    words = {w for t in _paragraphs(cmd.help) + [p.help for p in cmd.params
                                                 if getattr(p, "help", None)]
             for w in t.split()}
    assert words <= shown, sorted(words - shown)


# ------------------------------------------------------------------ bundled names
def test_run_sweep_and_compare_take_a_bundled_cases_name(tmp_path, monkeypatch):
    seen = []
    monkeypatch.setattr(passes, "run_case", lambda case, out, **k: seen.append(case.name) or {
        "exit_code": 0, "status": "steady", "roll_force": 1.0})
    monkeypatch.setattr(passes, "run_compare", lambda case, out, **k: seen.append(case.name)
                        or {"rows": []})
    assert _cli("run", "thin_strip", "--out", str(tmp_path / "a")).exit_code == 0
    assert _cli("run", "2", "--out", str(tmp_path / "b")).exit_code == 0
    r = _cli("sweep", "thin_strip", "--param", "friction.mu", "--values", "0.25",
             "--out", str(tmp_path / "c"))
    assert r.exit_code == 0, r.output
    assert _cli("compare", "thin_strip", "--out", str(tmp_path / "d")).exit_code == 0
    assert seen == ["thin_strip", "example2", "thin_strip friction.mu=0.25", "thin_strip"]


@pytest.mark.parametrize("command,kinds", [
    (["run"], ["cases"]), (["sweep", "--param", "material.m", "--values", "0.2"], ["cases"]),
    (["compare"], ["cases"]), (["schedule"], ["schedules"]), (["study"], ["studies"])])
def test_an_unknown_name_is_refused_listing_the_bundled_names(tmp_path, command, kinds):
    r = _cli(command[0], "no_such_thing", *command[1:], "--out", str(tmp_path))
    assert r.exit_code == 2
    text = _flat(r.output)
    assert f"{command[0]}: no_such_thing is neither a file nor a bundled" in text
    for kind in kinds:
        folder = HERE / kind
        names = ", ".join(sorted(p.stem for p in folder.glob("*.toml")))
        assert f"bundled {kind}: {names}" in text
    assert not (tmp_path / "no_such_thing").exists()


def test_validate_refuses_an_unknown_name_listing_all_three_kinds():
    r = _cli("validate", "no_such_thing")
    assert r.exit_code == 2
    text = _flat(r.output)
    assert "thin_strip" in text and "finishing_mill" in text and "af_study" in text


# ------------------------------------------------------------------ validate
@pytest.mark.parametrize("data,kind", [
    ({"pass": {"roll_radius": 0.3}}, "case"), ({}, "case"),
    ({"pass": [{"roll_radius": 0.3}]}, "schedule"), ({"strip": {}}, "schedule"),
    ({"mill": {}}, "schedule"), ({"base": {}}, "study"), ({"vary": {}}, "study"),
    ({"cases": [{}], "pass": [{}]}, "study"), ({"cases_file": "x.csv"}, "study")])
def test_the_kind_of_a_file_is_told_from_its_keys(data, kind):
    assert file_kind(data) == kind


@pytest.mark.parametrize("name", sorted(p.stem for p in (HERE / "schedules").glob("*.toml")))
def test_validate_a_bundled_schedule(name):
    r = _cli("validate", name)
    assert r.exit_code == 0, r.output
    text = _flat(r.output)
    n = text.count("│ F")
    assert f"{schedule_path(name)}: a valid schedule, {name!r}, {n} passes" in text and n >= 6
    assert "checked: every key against the schedule schema" in text
    # the passes as given, with units: F1 of finishing_mill exits at 20.5 mm, R = 350 mm
    assert "R mm" in text and "exit h mm" in text and "U m/s" in text
    r2 = _cli("validate", str(schedule_path(name)))
    assert r2.exit_code == 0 and r2.output == r.output


def test_validate_a_schedule_shows_its_passes_as_given():
    r = _cli("validate", "finishing_mill")
    row = next(x for x in r.output.splitlines() if x.startswith("│ F1"))
    assert [c.strip() for c in row.strip("│").split("│")] == [
        "F1", "350.0", "20.50", "-", "1", "-", "0", "0", "5.5 m"]


@pytest.mark.parametrize("name,n", [("af_study", 8), ("mesh_table", 6), ("report_examples", 4)])
def test_validate_a_bundled_study(name, n):
    r = _cli("validate", name)
    assert r.exit_code == 0, r.output
    text = _flat(r.output)
    assert f"{study_path(name)}: a valid study, {name!r}, {n} combinations" in text
    assert f"{n} of {n} combinations valid" in text
    assert "checked: the study's keys" in text


def test_validate_af_study_names_the_varied_key_with_its_unit():
    text = _flat(_cli("validate", "af_study").output)
    assert "varied: friction.a_f [m^-m]: 1, 2, 5, 10, 20, 50, 100, estimate" in text


@pytest.mark.parametrize("kind,old,new,field", [
    ("schedule", "thickness = 0.035 ", "thickness = -0.035 ", "strip.thickness"),
    ("schedule", "exit_thickness = 0.0126", "exit_thickness = 0.0226", "pass[2].exit_thickness"),
    ("schedule", 'speeds = "mass_flow"', 'speeds = "fast"', "mill.speeds"),
    ("study", '"friction.a_f" = [', '"friction_a_f" = [', "'friction_a_f'"),
    ("study", 'example = "example1"', 'example = "example9"', "base.example"),
])
def test_validate_a_broken_schedule_or_study_names_the_field(tmp_path, kind, old, new, field):
    src = schedule_path("finishing_mill") if kind == "schedule" else study_path("af_study")
    text = src.read_text()
    assert old in text
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace(old, new, 1))
    r = _cli("validate", str(bad))
    assert r.exit_code == 2, r.output
    out = _flat(r.output)
    assert f"{bad}: read as a {kind} file" in out and field in out, out


def test_validate_a_case_says_what_it_checked_and_stays_toml():
    from hotroll.config.case import case_from_toml

    r = _cli("validate", "thin_strip")
    assert r.exit_code == 0, r.output
    first = r.output.splitlines()[0]
    assert first.startswith("# ") and "a valid case file" in first and "unit" in first
    assert case_from_toml(r.output).name == "thin_strip"


def test_validate_a_file_that_is_not_toml(tmp_path):
    bad = tmp_path / "x.toml"
    bad.write_text("[pass\n")
    r = _cli("validate", str(bad))
    assert r.exit_code == 2 and "TOML syntax error" in r.output


# ------------------------------------------------------------------ tables keep every figure
ROW = {"name": "F1", "entry_thickness": 0.035, "exit_thickness": 0.0215,
       "roll_surface_speed": 1.234, "roll_force": 8.5e6, "roll_torque": 3.2e5,
       "exit_temperature_mean": 1301.25, "exit_strain_mean": 0.5617, "fe_solves": 3,
       "wall_time": 4.56, "roll_radius": 0.35, "roll_equivalent_radius": 0.3549,
       "gap_setting": 0.0161234, "front_tension": 12.5e6, "drx_onset_share": 0.625,
       "recrystallised_fraction_mean": 0.98765, "grain_size_mean": 31.26e-6,
       "retained_strain_mean": 0.00432}


@pytest.fixture
def mill(monkeypatch):
    """finishing_mill_elastic with tensions from the speeds, the rows faked: the widest
    schedule table (14 columns)."""
    from hotroll.config.schedule import load_schedule

    sch = load_schedule(schedule_path("finishing_mill_elastic"))
    sch.mill.tensions = "from_speeds"
    monkeypatch.setattr(runs, "load_schedule", lambda f: sch)
    monkeypatch.setattr(runs, "run_schedule", lambda *a, **k: [ROW])
    return sch


FIGURES = ["35.0>21.5", "1.23", "12.50", "12.75", "480", "1301.2", "0.562", "1.0140", "16.123",
           "0.62", "0.988", "31.3", "0.004", "3", "4.6"]


def test_a_piped_schedule_table_keeps_every_figure(tmp_path, mill):
    """Not a terminal (CliRunner, a pipe, a log): the table at its full width, the gap to set
    16.123 mm whole, not "16.…"."""
    r = _cli("schedule", "finishing_mill", "--out", str(tmp_path))
    assert r.exit_code == 0, r.output
    row = next(x for x in r.output.splitlines() if x.startswith("│ F1"))
    assert [c.strip() for c in row.strip("│").split("│")][1:] == FIGURES
    assert "…" not in r.output
    # and no line of text wrapped at 80 columns: the note with both paths is one line
    assert any(line.endswith(f"transports) in {tmp_path / 'schedule.csv'}; figure "
                             f"{tmp_path / 'schedule.png'}") and line.startswith("force and ")
               for line in r.output.splitlines())


def test_a_schedule_table_at_80_columns_keeps_every_figure(tmp_path, mill, monkeypatch):
    """A terminal of 80 columns: the table printed at the width it needs (the terminal may
    fold the line) rather than its figures cut."""
    buf = io.StringIO()
    monkeypatch.setattr(runs, "console", Console(file=buf, force_terminal=True, width=80,
                                                 color_system=None))
    r = _cli("schedule", "finishing_mill", "--out", str(tmp_path))
    assert r.exit_code == 0, r.output
    row = next(x for x in buf.getvalue().splitlines() if x.startswith("│ F1"))
    assert [c.strip() for c in row.strip("│").split("│")][1:] == FIGURES
    assert "…" not in buf.getvalue()


def test_schedule_as_json_and_csv_has_every_figure_unrounded(tmp_path, mill):
    """--format json|csv: the table's columns with the unit in brackets, the values unrounded
    (12.75 MN = 8.5e6 N/m x 1.5 m), h as two columns; the messages on stderr only."""
    r = _cli("schedule", "finishing_mill", "--out", str(tmp_path), "--format", "json")
    assert r.exit_code == 0, r.output
    (table,) = json.loads(r.stdout)
    (row,) = table["rows"]
    assert table["title"] == "finishing_mill_elastic: schedule"
    assert row["h in [mm]"] == pytest.approx(35.0) and row["h out [mm]"] == pytest.approx(21.5)
    assert row["F [MN]"] == pytest.approx(12.75, rel=1e-15)
    assert row["gap [mm]"] == pytest.approx(16.1234, rel=1e-15)
    assert row["t front [MPa]"] == pytest.approx(12.5) and row["R'/R"] == 0.3549 / 0.35
    assert row["T out [K]"] == 1301.25 and row["FE"] == 3 and row["s"] == 4.56
    assert "rolling" in r.stderr and "rolling" not in r.stdout
    r = _cli("schedule", "finishing_mill", "--out", str(tmp_path), "--format", "csv")
    assert r.exit_code == 0, r.output
    (row,) = list(csv.DictReader(io.StringIO(r.stdout)))
    assert float(row["gap [mm]"]) == pytest.approx(16.1234, rel=1e-15)
    assert float(row["d [um]"]) == pytest.approx(31.26, rel=1e-14)
    assert row["pass"] == "F1"


def test_run_as_csv_is_the_summary_in_si_units(tmp_path, monkeypatch):
    summary = {"exit_code": 0, "status": "steady", "roll_force": 7.61234567e6,
               "roll_torque": 123456.789, "forward_slip": 0.0361441234, "converged": True,
               "a_f": float("nan")}
    monkeypatch.setattr(passes, "run_case", lambda *a, **k: summary)
    r = _cli("run", "thin_strip", "--out", str(tmp_path), "--format", "csv")
    assert r.exit_code == 0, r.output
    rows = {x["quantity"]: x for x in csv.DictReader(io.StringIO(r.stdout))}
    assert float(rows["roll_force"]["value"]) == 7.61234567e6
    assert rows["roll_force"]["unit"] == "N/m" and rows["roll_torque"]["unit"] == "N m/m"
    assert float(rows["forward_slip"]["value"]) == 0.0361441234
    assert rows["a_f"]["value"] == ""                                # NaN: no figure
    assert "running thin_strip" in r.stderr and "running" not in r.stdout
    r = _cli("run", "thin_strip", "--out", str(tmp_path), "--format", "json")
    (table,) = json.loads(r.stdout)
    byq = {x["quantity"]: x for x in table["rows"]}
    assert byq["roll_force"] == {"quantity": "roll_force", "value": 7.61234567e6, "unit": "N/m"}


#: The display units of ``results.engineering.display`` and their SI factor, by hand.
SCALE = {"MN/m": 1e6, "MN": 1e6, "kN m/m": 1e3, "kN m": 1e3, "kW/m": 1e3, "kW": 1e3,
         "MPa": 1e6}


def _close(printed: str, value: float, unit: str) -> bool:
    """``printed`` (in ``unit``) is ``value`` (SI) to the printed precision."""
    scale = SCALE.get(unit, 1.0)
    place = Decimal(printed).as_tuple().exponent
    return abs(float(printed) * scale - value) <= 0.5001 * 10.0 ** place * scale


def test_a_real_run_piped_prints_every_figure_and_its_files_are_readable(tmp_path):
    """``hotroll run`` of a coarse Example 1 pass, stdout a pipe, COLUMNS=80, umask 022: every
    number of the table is summary.json's to the printed digits (in the printed unit), none
    cut; every figure of the table's keys that summary.json has is printed; every file written
    is readable by the group and the others (0o644: the atomic writer's temporary file is
    created 0o600)."""
    case = tmp_path / "ex1c.toml"
    case.write_text(EX1_COARSE_TOML)
    out = tmp_path / "out"
    old = os.umask(0o022)
    try:
        proc = subprocess.run([sys.executable, "-m", "hotroll.cli", "run", str(case), "--out",
                               str(out)], capture_output=True, text=True, timeout=600,
                              env={**os.environ, "COLUMNS": "80"})
    finally:
        os.umask(old)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "…" not in proc.stdout
    first = proc.stdout.splitlines()[0]                # not wrapped at 80 columns
    assert first.startswith(f"running ex1c -> {out} (about ") and first.endswith(" GB))")
    summary = json.loads((out / "summary.json").read_text())
    rows = [[c.strip() for c in line.strip("│").split("│")]
            for line in proc.stdout.splitlines() if line.startswith("│")]
    checked = set()
    for key, text, unit in rows:
        value = summary[key]
        if isinstance(value, bool) or not isinstance(value, (int, float, list)):
            assert text == str(value), key
            continue
        values = value if isinstance(value, list) else [value]
        printed = text.split(", ")
        assert len(printed) == len(values), key
        for p, v in zip(printed, values):
            assert _close(p, v, unit), (key, p, v, unit)
        checked.add(key)
    numeric = {k for k in passes.SUMMARY_KEYS if isinstance(summary.get(k), (int, float))
               and not isinstance(summary.get(k), bool) and summary[k] == summary[k]}
    assert numeric <= checked | {"neutral_angle", "neutral_point"} and len(checked) >= 12
    files = [p for p in out.rglob("*") if p.is_file()]
    assert files and all(p.stat().st_mode & 0o777 == 0o644 for p in files), [
        (p.name, oct(p.stat().st_mode & 0o777)) for p in files]


# ------------------------------------------------------------------ umask
@pytest.mark.parametrize("mask,mode", [(0o022, 0o644), (0o027, 0o640), (0o077, 0o600),
                                       (0o002, 0o664)])
def test_atomic_writes_follow_the_umask(tmp_path, mask, mode):
    path = tmp_path / "x.csv"
    old = os.umask(mask)
    try:
        with atomic(path) as tmp:
            tmp.write_text("a\n")
    finally:
        os.umask(old)
    assert path.read_text() == "a\n" and path.stat().st_mode & 0o777 == mode
    assert os.umask(old) == old                                # the umask restored


def test_the_umask_is_read_without_being_changed():
    from hotroll.files import umask

    old = os.umask(0o027)
    try:
        assert umask() == 0o027 and umask() == 0o027
    finally:
        os.umask(old)


# ------------------------------------------------------------------ the time left
class _Clock:
    def __init__(self, *times: float):
        self.times = list(times)

    def __call__(self) -> float:
        return self.times.pop(0)


def test_a_time_stepped_runs_progress_gives_the_time_left(monkeypatch):
    """Steps at 0.1 s and 0.2 s of simulated time, 10 s of wall time apart; end_time 1 s:
    100 s of wall time per simulated second, 0.8 s left: 80 s."""
    lines = []
    monkeypatch.setattr(passes.console, "print", lambda text, **k: lines.append(str(text)))
    p = passes._Progress(every=0.0, end_time=1.0, clock=_Clock(100.0, 110.0, 115.0))
    p({"step": 1, "time": 0.1})
    p({"step": 2, "time": 0.2})
    p({"step": 3, "time": 0.25})               # 15 s for 0.15 s: 100 s/s, 0.75 s left
    assert "ETA" not in lines[0]
    assert "ETA about 80 s (estimate from the steps so far, to end_time 1 s" in lines[1]
    assert "ETA about 75 s (estimate" in lines[2]
    steady = []
    monkeypatch.setattr(passes.console, "print", lambda text, **k: steady.append(str(text)))
    q = passes._Progress(every=0.0, end_time=None, clock=_Clock(0.0, 5.0))
    q({"step": 0, "time": float("nan")})
    q({"step": 1, "time": float("nan")})
    assert not any("ETA" in x for x in steady)         # a steady solve: no total known


def test_the_end_time_is_the_cases_or_the_automatic_one_capped_by_the_steps():
    from hotroll.config.case import load_case
    from hotroll.examples import example_path
    from hotroll.solvers.settling import default_end_time

    case = load_case(example_path("example1"))
    t = case.with_overrides(**{"solver.method": "transient", "solver.end_time": 0.5})
    assert passes._end_time(t) == 0.5
    auto = case.with_overrides(**{"solver.method": "transient", "solver.end_time": None})
    assert passes._end_time(auto) == pytest.approx(default_end_time(case.pass_.roll_pass()))
    few = t.with_overrides(**{"solver.max_steps": 3})
    assert passes._end_time(few) == pytest.approx(3 * case.dt)
    assert passes._end_time(case.with_overrides(**{"solver.method": "steady"})) is None


def test_a_schedules_passes_give_the_time_left(monkeypatch):
    """Four passes: F1 done 10 s after the start, F2 20 s later, F3 15 s after F2: 15 s a
    pass; a warning line of F2 is not a pass."""
    lines = []
    monkeypatch.setattr(runs.console, "print", lambda text, **k: lines.append(str(text)))
    clock = runs._PassClock(["F1", "F2", "F3", "F4"],
                            clock=_Clock(0.0, 10.0, 30.0, 31.0, 45.0, 60.0))
    clock("F1: 35.00 -> 20.50 mm, ...")
    clock("F2: 20.50 -> 12.60 mm, ...")
    clock("F2: WARNING: the gap to set is negative")      # not a pass
    clock("F3: 12.60 -> 8.40 mm, ...")
    clock("F4: 8.40 -> 6.10 mm, ...")
    assert lines[0].endswith("; ETA about 30 s (estimate from 1 pass so far)")
    assert lines[1].endswith("; ETA about 30 s (estimate from 2 passes so far)")
    assert lines[2] == "  F2: WARNING: the gap to set is negative"
    assert lines[3].endswith("; ETA about 15 s (estimate from 3 passes so far)")
    assert "ETA" not in lines[4]


def test_the_tensions_rolls_are_not_counted_as_passes(monkeypatch):
    """from_speeds: between "tensions" lines whole rolls run unprinted; the first pass after
    one is not measured (its interval holds those rolls), the ETA is this roll's."""
    lines = []
    monkeypatch.setattr(runs.console, "print", lambda text, **k: lines.append(str(text)))
    clock = runs._PassClock(["F1", "F2"], clock=_Clock(0.0, 10.0, 20.0, 21.0, 500.0, 504.0))
    clock("F1: ...")
    clock("F2: ...")
    clock("tensions [0] kPa: largest flux difference 1e-2")
    clock("F1: ...")                           # 479 s after: the unprinted rolls
    clock("F2: ...")
    assert lines[3].endswith("; ETA about 10 s (estimate from 2 passes so far) for this roll "
                             "through the mill; the tensions' iterations follow")


def test_a_studys_progress_labels_its_estimate():
    text = runs._study_info({"done": 2, "failed": 1, "running": 2, "remaining_s": 150.0})
    assert text == ("failed 1, running 2, ETA about 2.5 min (estimate from the cases solved "
                    "so far)")
    assert "ETA" not in runs._study_info({"done": 0, "failed": 0, "remaining_s": float("nan")})


def test_a_sweep_gives_the_time_left_after_each_run(tmp_path, monkeypatch):
    class Time:
        t = iter([0.0, 12.0, 12.0, 20.0, 20.0, 30.0])

        @staticmethod
        def monotonic():
            return next(Time.t)

    monkeypatch.setattr(passes, "time", Time)
    monkeypatch.setattr(passes, "_Progress", lambda **k: None)
    monkeypatch.setattr(passes, "run_case", lambda *a, **k: {"exit_code": 0, "roll_force": 1.0})
    r = _cli("sweep", "example1", "--param", "material.m", "--values", "0.1,0.2,0.3",
             "--out", str(tmp_path))
    assert r.exit_code == 0, r.output
    text = _flat(r.output)
    # 12 s for the first: 24 s for two; 12 and 8 s: 10 s for the last
    assert "1 of 3 runs done; ETA about 24 s (estimate from the 1 run so far) for the 2 left" in text
    assert "2 of 3 runs done; ETA about 10 s (estimate from the 2 runs so far) for the 1 left" in text
    assert "3 of 3" not in text


def test_durations_carry_their_unit():
    from hotroll.cli.common import duration

    assert [duration(s) for s in (0.4, 119.0, 150.0, 7199.0, 9000.0)] == [
        "0 s", "119 s", "2.5 min", "120.0 min", "2.5 h"]
