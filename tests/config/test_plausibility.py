"""Plausibility of a case (issue 51, item 3; hotroll/config/plausibility.py): the unit slips a
user made are refused with the fix named, before anything runs; a pass outside its flow-stress
fit is reported with the figure and the range; Example 1 runs, named nondimensional."""
from __future__ import annotations

import copy
import math
import tomllib

import pytest

from hotroll.config import plausibility as P
from hotroll.config.case import CaseError, case_from_dict
from hotroll.examples import example_path


def _bundled(name: str) -> dict:
    return tomllib.loads(example_path(name).read_text())


def _in_mm(d: dict) -> dict:
    """The case written with its lengths in mm as plain numbers (the slip of issue 51)."""
    d = copy.deepcopy(d)
    for key in ("roll_radius", "entry_thickness", "exit_thickness"):
        d["pass"][key] *= 1000.0
    d["plate"]["length"] *= 1000.0
    d.get("mesh", {}).pop("h_contact", None)
    return d


def test_a_case_written_in_mm_is_refused_naming_the_fix():
    """hot_strip_finishing in mm: R = 350 m, 5000 m/s at the roll's surface: refused, each
    line naming its key, the figure and the fix (mm), before any mesh."""
    d = _in_mm(_bundled("hot_strip_finishing"))
    with pytest.raises(CaseError) as e:
        case_from_dict(d)
    text = "\n".join(e.value.problems)
    speed = d["pass"]["roll_radius"] * d["pass"]["roll_angular_velocity"]
    assert f"R omega = {speed:.4g} m/s is above 60 m/s" in text
    assert "pass.roll_radius: 350 m is above 2 m" in text
    assert text.count("the lengths look like mm") >= 2
    assert all(line.endswith("(solver.force = true or --force runs it anyway)")
               for line in e.value.problems if "above" in line)


def test_forced_a_slip_runs_as_written():
    d = _in_mm(_bundled("hot_strip_finishing"))
    d.setdefault("solver", {})["force"] = True
    assert case_from_dict(d).pass_.roll_radius == 350.0


@pytest.mark.parametrize("bound, key, value", [
    ("MAX_SURFACE_SPEED", "pass.roll_angular_velocity", 60.0),
    ("MAX_ROLL_RADIUS", "pass.roll_radius", 2.0),
    ("MAX_THICKNESS", "pass.entry_thickness", 1.0),
])
def test_each_unit_slip_bound_is_where_it_says(bound, key, value, monkeypatch):
    """Just below the bound runs, just above is refused naming the key (and 1.1 x the bound
    moves the verdict: a planted x 1.1 is caught)."""
    d = _bundled("roughing_slab")
    d.get("mesh", {}).pop("h_contact", None)
    R = d["pass"]["roll_radius"]

    def case_at(v: float) -> dict:
        e = copy.deepcopy(d)
        sec, name = key.split(".")
        if name == "roll_angular_velocity":
            e[sec][name] = v / R                       # the surface speed v
        elif name == "roll_radius":
            e[sec][name] = v
        else:                                            # keep the reduction
            e[sec]["exit_thickness"] = v * e[sec]["exit_thickness"] / e[sec][name]
            e[sec][name] = v
            e["plate"]["length"] = 50.0
        return e

    assert getattr(P, bound) == value
    case_from_dict(case_at(value * 0.99))
    with pytest.raises(CaseError) as e:
        case_from_dict(case_at(value * 1.01))
    assert any(p.startswith(key) for p in e.value.problems), e.value.problems
    monkeypatch.setattr(P, bound, value * 1.1)
    case_from_dict(case_at(value * 1.05))               # the planted bound lets it through


def test_a_grade_at_room_temperature_is_refused_as_a_degc_slip():
    d = _bundled("hot_strip_finishing")
    d["plate"]["temperature"] = 300.0
    with pytest.raises(CaseError) as e:
        case_from_dict(d)
    assert any(p.startswith("plate.temperature: 300 K (26.85 degC) is below 500 K")
               and 'write "300 degC"' in p for p in e.value.problems), e.value.problems


