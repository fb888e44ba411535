"""The FE's forward slip against an independent reference: slab theory in the thin-gap limit.

As l/h -> infinity at a fixed reduction with Coulomb mu = the bite angle (mu ~ h/l), the slab
(Orowan) equation is the leading order of the plane-strain problem and the slab's forward slip
is exact to O((h/l)^2) (``hotroll.theory.thin_gap``; docs/testing.md, "The forward slip
against the thin-gap limit"). Three steady FE runs (l/h = 8, 16, 32; automatic mesh, rigid
roll, unilateral contact (the default: it reaches the gap here); about 15 s) beside the slab
solution of the same law: the difference falls at the derived rate 2 and stays below the
derived bound at l/h = 32.
"""
from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import pytest

import hotroll
from hotroll.theory import slip_error_bound, solve_pass
from hotroll.workflows.compare import map_case

LH = (8.0, 16.0, 32.0)


def _script():
    """scripts/slip_limit.py: its ``thin_gap_case`` (sqrt(R dh)/h_mean = lh, Coulomb mu = the
    bite angle, Norton-Hoff m = 0.15) is the case here too."""
    scripts = Path(__file__).resolve().parents[2] / "scripts"
    if str(scripts) not in sys.path:          # the script's own helpers (_common)
        sys.path.insert(0, str(scripts))
    spec = importlib.util.spec_from_file_location("slip_limit", scripts / "slip_limit.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def sequence():
    rows = []
    for lh in LH:
        case = _script().thin_gap_case(lh, unilateral=True)
        s = map_case(case)  # the same law: local Norton-Hoff rate, Coulomb's rounded kinks
        slab = solve_pass(s.roll_radius, s.h0, s.h1, s.roll_speed, s.friction, s.flow_stress,
                          s.temperature)
        summary = hotroll.solve(case).summary
        assert summary["exit_code"] == 0
        rows.append((lh, summary, slab))
    return rows


def test_difference_falls_like_the_square_of_h_over_l(sequence):
    diffs = [fe["forward_slip"] - slab.forward_slip for _, fe, slab in sequence]
    assert all(d > 0 for d in diffs)  # the velocity profile's sign (thin_gap docstring)
    for (la, _, _), (lb, _, _), da, db in zip(sequence, sequence[1:], diffs, diffs[1:]):
        rate = math.log(da / db) / math.log(lb / la)
        assert 1.5 < rate < 3.0, (la, lb, da, db, rate)


def test_finest_step_within_the_derived_bound(sequence):
    _, fe, slab = sequence[-1]
    bound = slip_error_bound(_script().R, slab.neutral_thickness, slab.neutral_angle, slab.forward_slip)
    assert abs(fe["forward_slip"] - slab.forward_slip) <= bound
    # the neutral angles, from the slip's sign change on the arc, to the same relative order
    assert fe["neutral_angle"] == pytest.approx(slab.neutral_angle, rel=bound / slab.forward_slip)
