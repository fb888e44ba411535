"""The roll gap of two rolls (model/roll_gap.py) against hand numbers: the equivalent radius
and the draft split at R = 275/225 mm (../shared/notes/asymmetric-rolling.md 1.1), the entry
points of both arcs computed here from the circles, the symmetric gap's arc against today's
RollPass, mirroring. Planted bugs caught (measured): R_e x 1.1, the pass line x 1.1, dh1 x 1.1.
"""
from __future__ import annotations

import math
from dataclasses import astuple, fields, replace

import pytest

from hotroll.model.geometry import RollPass
from hotroll.model.roll_gap import LOWER, UPPER, Roll, RollFriction, RollGap

R1, R2 = 0.275, 0.225               # m: the note's example radii
H0, H1 = 0.040, 0.030               # m: dh = 10 mm
OMEGA = 5.0                         # rad/s


def gap(r1=R1, r2=R2, w1=OMEGA, w2=OMEGA, h0=H0, h1=H1, **kw) -> RollGap:
    return RollGap(Roll(r1, w1, side=UPPER, **kw), Roll(r2, w2, side=LOWER, **kw), h0, h1, 1.0)


def test_equivalent_radius_is_the_harmonic_mean_by_hand():
    """2 R1 R2/(R1 + R2) = 2 x 0.275 x 0.225 / 0.5 = 0.2475 m; one roll's radius when equal."""
    assert gap().equivalent_radius == pytest.approx(0.2475, rel=1e-15)
    assert gap(r2=R1).equivalent_radius == pytest.approx(R1, rel=1e-15)


def test_draft_split_by_hand():
    """The note's small-angle split dh1/dh = R2/(R1 + R2) = 0.45 in the limit dh -> 0; at
    dh = 10 mm the exact split of equal entry points dh (2 R2 - dh)/(2 (R1 + R2 - dh)) =
    10 x 440/980 mm = 220/49 mm, the lower roll the rest 270/49 mm; the pass line (dh1 -
    dh2)/2 = -25/49 mm (below the mid-plane: the larger upper roll takes less)."""
    tiny = gap(h0=H1 + 1e-9)
    dh1, dh2 = tiny.draft_split()
    assert dh1 / tiny.draft == pytest.approx(0.45, rel=1e-6)
    assert dh2 / tiny.draft == pytest.approx(0.55, rel=1e-6)
    dh1, dh2 = gap().draft_split()
    assert dh1 == pytest.approx(220 / 49 * 1e-3, rel=1e-12)
    assert dh2 == pytest.approx(270 / 49 * 1e-3, rel=1e-12)
    assert gap().pass_line == pytest.approx(-25 / 49 * 1e-3, rel=1e-12)


def _entry_x(centre, radius, y) -> float:
    """Where a circle about ``centre`` of ``radius`` reaches height ``y``, upstream (m)."""
    return centre[0] - math.sqrt(radius**2 - (y - centre[1]) ** 2)


def test_both_rolls_bite_at_the_same_x_at_the_pass_line():
    """The entry strip at the pass line: its top at pass_line + h0/2 meets the upper circle
    (centre (1, h1/2 + R1)), its bottom at pass_line - h0/2 the lower circle (centre
    (1, -h1/2 - R2)) at the same x, computed here from the circles; each arc's own x_touch
    is that x. At the note's small-angle split the two would be 0.10 mm apart (of 49.5 mm)."""
    g = gap()
    top, bottom = g.pass_line + H0 / 2, g.pass_line - H0 / 2
    x_up = _entry_x((1.0, H1 / 2 + R1), R1, top)
    x_low = _entry_x((1.0, -H1 / 2 - R2), R2, bottom)
    assert x_up == pytest.approx(x_low, abs=1e-15)
    assert g.arc(UPPER).x_touch == pytest.approx(x_up, abs=1e-15)
    assert g.arc(LOWER).x_touch == pytest.approx(x_up, abs=1e-15)
    small_angle = (0.45 * 0.01, 0.55 * 0.01)
    apart = _entry_x((1.0, 0.0), R1, -R1 + small_angle[0]) \
        - _entry_x((1.0, 0.0), R2, -R2 + small_angle[1])
    assert 0.9e-4 < abs(apart) < 1.1e-4


def test_centres_in_the_full_thickness_frame():
    """(axis_x, +-(h1/2 + R)): the rolls' nearest points h1 apart about y = 0."""
    g = gap()
    assert g.centre(UPPER) == (1.0, H1 / 2 + R1)
    assert g.centre(LOWER) == (1.0, -(H1 / 2 + R2))
    assert g.centre(UPPER)[1] - R1 - (g.centre(LOWER)[1] + R2) == pytest.approx(H1, abs=1e-15)


def test_the_lower_arc_is_the_lower_roll_mirrored():
    """arc(-1) is the lower roll seen with y -> -y: its centre the mirror of centre(-1), its
    entry surface at -(pass_line - h0/2), its exit at h1/2, its own radius and speed."""
    g = gap(w2=4.0)
    a = g.arc(LOWER)
    assert a.centre == (g.centre(LOWER)[0], -g.centre(LOWER)[1])
    assert a.half_entry == pytest.approx(-(g.pass_line - H0 / 2), abs=1e-16)
    assert (a.radius, a.half_exit, a.omega, a.axis_x) == (R2, H1 / 2, 4.0, 1.0)


