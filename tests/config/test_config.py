"""Case description: loading, validation messages, round trips and the CLI front end."""

import math
import types

import pytest
from typer.testing import CliRunner

from hotroll.cli import app, passes
from hotroll.config.case import (
    MESH_TABLE,
    Case,
    CaseError,
    case_from_dict,
    case_from_toml,
    load_case,
)
from hotroll.examples import EXAMPLES, example_path

NAMES = ["example1", "example2", "example3_m015", "example3_m025"]


@pytest.fixture
def base() -> dict:
    return load_case(example_path("example1")).to_dict()


def problems(data: dict) -> str:
    with pytest.raises(CaseError) as info:
        case_from_dict(data)
    return str(info.value)


@pytest.mark.parametrize("name", NAMES)
def test_examples_load(name):
    case = load_case(example_path(name))
    p = case.pass_
    assert case.name == name
    assert (p.roll_radius, p.half_entry, p.half_exit, p.roll_axis_x) == (0.6, 0.25, 0.2, 1.0)
    assert p.roll_centre == (1.0, 0.8)
    assert p.contact_length == pytest.approx(math.sqrt(0.6**2 - 0.55**2))
    assert p.bite_angle == pytest.approx(math.acos(1 - 0.05 / 0.6))
    assert case.material.K == 1.0 and case.material.eps0 == 1e-4
    assert case.friction.a_f == "estimate" and case.mesh.h == MESH_TABLE["C2"]
    assert case.dt == pytest.approx(4.2e-3 / 6)


def test_example_parameters():
    omega = {n: load_case(example_path(n)).pass_.roll_angular_velocity for n in NAMES}
    m = {n: load_case(example_path(n)).material.m for n in NAMES}
    assert omega["example1"] == pytest.approx(math.pi / 3)
    assert omega["example2"] == pytest.approx(math.pi / 6)
    assert [m[n] for n in EXAMPLES["3"]] == [0.15, 0.2, 0.25]
    with pytest.raises(FileNotFoundError):
        example_path("nope")


@pytest.mark.parametrize("name,h", list(MESH_TABLE.items()))
def test_mesh_table(base, name, h):
    base["mesh"]["h_contact"] = name.lower()
    assert case_from_dict(base).mesh.h == h


def test_table_values():
    assert MESH_TABLE == {"C1": 5.02e-3, "C2": 4.2e-3, "M1": 3.7e-3, "M2": 3.01e-3,
                          "F1": 2.7e-3, "F2": 2.02e-3}


@pytest.mark.parametrize("section,key,value,expected", [
    ("pass", "roll_radius", 0.0, "pass.roll_radius: must be > 0"),
    ("pass", "entry_thickness", -0.5, "pass.entry_thickness: must be > 0"),
    ("pass", "roll_angular_velocity", 0, "pass.roll_angular_velocity: must be > 0"),
    ("plate", "length", -4.0, "plate.length: must be > 0"),
    ("mesh", "h_contact", 0.0, "mesh.h_contact: must be"),
    ("mesh", "h_contact", "Z9", "mesh.h_contact: must be \"auto\", one of C1"),
    ("pass", "exit_thickness", 0.5, "pass.exit_thickness: must be smaller than pass.entry_thickness"),
    ("pass", "exit_thickness", 0.6, "pass.exit_thickness: must be smaller"),
    ("material", "m", 0.0, "material.m: must be in (0, 1], got 0.0"),
    ("material", "m", -0.2, "material.m: must be in (0, 1], got -0.2"),
    ("material", "m", 1.5, "material.m: must be in (0, 1], got 1.5"),
    ("pass", "roll_radius", 0.04, "pass.roll_radius: must exceed the draft"),
    ("pass", "foo", 1, "pass.foo: unknown key (allowed: roll_radius"),
    ("friction", "a_f", "foo", 'friction.a_f: must be "estimate" or a number > 0'),
    ("friction", "a_f", -1, "friction.a_f: must be"),
    ("plate", "length", 0.5, "plate.length: must be >= 3 x projected contact length"),
    ("mesh", "h_contact", 0.1, "mesh.h_contact: must be < contact_length/4"),
    ("mesh", "h_contact", 0.06, "mesh.h_contact: must be <= exit half-thickness/4 = 0.05 m"),
    ("solver", "max_iterations", 0, "solver.max_iterations: must be an integer >= 1"),
    ("solver", "nonlinear", "bfgs", "solver.nonlinear:"),
])
def test_bad_values(base, section, key, value, expected):
    base[section][key] = value
    assert expected in problems(base)


