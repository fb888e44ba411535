"""config/schedule_rolls.py's refusal of a tandem's mass-flow speeds for an asymmetric pass,
naming the pass and every way its rolls differ (no FE solve)."""
from __future__ import annotations

from types import SimpleNamespace

import hotroll.config.schedule_rolls as sr
from hotroll.model.roll_gap import LOWER, Roll, RollGap


def test_mass_flow_speeds_are_refused_naming_how_the_rolls_differ(monkeypatch):
    monkeypatch.setattr(sr, "asymmetric_refusal", lambda case: None)
    gap = RollGap(Roll(0.275, 5.0), Roll(0.225, 4.0, side=LOWER), 0.04, 0.03)
    case = SimpleNamespace(roll_gap=lambda: gap, thermal=object())
    sch = SimpleNamespace(passes=[None, None],
                          mill=SimpleNamespace(speeds="mass_flow", tensions="given"),
                          microstructure=SimpleNamespace(kinetics=None))
    (line,) = sr.asymmetric_problems(sch, 1, case)
    assert line.startswith('mill.speeds: "mass_flow" cannot set pass[2] (asymmetric: the rolls '
                           'differ in radius, omega): ')
