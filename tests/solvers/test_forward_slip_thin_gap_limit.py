"""The FE's forward slip against an independent reference: slab theory in the thin-gap limit.

As l/h -> infinity at a fixed reduction with Coulomb mu = the bite angle (mu ~ h/l), the slab
(Orowan) equation is the leading order of the plane-strain problem and the slab's forward slip
is exact to O((h/l)^2) (``hotroll.theory.thin_gap``; docs/testing.md, "The forward slip
against the thin-gap limit"). Three steady FE runs (l/h = 8, 16, 32; automatic mesh, rigid
roll, bilateral contact; about 15 s) beside the slab solution of the same law: the difference
falls at the derived rate 2 and stays below the derived bound at l/h = 32.
"""
from __future__ import annotations

import math

import pytest

import hotroll
from hotroll.config.case import case_from_dict
from hotroll.theory import slip_error_bound, solve_pass
from hotroll.workflows.compare import map_case

R, U = 0.4, 3.0
LH = (8.0, 16.0, 32.0)


def thin_gap_case(lh: float, reduction: float = 0.3):
    """sqrt(R dh)/h_mean = lh, Coulomb mu = bite angle, Norton-Hoff m = 0.15."""
    h0 = R * reduction / (lh ** 2 * (1.0 - reduction / 2.0) ** 2)
    h1 = h0 * (1.0 - reduction)
    alpha = math.acos(1.0 - (h0 - h1) / (2.0 * R))
    return case_from_dict({
        "name": f"thin_gap_lh{lh:g}",
        "pass": {"roll_radius": R, "entry_thickness": h0, "exit_thickness": h1,
                 "roll_angular_velocity": U / R},
        "plate": {"length": 4.0 * math.sqrt(R * (h0 - h1)), "temperature": 1373.15},
        "material": {"law": "norton-hoff", "K": 4e7, "m": 0.15},
        "friction": {"law": "coulomb", "mu": alpha},
        "mesh": {"h_contact": "auto"},
        "solver": {"method": "steady", "threads": 1},
        "output": {"figures": False, "vtk": False},
    })


@pytest.fixture(scope="module")
def sequence():
    rows = []
    for lh in LH:
        case = thin_gap_case(lh)
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
    bound = slip_error_bound(R, slab.neutral_thickness, slab.neutral_angle, slab.forward_slip)
    assert abs(fe["forward_slip"] - slab.forward_slip) <= bound
    # the neutral angles, from the slip's sign change on the arc, to the same relative order
    assert fe["neutral_angle"] == pytest.approx(slab.neutral_angle, rel=bound / slab.forward_slip)