def test_a_steel_written_in_degc_as_kelvin_is_warned_with_the_fix():
    """1000 meant as degC runs as 1000 K = 726.85 degC, below the austenite (800 degC):
    warned, the fix named; at 1273.15 K no such warning."""
    d = _bundled("hot_strip_finishing")
    d["plate"]["temperature"] = 1000.0
    w = case_from_dict(d).warnings()
    assert any(x.startswith("plate.temperature: 1000 K (726.85 degC) is below 1073.15 K")
               and 'write "1000 degC"' in x for x in w), w
    d["plate"]["temperature"] = "1000 degC"
    assert not any(x.startswith("plate.temperature") for x in case_from_dict(d).warnings())


def test_a_pass_outside_its_grades_fit_is_warned_with_the_figure_and_the_range():
    """hot_aluminium (Al99.5, fit 250-550 degC): at 600 degC warned (50 K out), at 700 degC
    warned as far outside (150 K out) and still run (a fit range is not a refusal: Misaka's
    30-200 1/s would refuse every plate pass), inside not. The figure and the range in the
    line."""
    d = _bundled("hot_aluminium")
    lo, hi = 250.0 + 273.15, 550.0 + 273.15
    inside = case_from_dict(d)
    assert lo <= inside.plate.temperature <= hi
    assert not any(x.startswith("plate.temperature") for x in inside.warnings())
    d["plate"]["temperature"] = hi + 50.0
    w = case_from_dict(d).warnings()
    assert (f"plate.temperature: the estimated temperature {hi + 50:.4g} K is outside grade "
            f"Al99.5's fit range {lo:.4g} to {hi:.4g} K") in " ".join(w), w
    d["plate"]["temperature"] = hi + 150.0
    d["contact"] = {"strip_youngs_modulus": "off"}      # its E(T) ends at 600 degC
    w = case_from_dict(d).warnings()
    assert any("is far outside grade Al99.5's fit range" in x for x in w), w


def test_a_plate_pass_with_misaka_runs_warned():
    """A plate pass (R 0.55 m, 250 -> 225 mm, 1.4 m/s) with Misaka's law (fit 30-200 1/s) at
    about 1.4 1/s: warned far outside, not refused (the reviewer's case)."""
    d = _bundled("roughing_slab")
    d["pass"].update(roll_radius=0.55, entry_thickness=0.25, exit_thickness=0.225,
                     roll_angular_velocity=1.4 / 0.55)
    d["material"] = {"law": "misaka", "carbon": 0.2}
    d["plate"]["length"] = 2.0
    d.get("mesh", {}).pop("h_contact", None)
    c = case_from_dict(d)
    assert any(x.startswith("pass.roll_angular_velocity: the estimated strain rate")
               and "far outside the misaka law's fit range 30 to 200 1/s" in x
               for x in c.warnings()), c.warnings()


def test_the_estimated_rate_is_the_homogeneous_one_by_hand():
    """The pass estimates: strain (2/sqrt 3) ln(h0/h1), rate that strain x U / L."""
    c = case_from_dict(_bundled("hot_strip_finishing"))
    p = c.pass_
    e = P.pass_estimates(c)
    strain = 2 / math.sqrt(3) * math.log(p.entry_thickness / p.exit_thickness)
    L = math.sqrt(p.roll_radius * (p.entry_thickness - p.exit_thickness)
                  - (p.entry_thickness - p.exit_thickness) ** 2 / 4)
    assert e["strain"][1] == pytest.approx(strain, rel=1e-12)
    assert e["strain_rate"][0] == pytest.approx(
        strain * p.roll_radius * p.roll_angular_velocity / L, rel=1e-12)