def test_unknown_and_missing_sections(base):
    base["foo"] = {"x": 1}
    del base["plate"]
    msg = problems(base)
    assert "foo: unknown section" in msg and "plate: missing required section" in msg


def test_all_problems_reported(base):
    base["pass"]["roll_radius"] = -1
    base["material"]["m"] = 2
    base["mesh"]["bogus"] = 1
    msg = problems(base)
    assert all(s in msg for s in ["pass.roll_radius", "material.m", "mesh.bogus"])
    assert "pass_" not in msg


def test_bad_files(tmp_path):
    with pytest.raises(CaseError, match="cannot read"):
        load_case(tmp_path / "missing.toml")
    with pytest.raises(CaseError, match="TOML syntax error"):
        case_from_toml("[pass\nroll_radius = 1")


@pytest.mark.parametrize("name", NAMES)
def test_toml_round_trip(name):
    case = load_case(example_path(name)).with_overrides(
        **{"friction.a_f": 12.5, "friction.v_reg": 1e-5, "solver.end_time": 0.3,
           "mesh.h_contact": 3e-3, "output.vtk": False, "name": 'odd "name" é'})
    again = case_from_toml(case.to_toml())
    assert again == case and again.to_toml() == case.to_toml()


def test_with_overrides():
    case = load_case(example_path("example1"))
    new = case.with_overrides(**{"mesh.h_contact": "C1", "solver.end_time": 0.3,
                                 "pass_.roll_axis_x": 2.0})
    assert new.mesh.h == 5.02e-3 and new.solver.end_time == 0.3 and new.pass_.roll_axis_x == 2.0
    assert case.mesh.h_contact == "C2" and case.solver.end_time is None  # original unchanged
    with pytest.raises(CaseError, match="material.m"):
        case.with_overrides(**{"material.m": 0})
    with pytest.raises(CaseError, match="solver.foo: unknown key"):
        case.with_overrides(**{"solver.foo": 1})


def test_derived_helpers():
    case = load_case(example_path("example1"))
    u = case.pass_.roll_surface_speed
    assert u == pytest.approx(0.6 * math.pi / 3)
    assert case.friction.regularisation_velocity(u) == pytest.approx(1e-4 * u)
    assert case.with_overrides(**{"friction.v_reg": 0.01}).friction.regularisation_velocity(u) == 0.01
    assert case.with_overrides(**{"solver.time_step": 1e-3}).dt == 1e-3
    assert isinstance(Case.model_fields["pass_"].description, str)
    for model in (type(case.pass_), type(case.material), type(case.solver)):
        for f in model.model_fields.values():
            assert "allowed" in f.description


# ------------------------------------------------------------------------ CLI

runner = CliRunner()


def test_cli_validate_ok():
    result = runner.invoke(app, ["validate", str(example_path("example2"))])
    assert result.exit_code == 0, result.output
    assert case_from_toml(result.output).pass_.roll_angular_velocity == pytest.approx(math.pi / 6)
    # Example 2 (R 0.6 m, 0.5 -> 0.4 m, omega pi/6, C2): draft 0.05 m a roll, so the bite
    # angle is acos(11/12), the projected contact R sin(alpha) = 0.05 sqrt(23) m, U = 0.1 pi
    # m/s, h = 4.2 mm and dt = h/6 = 0.7 ms (by hand)
    derived = [line for line in result.output.splitlines() if line.startswith("# derived:")]
    assert derived == [(
        f"# derived: contact_length = {0.05 * math.sqrt(23):.6g} m, bite_angle = "
        f"{math.acos(11 / 12):.6g} rad, roll_surface_speed = {0.1 * math.pi:.6g} m/s, "
        f"h_contact = 0.0042 m, dt = 0.0007 s")]
    # Example 2 is nondimensional (K = 1 Pa s^m): said after the derived line (plausibility)
    assert "# warning: material: the flow stress at the pass's estimated state" in result.output


