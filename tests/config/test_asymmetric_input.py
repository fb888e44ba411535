"""The case input of an asymmetric pass (issue 52 stage 2): [pass.upper]/[pass.lower],
pass.speed_ratio, [friction.upper]/[friction.lower], [roll.upper]/[roll.lower] -> ``Case.roll_gap``.
Every bundled case keeps today's RollPass (an identity: the symmetric path is today's code);
the per-roll speeds against hand numbers; each refusal names its field."""
from __future__ import annotations

import copy
import math
import tomllib

import pytest
from typer.testing import CliRunner

from hotroll.cli import app
from hotroll.config.case import CaseError, case_from_dict, case_from_toml, load_case
from hotroll.examples import example_path
from hotroll.model.geometry import RollPass
from hotroll.model.roll_gap import RollFriction
from hotroll.workflows.build import asymmetric_refusal, build_model

#: the bundled asymmetric passes (hotroll/examples/cases/asymmetric_*.toml) aside
EXAMPLES = sorted(p.stem for p in example_path("example1").parent.glob("*.toml")
                  if not p.stem.startswith("asymmetric"))
#: hot_strip_finishing: R = 350 mm, 8 -> 6 mm, omega = 100/7 rad/s (5 m/s), Coulomb mu = 0.3
BASE = tomllib.loads(example_path("hot_strip_finishing").read_text())


def with_(**tables) -> dict:
    """The base case with ``{"pass.lower": {...}, ...}`` tables (dotted: a section's own)."""
    d = copy.deepcopy(BASE)
    for dotted, values in tables.items():
        node = d
        for part in dotted.split("."):
            node = node.setdefault(part, {})
        node.update(values)
    return d


def problems(d: dict) -> list[str]:
    with pytest.raises(CaseError) as info:
        case_from_dict(d)
    return info.value.problems


@pytest.mark.parametrize("name", EXAMPLES)
def test_every_bundled_case_gives_todays_roll_pass(name):
    """Symmetric, and arc(+1) = roll_pass() = RollPass(R, h0/2, h1/2, omega, axis_x) built
    here from the file's own numbers, field by field (an identity)."""
    case = load_case(example_path(name))
    p = case.pass_
    today = RollPass(p.roll_radius, 0.5 * p.entry_thickness, 0.5 * p.exit_thickness,
                     p.roll_angular_velocity, p.roll_axis_x)
    gap = case.roll_gap()
    assert gap.symmetric and asymmetric_refusal(case) is None
    assert gap.arc(+1) == p.roll_pass() == today
    assert (gap.upper.friction, gap.lower.friction) == (None, None)
    assert gap.upper.model == gap.lower.model == case.roll.model
    assert case.to_dict() == load_case(example_path(name)).to_dict()
    assert "upper" not in case.to_dict()["pass"] and "speed_ratio" not in case.to_dict()["pass"]


def test_tables_that_repeat_the_pass_are_symmetric():
    """Per-roll tables with [pass]'s own values, [friction]'s mu and roll.model: still the
    half model's pass, its RollPass today's to the bit."""
    d = with_(**{"pass.upper": {"roll_radius": 0.35},
                 "pass.lower": {"roll_radius": "350 mm",
                                "roll_angular_velocity": BASE["pass"]["roll_angular_velocity"]},
                 "friction.lower": {"mu": 0.3}, "roll.upper": {"model": "rigid"}})
    case = case_from_dict(d)
    assert case.roll_gap().symmetric
    assert case.pass_.roll_pass() == load_case(example_path("hot_strip_finishing")).pass_.roll_pass()
    assert case_from_dict(with_(**{"pass": {"speed_ratio": 1}})).roll_gap().symmetric


def test_radii_and_speeds_with_units_by_hand():
    """275/225 mm rolls: the upper keeps omega = 100/7 rad/s (U1 = 3.9286 m/s); speed_ratio
    1.2 puts the lower at U1/1.2 = 3.2738 m/s, omega2 = U1/(1.2 x 0.225 m) = 14.550 rad/s;
    "60 rpm" is 2 pi rad/s, "1.5 m/s" on R = 225 mm is 6.667 rad/s."""
    case = case_from_dict(with_(**{"pass": {"speed_ratio": 1.2},
                                   "pass.upper": {"roll_radius": "275 mm"},
                                   "pass.lower": {"roll_radius": "225 mm"}}))
    g = case.roll_gap()
    assert (g.upper.radius, g.lower.radius) == (0.275, 0.225)
    omega = 100 / 7
    assert g.upper.omega == pytest.approx(omega, rel=1e-15)
    assert g.lower.surface_speed == pytest.approx(omega * 0.275 / 1.2, rel=1e-14)
    assert g.lower.omega == pytest.approx(14.550264550264550, rel=1e-14)
    assert g.speed_ratio == pytest.approx(1.2, rel=1e-14)
    assert g.equivalent_radius == pytest.approx(0.2475, rel=1e-15)
    assert case.pass_.roll_pass() == g.arc(+1)
    rpm = case_from_dict(with_(**{"pass.lower": {"roll_angular_velocity": "60 rpm"}}))
    assert rpm.roll_gap().lower.omega == pytest.approx(2 * math.pi, rel=1e-15)
    speed = case_from_dict(with_(**{"pass.lower": {"roll_radius": "225 mm",
                                                   "roll_surface_speed": "1.5 m/s"}}))
    assert speed.roll_gap().lower.omega == pytest.approx(1.5 / 0.225, rel=1e-15)
    assert speed.roll_gap().upper.omega == BASE["pass"]["roll_angular_velocity"]