def test_example_1_runs_and_is_named_nondimensional():
    c = case_from_dict(_bundled("example1"))
    w = c.warnings()
    assert len(w) == 1 and w[0].startswith("material: the flow stress at the pass's estimated "
                                           "state is") and "nondimensional" in w[0]
    real = case_from_dict(_bundled("hot_strip_finishing"))
    assert not any("nondimensional" in x for x in real.warnings())


def test_a_nondimensional_case_is_not_held_to_a_mills_speeds_and_sizes():
    """Example 1 (K = 1) at 100x its roll speed, or written per minute (the exact scalings of
    tests/solvers/test_contact.py), runs: its units are its own; the same speed with a grade
    is refused."""
    d = _bundled("example1")
    d["pass"]["roll_angular_velocity"] *= 100.0            # 62.8 m/s at R = 0.6 m
    d["material"]["eps0"] = 1e-2
    c = case_from_dict(d)
    assert c.pass_.roll_surface_speed > P.MAX_SURFACE_SPEED
    assert any("nondimensional" in w for w in c.warnings())
    real = _bundled("hot_strip_finishing")
    real["pass"]["roll_angular_velocity"] = 62.8 / real["pass"]["roll_radius"]
    with pytest.raises(CaseError):
        case_from_dict(real)


def test_a_run_reports_its_solved_state_against_the_fit(tmp_path):
    """hot_aluminium 40 K above Al99.5's fit (550 degC): the run's summary replaces the
    estimated line by the solved one (the same temperature: isothermal), and its strain rate,
    inside the fit, is not reported."""
    from hotroll.workflows.runner import run_case

    d = _bundled("hot_aluminium")
    d["plate"]["temperature"] = 550.0 + 273.15 + 40.0
    d.setdefault("output", {}).update(figures=False, vtk=False)
    case = case_from_dict(d)
    assert any(" the estimated temperature " in w for w in case.warnings())
    s = run_case(case, tmp_path / "al", resume=False)
    w = s["warnings"]
    assert not any(" the estimated " in x for x in w), w
    assert any(x.startswith(f"plate.temperature: the solved temperature {863.15:.4g} K is "
                            f"outside grade Al99.5's fit range 523.1 to 823.1 K") for x in w), w
    assert 0.01 <= s["mean_strain_rate"] <= 500.0
    assert not any("strain rate" in x for x in w)


def test_force_on_the_command_line_lets_a_refused_file_load(tmp_path):
    """``--force`` (``load_case(path, {"solver.force": True})``, the command line's overrides
    set before the one validation) lets a case the plausibility refuses load; without it the
    file is refused naming the key."""
    from hotroll.cli.passes import _load
    from hotroll.config.case import load_case

    d = _in_mm(_bundled("hot_strip_finishing"))
    lines = []
    for sec, table in d.items():
        if isinstance(table, dict):
            lines.append(f"[{sec}]")
            lines += [f"{k} = {v!r}".replace("'", '"') for k, v in table.items()]
    f = tmp_path / "mm.toml"
    f.write_text("\n".join(lines) + "\n")
    with pytest.raises(CaseError) as e:
        load_case(f)
    assert any(p.startswith("pass.roll_radius") for p in e.value.problems)
    assert load_case(f, {"solver.force": True}).pass_.roll_radius == 350.0
    assert _load(f, {"solver.force": True}).solver.force is True


def test_the_nondimensional_bound_is_where_it_says():
    """Example 1 with K scaled so its estimated flow stress is 0.95 and 1.05 x 1e5 Pa: named
    nondimensional below the bound, not above (the bound x 1.1 is caught)."""
    d = _bundled("example1")
    s1 = P._mean_stress(case_from_dict(d))           # K = 1: the stress per unit K
    named = {}
    for f in (0.95, 1.05):
        e = copy.deepcopy(d)
        e["material"]["K"] = f * P.NONDIMENSIONAL_STRESS / s1
        named[f] = any("nondimensional" in w for w in case_from_dict(e).warnings())
    assert P.NONDIMENSIONAL_STRESS == 1e5
    assert named == {0.95: True, 1.05: False}
