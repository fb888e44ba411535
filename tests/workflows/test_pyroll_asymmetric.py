"""The PyRolL plugin and PyRolL's asymmetric pass (issue 52 item 4; hotroll/pyroll_asymmetric.py).

pyroll-core 3.1 has no asymmetric pass; its PR #251 adds ``AsymmetricTwoRollPass`` (hook hosts
``UpperRoll``/``LowerRoll``) and removes ``BaseRollPass.Roll``. Both are faked here by class
layouts: [plumb] the roll hooks land on ``SymmetricRollPass.Roll`` when ``BaseRollPass.Roll`` is
gone, and on the asymmetric hosts; [hand] a fake asymmetric pass (real pyroll ``Roll`` objects)
becomes an asymmetric hotroll case with each roll's radius and speed as set; [refusal] what the
full strip cannot carry is refused naming what PyRolL described; [id] the asymmetric hooks give
the summary's per-roll figures (a canned summary: no FE solve in this file)."""
from __future__ import annotations

import math

import pytest

pr = pytest.importorskip("pyroll.core", reason="the [pyroll] extra (scripts/setup.sh installs it)")

from pyroll.core import Hook  # noqa: E402
from pyroll.core.hooks import HookHost  # noqa: E402

import hotroll.pyroll as hp  # noqa: E402
import hotroll.pyroll_asymmetric as ha  # noqa: E402

WIDTH = 1.5


def test_roll_hosts_follow_the_class_layout():
    """[plumb] pyroll-core 3.1: BaseRollPass.Roll; PR #251's layout (no BaseRollPass.Roll):
    SymmetricRollPass.Roll, plus the asymmetric pass's UpperRoll and LowerRoll."""
    assert ha.roll_hosts(pr.BaseRollPass, pr.SymmetricRollPass) == [pr.BaseRollPass.Roll]

    class Base:        # BaseRollPass after the PR: no Roll
        pass

    class Asym:
        class UpperRoll:
            pass

        class LowerRoll:
            pass

    hosts = ha.roll_hosts(Base, pr.SymmetricRollPass, Asym)
    assert hosts == [pr.SymmetricRollPass.Roll, Asym.UpperRoll, Asym.LowerRoll]


def _fake_roll_class():
    class Roll(HookHost):
        contact_length = Hook[float]()
    return Roll


def test_the_roll_hooks_register_on_a_host_without_them_declared():
    """[plumb] register_roll_hooks on a fresh host (as SymmetricRollPass.Roll after the PR):
    hotroll's contact length first, flattened_radius and flattening_ratio declared there."""
    host = _fake_roll_class()
    hp.register_roll_hooks(host)
    assert [f.function for f in host.contact_length._first_functions] == [hp.contact_length]
    assert isinstance(host.__dict__["flattened_radius"], Hook)
    assert [f.function for f in host.flattening_ratio._first_functions] == [hp.flattening_ratio]


def _pass(upper: dict, lower: dict, label="A1"):
    """A fake PR #251 pass: real pyroll Rolls (flat grooves), a real in profile; the reads
    the plugin makes (has_value, has_set) on the pass itself."""
    def roll(R, **speed):
        return pr.Roll(groove=pr.FlatGroove(usable_width=WIDTH), nominal_radius=R, **speed)

    class FakeAsymmetricPass:
        def __init__(self):
            self.label = label
            self.upper_roll, self.lower_roll = roll(**upper), roll(**lower)
            self.in_profile = pr.Profile.box(height=0.025, width=WIDTH, temperature=1373.15,
                                             strain=0.0, flow_stress=1.2e8)
            self.height = self.gap = 0.02

        def has_value(self, name):
            return getattr(self, name, None) is not None

        def has_set(self, name):
            return name in self.__dict__

    return FakeAsymmetricPass()


def test_an_asymmetric_pass_becomes_an_asymmetric_case():
    """[hand] each roll's radius and surface speed from its own Roll (rotational frequency
    f: U = 2 pi f R; working_velocity as given); with its temperature."""
    rp = _pass({"R": 0.4, "rotational_frequency": 0.8}, {"R": 0.38, "working_velocity": 1.7})
    assert ha.is_asymmetric(rp) and hp.is_flat(rp) and hp.handles(rp)
    case, _ = hp.pass_case(rp)
    gap = case.roll_gap()
    assert not gap.symmetric
    assert gap.upper.radius == 0.4 and gap.lower.radius == 0.38
    assert gap.upper.surface_speed == pytest.approx(2 * math.pi * 0.8 * 0.4, rel=1e-9)
    assert gap.lower.surface_speed == pytest.approx(1.7, rel=1e-12)
    assert case.thermal is not None and case.pass_.exit_thickness == 0.02