def test_the_lower_roll_by_default_turns_at_the_pass_angular_velocity():
    """No speed ratio, no speed of its own: both rolls at pass.roll_angular_velocity, so a
    smaller lower roll is the slower one (U ratio = R1/R2 = 350/225)."""
    g = case_from_dict(with_(**{"pass.lower": {"roll_radius": 0.225}})).roll_gap()
    assert g.lower.omega == g.upper.omega
    assert g.speed_ratio == pytest.approx(0.35 / 0.225, rel=1e-15)


def test_per_roll_friction_and_model():
    """[friction.lower] without law changes only mu; with another law it is that law's whole
    data; [roll.lower] its own model."""
    case = case_from_dict(with_(**{"friction.lower": {"mu": 0.4},
                                   "roll.lower": {"model": "hitchcock"}}))
    g = case.roll_gap()
    assert g.upper.friction is None
    assert g.lower.friction == RollFriction("coulomb", (("a_f_max", 1e6), ("mu", 0.4)))
    assert (g.upper.model, g.lower.model) == ("rigid", "hitchcock")
    assert g.differences() == ["friction", "model"]
    tresca = case_from_dict(with_(**{"friction.upper": {"law": "tresca", "factor": 0.7}}))
    assert tresca.roll_gap().upper.friction == RollFriction(
        "tresca", (("a_f_max", 1e6), ("factor", 0.7)))
    assert tresca.friction.upper.mu is None          # not [friction]'s mu under another law


def test_an_asymmetric_case_round_trips_through_toml():
    case = case_from_dict(with_(**{"pass": {"speed_ratio": 1.2},
                                   "pass.lower": {"roll_radius": "225 mm"},
                                   "friction.upper": {"mu": 0.25},
                                   "roll.lower": {"model": "hitchcock"}}))
    text = case.to_toml()
    assert "[pass.lower]" in text and "[friction.upper]" in text and "[roll.lower]" in text
    again = case_from_toml(text)
    assert again == case and again.roll_gap() == case.roll_gap()
    assert case.with_overrides(**{"pass.lower.roll_radius": 0.2}).roll_gap().lower.radius == 0.2


@pytest.mark.parametrize("tables,field", [
    ({"pass": {"speed_ratio": 0}}, "pass.speed_ratio"),
    ({"pass": {"speed_ratio": -1.2}}, "pass.speed_ratio"),
    ({"pass.lower": {"roll_angular_velocity": -3.0}}, "pass.lower.roll_angular_velocity"),
    ({"pass.upper": {"roll_surface_speed": "0 m/s"}}, "pass.upper.roll_surface_speed"),
    ({"pass.lower": {"roll_radius": "-5 mm"}}, "pass.lower.roll_radius"),
    ({"pass.lower": {"roll_radius": "2 s"}}, "pass.lower.roll_radius"),
    ({"pass.lower": {"roll_radius": "0.5 mm"}}, "pass.lower.roll_radius"),
    ({"pass.upper": {"roll_radius": "0.5 mm"}}, "pass.upper.roll_radius"),
    ({"pass": {"speed_ratio": 1.1}, "pass.lower": {"roll_surface_speed": 4.0}},
     "pass.speed_ratio"),
    ({"pass.lower": {"roll_angular_velocity": 4.0, "roll_surface_speed": 4.0}},
     "pass.lower.roll_surface_speed"),
    ({"pass.lower": {"radius": 0.2}}, "pass.lower.radius"),
    ({"friction.lower": {"law": "ice"}}, "friction.lower.law"),
    ({"friction.upper": {"law": "tresca"}}, "friction.upper.factor"),
    ({"friction.lower": {"mu": 3.0}}, "friction.lower.mu"),
    ({"roll.lower": {"model": "soft"}}, "roll.lower.model"),
    ({"pass": {"speed_ratio": 0.05}}, "pass.speed_ratio"),      # lower at 100 m/s
    ({"pass": {"speed_ratio": 1e-320}}, "pass.speed_ratio"),    # lower at inf rad/s
    ({"pass.lower": {"roll_surface_speed": "70 m/s"}}, "pass.lower.roll_surface_speed"),
    ({"pass.upper": {"roll_radius": 2.5}, "plate": {"length": 1.0}}, "pass.upper.roll_radius"),
    ({"roll.lower": {"model": "elastic"}, "solver": {"method": "transient"}},
     "roll.lower.model"),
])
def test_each_refusal_names_its_field(tables, field):
    """A roll that would stand or drive backwards, a radius that does not fit its share of
    the draft (0.5 mm of the 2 mm draft), conflicting speeds, an unregistered law, a law's
    missing datum, an unknown key or model: one line, naming the field (and the range)."""
    lines = problems(with_(**tables))
    assert len(lines) == 1 and lines[0].startswith(f"{field}: "), lines
    if "speed_ratio" in tables.get("pass", {}) and tables["pass"]["speed_ratio"] <= 0:
        assert "must be > 0" in lines[0]
    if "0.5 mm" in str(tables):
        assert "must exceed this roll's share of the draft" in lines[0] and "allowed: >" in lines[0]