def test_symmetric_gap_arc_is_todays_roll_pass_field_by_field():
    """Equal rolls: arc(+1) and arc(-1) are RollPass(R, h0/2, h1/2, omega, axis_x) to the bit
    (an identity with today's construction, config/sections.py)."""
    g = gap(r2=R1)
    today = RollPass(R1, 0.5 * H0, 0.5 * H1, OMEGA, 1.0)
    for side in (UPPER, LOWER):
        arc = g.arc(side)
        assert [getattr(arc, f.name) for f in fields(RollPass)] == \
            [getattr(today, f.name) for f in fields(RollPass)]
    assert g.pass_line == 0.0 and g.draft_split() == (0.5 * g.draft, 0.5 * g.draft)


def test_symmetric_exactly_when_every_per_roll_value_is_equal():
    base = gap(r2=R1)
    assert base.symmetric and base.differences() == []
    lower = base.lower
    changes = {"radius": math.nextafter(R1, 1.0), "omega": math.nextafter(OMEGA, 10.0),
               "friction": RollFriction("coulomb", (("mu", 0.3),)), "model": "hitchcock"}
    for name, value in changes.items():
        other = replace(base, lower=replace(lower, **{name: value}))
        assert not other.symmetric and other.differences() == [name], name
    same = RollFriction("tresca", (("factor", 0.5),))
    both = replace(base, upper=replace(base.upper, friction=same),
                   lower=replace(lower, friction=RollFriction("tresca", (("factor", 0.5),))))
    assert both.symmetric


def test_speed_ratio_and_surface_speed():
    """U = omega R; the ratio upper over lower: 5 x 0.275 / (4 x 0.225) = 1.375/0.9."""
    g = gap(w2=4.0)
    assert g.upper.surface_speed == pytest.approx(1.375, rel=1e-15)
    assert g.speed_ratio == pytest.approx(1.375 / 0.9, rel=1e-15)


def test_mirror_swaps_the_rolls_and_twice_is_identity():
    g = gap(w2=4.0, model="hitchcock")
    g = replace(g, lower=replace(g.lower, friction=RollFriction("coulomb", (("mu", 0.2),))))
    m = g.mirror()
    assert m.upper == replace(g.lower, side=UPPER) and m.lower == replace(g.upper, side=LOWER)
    assert m.mirror() == g
    assert m.pass_line == -g.pass_line
    assert m.draft_split() == g.draft_split()[::-1]
    assert m.speed_ratio == pytest.approx(1.0 / g.speed_ratio, rel=1e-15)
    assert astuple(m.arc(UPPER)) == astuple(g.arc(LOWER))


@pytest.mark.parametrize("change,field", [
    ({"w1": 0.0}, "upper.omega"), ({"w2": -1.0}, "lower.omega"),
    ({"r1": -0.1}, "upper.radius"), ({"h1": 0.05}, "exit_thickness"),
    ({"r2": 0.006}, "lower.radius"), ({"r1": 0.004, "r2": 0.005}, "lower.radius")])
def test_bad_gaps_are_refused_naming_the_field(change, field):
    """A roll driving backwards or standing, a radius <= 0, an exit above the entry, a
    radius below its share of the draft (R2 = 6 mm: dh (2 R1 - dh)/(2 (R1 + R2 - dh)) =
    10 x 540/542 = 9.963 mm of the 10), two radii whose sum is below the draft."""
    with pytest.raises(ValueError, match=rf"^(.*; )?{field}: "):
        gap(**change)


def test_a_radius_just_above_its_share_fits():
    """The refusal's bound is the share itself, which moves with R2: at R2 = share(R2) (the
    hand formula's fixed point, iterated here) x 1.0001 the gap fits, x 0.9999 it does not."""
    from hotroll.model.roll_gap import fit_problems

    def share(r2):                       # dh2 by hand, dh = 10 mm
        return 0.01 * (2 * R1 - 0.01) / (2 * (R1 + r2 - 0.01))

    r2 = 0.0099
    for _ in range(60):
        r2 = share(r2)
    assert fit_problems(R1, 1.0001 * r2, 0.01) == []
    assert fit_problems(R1, 0.9999 * r2, 0.01)[0].startswith("lower.radius: must exceed")


def test_unregistered_friction_law_and_bad_side_are_refused():
    with pytest.raises(ValueError, match=r"lower.friction: law 'ice' is not registered"):
        RollGap(Roll(R1, OMEGA), Roll(R2, OMEGA, RollFriction("ice"), side=LOWER), H0, H1)
    with pytest.raises(ValueError, match=r"lower.side: must be -1"):
        RollGap(Roll(R1, OMEGA), Roll(R2, OMEGA), H0, H1)
    with pytest.raises(ValueError, match=r"upper.model: must be one of"):
        RollGap(Roll(R1, OMEGA, model="soft"), Roll(R2, OMEGA, side=LOWER), H0, H1)


def test_a_zero_radius_is_refused_and_a_bad_side_named():
    """R = 0 is no roll (> 0, not >= 0); a side other than +1/-1 is refused naming it."""
    assert Roll(0.0, OMEGA).problems("upper")[0].startswith("upper.radius: must be > 0")
    with pytest.raises(ValueError, match=r"^side: must be \+1 \(upper\) or -1 \(lower\), got 0$"):
        gap().roll(0)