def test_a_symmetric_pass_is_no_asymmetric_one():
    """[plumb] a RollPass has no upper_roll/lower_roll: the symmetric path."""
    rp = pr.RollPass(label="S", gap=0.02, roll=pr.Roll(groove=pr.FlatGroove(usable_width=1.0),
                                                       nominal_radius=0.4))
    assert not ha.is_asymmetric(rp)


def test_an_elastic_lower_roll_is_that_rolls_model():
    """[plumb] PyRolL's elastic_modulus on the lower roll only: the case's [roll.lower] model
    is "elastic", the upper stays rigid (issue 52: the full strip flattens each roll)."""
    rp = _pass({"R": 0.4, "rotational_frequency": 0.8},
               {"R": 0.4, "working_velocity": 1.7, "elastic_modulus": 2.1e11})
    case, _ = hp.pass_case(rp)
    gap = case.roll_gap()
    assert gap.lower.model == "elastic" and gap.upper.model == "rigid"


def test_the_lower_rolls_own_elasticity_or_contact_is_refused_not_dropped():
    """[refusal] one [roll] elasticity and one [thermal] roll contact serve both rolls: a lower
    roll with another elastic modulus, or another temperature, than the upper's is refused
    naming the key (found in review: the lower roll's values were silently dropped)."""
    rp = _pass({"R": 0.4, "rotational_frequency": 0.8, "elastic_modulus": 2.1e11},
               {"R": 0.4, "working_velocity": 1.7, "elastic_modulus": 1.0e11})
    with pytest.raises(ValueError, match="roll.youngs_modulus: one value for both rolls"):
        hp.pass_case(rp)
    rp = _pass({"R": 0.4, "rotational_frequency": 0.8},
               {"R": 0.4, "working_velocity": 1.7, "temperature": 400.0})
    with pytest.raises(ValueError, match="thermal.roll_temperature: one value for both rolls"):
        hp.pass_case(rp)


def test_what_the_full_strip_cannot_carry_is_refused_naming_both_sides(monkeypatch):
    """[refusal] the constrained free surface (the full strip traces both), forced on: the
    message names the pass, both rolls as PyRolL described them and the key hotroll needs."""
    from hotroll import pyroll_case

    real = pyroll_case.case_from_dict

    def constrained(d):
        d["plate"]["free_surface"] = "constrained"
        return real(d)

    monkeypatch.setattr(pyroll_case, "case_from_dict", constrained)
    rp = _pass({"R": 0.4, "rotational_frequency": 0.8}, {"R": 0.4, "working_velocity": 1.7})
    with pytest.raises(ValueError) as e:
        hp.pass_case(rp)
    msg = str(e.value)
    assert "pass 'A1'" in msg and "asymmetric two-roll pass" in msg
    assert "lower roll R = 400 mm, U = 1.7 m/s" in msg
    assert "plate.free_surface" in msg


def test_a_roll_without_its_own_speed_is_left_with_the_reason(caplog):
    """[refusal] the lower roll without a speed: hotroll does not solve the pass, and says why."""
    rp = _pass({"R": 0.4, "rotational_frequency": 0.8}, {"R": 0.4})
    assert not hp.handles(rp)
    assert "no roll speed on lower_roll" in caplog.text


SUMMARY = {"roll_force": 7.0e6, "exit_velocity": 2.0, "outlet_strain_mean": 0.26,
           "exit_curvature": -1.55,
           "rolls": [{"roll_torque": 6.7e5, "neutral_angle": 0.028, "contact_length": 0.039},
                     {"roll_torque": -3.2e5, "neutral_angle": 0.05, "contact_length": 0.041}]}