def test_build_model_refuses_an_asymmetric_pass_the_full_strip_cannot_take_by_name():
    """hot_strip_finishing with a speed ratio and the constrained free surface (flat tops held
    by a penalty), which the full-thickness strip does not carry (it traces both surfaces)."""
    case = case_from_dict(with_(**{"pass": {"speed_ratio": 1.2},
                                   "plate": {"free_surface": "constrained"}}))
    with pytest.raises(CaseError, match=r"plate.free_surface: the full-thickness strip traces "
                       r"both free surfaces") as info:
        build_model(case)
    assert "differ in omega" in str(info.value) and "speed ratio 1.2)" in str(info.value)


def test_the_command_line_refuses_an_asymmetric_run_it_cannot_take_before_writing(tmp_path):
    """`hotroll run`: exit code 2 with the refusal naming its key, nothing written; `hotroll
    validate` takes the same file (it is a valid case)."""
    text = example_path("hot_strip_finishing").read_text().replace(
        "[plate]", "[plate]\nfree_surface = \"constrained\"") + "\n[pass.lower]\nroll_radius = " \
        "\"225 mm\"\n"
    path = tmp_path / "asym.toml"
    path.write_text(text)
    out = tmp_path / "out"
    runner = CliRunner()
    result = runner.invoke(app, ["run", str(path), "--out", str(out)])
    assert result.exit_code == 2, result.output
    assert "plate.free_surface: the full-thickness strip" in result.output
    assert not out.exists()
    assert runner.invoke(app, ["validate", str(path)]).exit_code == 0


def test_a_study_names_the_unit_of_a_rolls_own_key():
    from hotroll.config.study import key_unit

    assert key_unit("pass.lower.roll_radius") == "m"
    assert key_unit("pass.upper.roll_surface_speed") == "m/s"
    assert key_unit("friction.lower.v_reg") == "m/s"


def test_the_reference_pages_example_is_the_gap_it_describes():
    """docs/reference/case.md's asymmetric example, completed with a plate and a material:
    R = 275/225 mm, 60 rpm upper, ratio 1.2, the lower's mu 0.35 and Hitchcock model."""
    from pathlib import Path

    page = (Path(__file__).resolve().parents[2] / "docs" / "reference" / "case.md").read_text()
    block = page.split("**Asymmetric passes**", 1)[1].split("```toml", 1)[1].split("```", 1)[0]
    text = block + ('\n[plate]\nlength = 0.5\n[material]\nlaw = "norton-hoff"\nK = 1e8\n'
                    'm = 0.2\n[friction]\nlaw = "coulomb"\nmu = 0.3\n')
    g = case_from_toml(text).roll_gap()
    assert (g.upper.radius, g.lower.radius) == (0.275, 0.225)
    assert g.upper.omega == pytest.approx(2 * math.pi, rel=1e-15)
    assert g.speed_ratio == pytest.approx(1.2, rel=1e-14)
    assert g.lower.friction == RollFriction("coulomb", (("a_f_max", 1e6), ("mu", 0.35)))
    assert g.lower.model == "hitchcock" and g.upper.model == "rigid"


def test_two_refusals_of_one_pass_are_both_said():
    """A lower roll given both its speeds AND a radius below its share of the draft: both lines
    (the speed conflict and the fit), neither hiding the other."""
    lines = problems(with_(**{"pass.lower": {"roll_radius": "0.5 mm", "roll_angular_velocity": 4.0,
                                             "roll_surface_speed": 4.0}}))
    assert len(lines) == 2, lines
    assert lines[0].startswith("pass.lower.roll_surface_speed: give one of")
    assert lines[1].startswith("pass.lower.roll_radius: must exceed")