def test_cli_validate_bad(tmp_path):
    text = example_path("example1").read_text().replace("m = 0.2 ", "m = -0.2 ")
    bad = tmp_path / "bad.toml"
    bad.write_text(text)
    result = runner.invoke(app, ["validate", str(bad)])
    assert result.exit_code == 2
    assert "material.m" in result.output and "(0, 1]" in result.output


def test_cli_meshes():
    """The report's Table 2 as the command prints it, row by row (h and h/6 by hand)."""
    result = runner.invoke(app, ["meshes"])
    assert result.exit_code == 0 and "Table 2: contact mesh sizes" in result.output
    lines = result.output.splitlines()
    head = next(line for line in lines if "name" in line)
    assert [c.strip() for c in head.strip("┃ ").split("┃")] == ["name", "h_contact [m]",
                                                              "dt = h/6 [s]"]
    rows = [[c.strip() for c in line.strip("│ ").split("│")] for line in lines
            if line.startswith("│")]
    assert rows == [["C1", "0.00502", "0.0008367"], ["C2 (default)", "0.0042", "0.0007"],
                    ["M1", "0.0037", "0.0006167"], ["M2", "0.00301", "0.0005017"],
                    ["F1", "0.0027", "0.00045"], ["F2", "0.00202", "0.0003367"]]
    c1 = next(line for line in lines if line.startswith("│ C1"))
    assert c1.split("│")[2].endswith("0.00502 ")            # numbers right-aligned


@pytest.fixture
def fake_runner(monkeypatch):
    calls = []

    def run_case(case, out, *, resume=True, progress=None, sweep=None):
        calls.append((case, out, resume))
        progress and progress({"step": 1, "time": 0.1, "message": "started"})
        return {"roll_force": 1.25, "converged": True, "steps": 3, "exit_code": 0}

    monkeypatch.setattr(passes, "run_case", run_case)      # where the command line calls it
    return calls


def test_cli_run_overrides(tmp_path, fake_runner):
    result = runner.invoke(app, ["run", str(example_path("example1")), "--out", str(tmp_path),
                                 "--mesh", "F1", "--end-time", "0.2", "--nonlinear", "picard",
                                 "--no-figures", "--no-resume"])
    assert result.exit_code == 0, result.output
    (case, out, resume), = fake_runner
    assert (case.mesh.h, case.solver.end_time, case.solver.nonlinear) == (2.7e-3, 0.2, "picard")
    assert case.output.figures is False and resume is False and out == tmp_path
    assert "roll_force" in result.output and "1.25" in result.output
    assert "example1: summary" in result.output                 # the table's title


def test_cli_progress_is_throttled_but_messages_always_show(monkeypatch):
    """cli/passes._Progress: within ``every`` seconds of the last line a plain update is
    dropped and one with a message is printed (its keys in PROGRESS_KEYS order, units from
    results/units.py); after ``every`` seconds a plain update is printed too."""
    import time

    progress = passes._Progress(every=3600.0)
    progress.last = time.monotonic()                          # a line was just printed
    with passes.console.capture() as cap:
        progress({"step": 2, "roll_force": 1.5})
    assert cap.get() == ""
    with passes.console.capture() as cap:
        progress({"message": "mesh refined", "step": 3})
    assert cap.get().split() == ["step=3", "message=mesh", "refined"]
    progress.last = time.monotonic() - 3601.0
    with passes.console.capture() as cap:
        progress({"step": 4})
    assert cap.get().split() == ["step=4"]


def test_cli_bad_option_before_run(tmp_path, fake_runner):
    result = runner.invoke(app, ["example", "3", "--out", str(tmp_path), "--mesh", "0.5"])
    assert result.exit_code == 2 and "mesh.h_contact" in result.output and not fake_runner
    assert runner.invoke(app, ["example", "7", "--out", str(tmp_path)]).exit_code == 2