def test_the_asymmetric_hooks_give_each_rolls_figures(monkeypatch):
    """[id] on a fake PR #251 class layout: roll_force = the summary's (mean) x width, each
    roll's torque its own x width, neutral angles in PyRolL's sign, the out profile's
    curvature; the contact length per roll through the roll hosts."""
    class Out(HookHost):
        velocity, strain, width = Hook[float](), Hook[float](), Hook[float]()

    class Asym(HookHost):
        roll_force = Hook[float]()
        OutProfile = Out

        class UpperRoll(HookHost):
            roll_torque, neutral_angle = Hook[float](), Hook[float]()

        class LowerRoll(HookHost):
            roll_torque, neutral_angle = Hook[float](), Hook[float]()

    ha.install_on(Asym, lambda rp: SUMMARY, lambda rp: True, hp._declare)
    rp = _pass({"R": 0.4, "rotational_frequency": 0.8}, {"R": 0.4, "working_velocity": 1.7})
    first = lambda host, name: getattr(host, name)._first_functions[0].function  # noqa: E731
    assert first(Asym, "roll_force")(rp) == 7.0e6 * WIDTH
    up = type("U", (), {"roll_pass": rp})()
    low = type("L", (), {"roll_pass": rp})()
    assert first(Asym.UpperRoll, "roll_torque")(up) == 6.7e5 * WIDTH
    assert first(Asym.LowerRoll, "roll_torque")(low) == -3.2e5 * WIDTH
    assert first(Asym.LowerRoll, "neutral_angle")(low) == -0.05
    out = type("O", (), {"roll_pass": rp})()
    assert first(Out, "curvature")(out) == -1.55 and first(Out, "velocity")(out) == 2.0
    monkeypatch.setattr(hp, "solve", lambda rp: SUMMARY)
    monkeypatch.setattr(hp, "handles", lambda rp: True)
    lower_roll = rp.lower_roll
    lower_roll.__dict__["roll_pass"] = rp
    assert hp.contact_length(lower_roll) == 0.041


def test_a_pass_hotroll_cannot_answer_raises_with_its_reason(monkeypatch, tmp_path):
    """[plumb] a pass whose run ends with a non-zero exit code (a canned summary: exit 10, a
    strip that would follow its slower roll further than the model) raises with the code's
    meaning and the run's reason, not only the number."""
    from hotroll.config.case import load_case
    from hotroll.examples import example_path

    case = load_case(example_path("asymmetric_plate"), {"pass.speed_ratio": 1.15})
    monkeypatch.setattr(hp, "pass_case", lambda rp: (case, None))
    monkeypatch.setattr(hp, "run_case", lambda *a, **k: {
        "exit_code": 10, "status": "steady",
        "failure": "contact not resolved: the lower roll's contact end is held"})
    monkeypatch.setattr(hp.Config, "OUTPUT_DIR", str(tmp_path))

    class Pass:
        label = "P1"

    with pytest.raises(RuntimeError) as err:
        hp.solve(Pass())
    assert str(err.value) == (
        f"hotroll.pyroll: pass 'P1' ended with exit code 10, contact not resolved (status "
        f"steady: contact not resolved: the lower roll's contact end is held); its output is "
        f"in {tmp_path / case.name}")


def test_the_hooks_answer_only_for_the_pass_hotroll_handles():
    """[id] handles(rp) true for one pass only: that pass gets hotroll's result, its rolls'
    torques and its out profile's width (the in profile's); another pass gets None."""
    class Out(HookHost):
        width = Hook[float]()

    class Asym(HookHost):
        OutProfile = Out

        class UpperRoll(HookHost):
            roll_torque = Hook[float]()

        class LowerRoll(HookHost):
            roll_torque = Hook[float]()

    rp = _pass({"R": 0.4, "rotational_frequency": 0.8}, {"R": 0.4, "working_velocity": 1.7})
    other = _pass({"R": 0.4, "rotational_frequency": 0.8}, {"R": 0.4, "working_velocity": 1.7})
    ha.install_on(Asym, lambda p: SUMMARY, lambda p: p is rp, hp._declare)
    first = lambda host, name: getattr(host, name)._first_functions[0].function  # noqa: E731
    on = lambda p: type("H", (), {"roll_pass": p})()  # noqa: E731
    assert first(Asym, "hotroll_result")(rp) is SUMMARY
    assert first(Asym, "hotroll_result")(other) is None
    assert first(Asym.UpperRoll, "roll_torque")(on(rp)) == 6.7e5 * WIDTH
    assert first(Asym.LowerRoll, "roll_torque")(on(other)) is None
    assert first(Out, "width")(on(rp)) == WIDTH and first(Out, "width")(on(other)) is None