def test_cli_example3(tmp_path, fake_runner, monkeypatch):
    compared = {}
    fake_plots = types.SimpleNamespace(plot_compare=lambda runs, png: compared.update(runs=runs, png=png))
    monkeypatch.setattr(passes, "plot_compare", fake_plots.plot_compare)
    monkeypatch.setattr(passes.console, "width", 400)      # long paths: no line wrapped
    result = runner.invoke(app, ["example", "3", "--out", str(tmp_path), "--end-time", "0.1"])
    assert result.exit_code == 0, result.output
    assert [c.material.m for c, _, _ in fake_runner] == [0.15, 0.2, 0.25]
    assert list(compared["runs"]) == ["m = 0.15", "m = 0.2", "m = 0.25"]
    assert compared["runs"]["m = 0.2"] == tmp_path / "example1"
    assert compared["png"] == tmp_path / "compare.png"
    # the figure code returned no path (here: None): the path it was given is named
    assert f"comparison plot: {tmp_path / 'compare.png'}" in result.output


def test_cli_sweep(tmp_path, fake_runner):
    result = runner.invoke(app, ["sweep", str(example_path("example1")), "--param",
                                 "material.m", "--values", "0.15, 0.3", "--out", str(tmp_path),
                                 "--method", "steady", "--no-figures"])
    assert result.exit_code == 0, result.output
    assert [c.material.m for c, _, _ in fake_runner] == [0.15, 0.3]
    assert [out.name for _, out, _ in fake_runner] == ["material.m=0.15", "material.m=0.3"]
    assert all(c.solver.method == "steady" and not c.output.figures for c, _, _ in fake_runner)
    rows = (tmp_path / "sweep.csv").read_text().splitlines()
    assert rows[0].startswith("param,value,status") and len(rows) == 3
    assert rows[2].split(",")[:2] == ["material.m", "0.3"]


def test_cli_sweep_bad_value_before_run(tmp_path, fake_runner):
    result = runner.invoke(app, ["sweep", str(example_path("example1")), "--param",
                                 "material.m", "--values", "0.2,1.5", "--out", str(tmp_path)])
    assert result.exit_code == 2 and "material.m" in result.output and not fake_runner
    result = runner.invoke(app, ["sweep", str(example_path("example1")), "--param",
                                 "material.mm", "--values", "0.2", "--out", str(tmp_path)])
    assert result.exit_code == 2 and "mm" in result.output and not fake_runner


# --- [thermal] (issue 16) ---------------------------------------------------------------------
THERMAL = {"htc_contact": 2e4, "roll_temperature": 350.0, "htc_air": 20.0, "emissivity": 0.8}


def _steady(base):
    return {**base, "solver": {**base.get("solver", {}), "method": "steady"}}


def test_thermal_section_needs_the_strip_properties(base):
    """A [thermal] section without the material's density, specific heat and conductivity is
    refused naming each missing key; without [thermal] they are not needed."""
    assert case_from_dict(base).thermal is None
    text = problems({**_steady(base), "thermal": THERMAL})
    for key in ("density", "specific_heat", "conductivity"):
        assert f"material.{key}: missing, required with a [thermal] section" in text


@pytest.mark.parametrize("section, key, value, expected", [
    ("thermal", "emissivity", 1.5, "thermal.emissivity: must be in [0, 1]"),
    ("thermal", "taylor_quinney", -0.1, "thermal.taylor_quinney: must be in [0, 1]"),
    ("thermal", "htc_contact", -1.0, "thermal.htc_contact: must be >= 0 [W/(m^2 K)]"),
    ("thermal", "roll_temperature", 0.0, "thermal.roll_temperature: must be > 0 [K]"),
    ("material", "conductivity", [[1400.0, 30.0], [1000.0, 25.0]], "material.conductivity: must be"),
    ("material", "density", -7800.0, "material.density: must be"),
    ("material", "specific_heat", [[1000.0, 650.0]], "material.specific_heat: must be"),
])
def test_bad_thermal_input_names_the_field(base, section, key, value, expected):
    data = {**_steady(base), "thermal": dict(THERMAL)}
    data["material"] = {**base["material"], "density": 7600.0, "specific_heat": 650.0,
                        "conductivity": 30.0}
    data[section] = {**data[section], key: value}
    assert expected in problems(data)


def test_thermal_case_round_trips_with_tables(base):
    data = {**_steady(base), "thermal": THERMAL,
            "material": {**base["material"], "density": 7600.0, "conductivity": 30.0,
                         "specific_heat": [[1000.0, 600.0], [1400.0, 700.0]]}}
    case = case_from_dict(data)
    assert case.material.specific_heat == [(1000.0, 600.0), (1400.0, 700.0)]
    assert case.thermal.taylor_quinney == 0.9 and case.thermal.friction_heat_to_strip == 0.5
    assert case_from_toml(case.to_toml()) == case


def test_thermal_is_accepted_by_both_methods(base):
    data = {**base, "thermal": THERMAL,
            "material": {**base["material"], "density": 7600.0, "specific_heat": 650.0,
                         "conductivity": 30.0},
            "solver": {**base.get("solver", {}), "method": "transient"}}
    assert case_from_dict(data).thermal is not None
    data["solver"]["method"] = "steady"
    assert case_from_dict(data).thermal is not None


def test_the_case_reference_page_is_the_schema():
    """docs/reference/case.md's key tables are generated from the schema (plumbing): the page
    holds what ``scripts/reference_docs.py`` writes now, every section and key of the case in
    it with its unit (a new field or law shows up here until the page is regenerated)."""
    from pathlib import Path

    from hotroll.config.base import fields_of
    from hotroll.config.case import Case, MaterialConfig
    from hotroll.config.reference import case_keys_markdown, with_generated

    page = (Path(__file__).resolve().parents[2] / "docs" / "reference" / "case.md").read_text()
    assert with_generated(page) == page, "run: python scripts/reference_docs.py"
    block = case_keys_markdown()
    for section in ("pass", "plate", "material", "friction", "mesh", "solver", "contact",
                    "roll", "output", "thermal", "spread"):
        assert f"## [{section}]" in block
    assert "| `carbon` | none | wt % | in [0, 1.2] |" in block
    assert all(f"| `{key}` |" in block for key in fields_of(MaterialConfig))
    assert len(fields_of(Case)) == 12


def test_cli_example_options_reach_the_case(tmp_path, monkeypatch):
    """``hotroll example``: each option lands in the case handed to the runner, the worst
    run's exit code ends the command, an unknown name lists the examples."""
    seen = []

    def run_case(case, out, *, resume=True, progress=None, sweep=None):
        seen.append((case, out, resume, sweep))
        return {"roll_force": 1.0, "exit_code": 5 if case.material.m == 0.2 else 0}

    from hotroll.cli import common

    monkeypatch.setattr(passes, "run_case", run_case)
    monkeypatch.setattr(passes, "plot_compare", lambda runs, png: png)
    monkeypatch.setattr(common.console, "width", 400)      # long paths: no line wrapped
    monkeypatch.setattr(common.err_console, "width", 400)
    r = runner.invoke(app, ["example", "1", "--out", str(tmp_path), "--mesh", "C1",
                            "--end-time", "0.1", "--nonlinear", "picard", "--method",
                            "transient", "--force", "--no-resume"])
    assert r.exit_code == 5, r.output
    (case, out, resume, sweep), = seen
    assert (case.mesh.h, case.solver.end_time, case.solver.nonlinear) == (0.00502, 0.1, "picard")
    assert case.solver.method == "transient" and case.solver.force is True
    assert out == tmp_path and resume is False and sweep is None
    # the run's outcome on stderr: EXIT_CODES[5] = "not settled"; the status (none given)
    assert "example1: not settled (exit code 5; status None)" in r.output
    seen.clear()
    r = runner.invoke(app, ["example", "3", "--out", str(tmp_path)])
    assert r.exit_code == 5                                  # m = 0.2's run: the worst
    assert [c.solver.method for c, *_ in seen] == ["steady"] * 3
    assert all(c.solver.force is False for c, *_ in seen)
    assert [o for _, o, _, _ in seen] == [tmp_path / c.name for c, *_ in seen]
    assert len({id(s) for *_, s in seen}) == 1 and seen[0][3] is not None   # one shared sweep
    assert f"comparison plot: {tmp_path / 'compare.png'}" in r.output
    r = runner.invoke(app, ["example", "nope", "--out", str(tmp_path)])
    assert r.exit_code == 2
    assert f"example: unknown example 'nope' (allowed: {', '.join(EXAMPLES)})" in r.output


def test_fail_prints_on_stderr_and_gives_the_exit(capsys):
    """cli/common.py: fail, every refusal's way out: the message on stderr, unwrapped, the exit
    code 2 (bad input) unless told."""
    from hotroll.cli.common import fail

    long = "x" * 300
    e = fail(long)
    assert e.exit_code == 2 and fail("short", code=8).exit_code == 8
    out = capsys.readouterr()
    assert out.out == "" and long in out.err.replace("\n", "") and "short" in out.err
    assert out.err.splitlines()[0] == long                        # soft wrap: one line


def test_cli_sweep_table_names_and_warm_starts(tmp_path, monkeypatch):
    """hotroll sweep: each value's case named after it, one Sweep shared by the runs unless
    --cold, the table's columns and rows as the runs gave them, the worst exit code, and the
    refusal of an empty --values."""
    from hotroll.cli import common

    seen = []

    def run_case(case, out, *, resume=True, progress=None, sweep=None):
        seen.append((case, out, sweep))
        return {"status": "steady", "exit_code": 0 if len(seen) == 1 else 7,
                "roll_force": 1.5 * len(seen), "a_f": None, "warm_start_from": "x"}

    monkeypatch.setattr(passes, "run_case", run_case)
    monkeypatch.setattr(common.console, "width", 400)
    r = runner.invoke(app, ["sweep", str(example_path("example1")), "--param", "friction.a_f",
                            "--values", "5, estimate", "--out", str(tmp_path)])
    assert r.exit_code == 7, r.output
    assert [c.name for c, *_ in seen] == ["example1 friction.a_f=5", "example1 friction.a_f=estimate"]
    assert [o for _, o, _ in seen] == [tmp_path / "friction.a_f=5",
                                       tmp_path / "friction.a_f=estimate"]
    assert seen[0][2] is not None and seen[0][2] is seen[1][2]          # one Sweep, warm
    assert f"sweep table: {tmp_path / 'sweep.csv'}" in r.output
    head, first, second = (tmp_path / "sweep.csv").read_text().splitlines()
    assert head == ("param,value,status,exit_code,converged,neutral_angle,neutral,roll_force,"
                    "roll_torque,roll_power,forward_slip,a_f,nonlinear_iterations,wall_time_s,"
                    "warm_start_from,warm_start_failed")
    assert first == "friction.a_f,5.0,steady,0,,,,1.5,,,,,,,x,"
    assert second.startswith("friction.a_f,estimate,steady,7,,,,3.0,")
    seen.clear()
    r = runner.invoke(app, ["sweep", str(example_path("example1")), "--param", "material.m",
                            "--values", "0.2", "--out", str(tmp_path / "c"), "--cold",
                            "--mesh", "C1"])
    assert r.exit_code == 0 and seen[0][2] is None and seen[0][0].mesh.h == 0.00502
    r = runner.invoke(app, ["sweep", str(example_path("example1")), "--param", "material.m",
                            "--values", " , ", "--out", str(tmp_path / "e")])
    assert r.exit_code == 2 and "sweep: --values is empty" in r.output


def test_set_dotted_sets_keys_and_refuses_a_value_as_a_section():
    """set_dotted: ``section.key`` set in place (``pass_`` read as ``pass``, a missing section
    made); a dotted key through a value that is not a table is a CaseError naming both."""
    from hotroll.config.case import set_dotted

    data = {"name": "x", "pass": {"roll_radius": 0.6}}
    assert set_dotted(data, {"pass_.roll_radius": 0.5, "thermal.htc_air": 20.0}) is data
    assert data == {"name": "x", "pass": {"roll_radius": 0.5}, "thermal": {"htc_air": 20.0}}
    with pytest.raises(CaseError) as e:
        set_dotted(data, {"name.first": "y"})
    assert e.value.problems == ["name.first: 'name' is not a section"]
