"""The strip map's stretch in x (fem/free_surface.py ``StripMap.stretch``): the piecewise-linear
map that takes the reference mesh's touching point to the contact's start x_c and its roll
gap to the contact's end x_e. Checks by hand: the fixed points stay, the map is monotone, and
no element between the gap and the exit anchor is squeezed by more than a factor 2, at any end
inside the allowed range. Before issue 52 session 4 the exit anchor was fixed at half a
contact length past the gap, the wrap's range reached it, and a wrap held there mapped every
node between the gap and it onto one point (the thermal strip's elements then had a zero
Jacobian: exit code 3 instead of 10)."""
from __future__ import annotations

import numpy as np
import pytest

from hotroll.fem.free_surface import StripMap
from hotroll.model.geometry import RollPass
from hotroll.solvers.contact_end import PAST_GAP
from hotroll.solvers.full_contact_end import PAST_GAP_WRAP

R, H0, H1, AXIS = 0.4, 0.0125, 0.01, 1.0


def bare_map(downstream_lc: float) -> StripMap:
    """A StripMap's stretch alone (no mesh): inlet two contact lengths before the touching
    point, outlet ``downstream_lc`` contact lengths after the gap."""
    rp = RollPass(R, H0, H1, omega=5.0, axis_x=AXIS)
    m = object.__new__(StripMap)
    m.rp = rp
    lc = rp.contact_length
    m.set_anchors(rp.x_touch - 2.0 * lc, AXIS + downstream_lc * lc)
    return m


@pytest.mark.parametrize("downstream_lc", [1.0, 1.5, 4.0])
@pytest.mark.parametrize("past", [0.0, PAST_GAP, PAST_GAP_WRAP, 1.0])
def test_the_exit_side_is_squeezed_at_most_twice_anywhere_in_the_range(downstream_lc, past):
    """[hand] at the end of the allowed range (and inside it) the reference spacing between the
    gap and the outlet shrinks by at most 2, the map stays monotone, the outlet stays."""
    m = bare_map(downstream_lc)
    rp, lc = m.rp, m.rp.contact_length
    lo, hi = m.end_bounds(past)
    assert lo == pytest.approx(AXIS - 0.5 * lc)
    assert hi == pytest.approx(AXIS + min(past * lc, 0.25 * downstream_lc * lc))
    X = np.linspace(rp.x_touch - 2.0 * lc, AXIS + downstream_lc * lc, 4001)
    for x_e in np.linspace(lo, hi, 7):
        x = m.stretch(X, rp.x_touch, x_e)
        spacing = np.diff(x) / np.diff(X)
        assert spacing.min() >= 0.5 - 1e-9, x_e
        assert x[-1] == X[-1] and x[0] == X[0]
        # the gap goes to the end, the touching point stays
        assert m.stretch(np.array([AXIS]), rp.x_touch, x_e)[0] == pytest.approx(x_e, abs=1e-15)


def test_an_end_up_to_a_quarter_contact_length_past_the_gap_keeps_the_old_anchor():
    """[hand] the anchor moves only for an end further than half of x_b's distance from the
    gap: the half model's elastic ends (a quarter contact length) map as before."""
    m = bare_map(4.0)
    lc = m.rp.contact_length
    assert m.x_b == pytest.approx(AXIS + 0.5 * lc)
    for d in (-0.5, 0.0, 0.1, PAST_GAP):
        assert m.exit_anchor(AXIS + d * lc) == m.x_b
    assert m.exit_anchor(AXIS + 0.4 * lc) == pytest.approx(AXIS + 0.8 * lc)
    assert m.exit_anchor(AXIS + 5.0 * lc) == m.x_b_max == pytest.approx(AXIS + 2.0 * lc)


def test_the_arcs_last_vertex_follows_a_flattened_roll():
    """[hand] the arc's chain of edges lies on the roll as it is now, its last vertex (the
    reference gap, mapped to the contact's end) included; the exit top after it on its own
    curve. A roll flattened uniformly by w0 after the shape was made (a roll coupling's update
    maps the mesh again with the shape as it stood: solvers/couplings.RollFlattening): its
    surface radius R - w0, its centre still the gap plus R above the axis, so its lowest point
    (the end) is at the gap + w0, while the shape's exit top still starts at the gap."""
    from dataclasses import replace

    from hotroll.fem.free_surface import StripShape
    from hotroll.model.geometry import RollShape

    theta = np.linspace(-0.4, 0.4, 9)
    rp = RollPass(R, H0, H1, omega=5.0, axis_x=AXIS, shape=RollShape(theta, np.zeros(9)))
    m = object.__new__(StripMap)
    m.rp, m.roll = replace(rp, shape=rp.shape.copy()), rp     # as StripMap.__init__
    lc = rp.contact_length
    m.set_anchors(rp.x_touch - 2.0 * lc, AXIS + 2.0 * lc)
    X = np.array([rp.x_touch - 0.5 * lc, AXIS - 0.5 * lc, AXIS, AXIS + 0.25 * lc])
    m.H_ref = np.array([H0, float(rp.height(AXIS - 0.5 * lc)), H1, H1])
    m.P = np.stack([X, m.H_ref], axis=1)                # the top's nodes
    shape = StripShape.flat(m.rp)
    w0 = 1e-4
    rp.shape.set(theta, np.full(9, -w0))
    y = m.positions(shape)[:, 1]
    assert float(rp.height(AXIS)) == pytest.approx(H1 + w0, abs=1e-15)
    assert y[2] == pytest.approx(H1 + w0, abs=1e-15)               # the end, on the roll
    assert y[1] == pytest.approx(float(rp.height(AXIS - 0.5 * lc)), abs=1e-15)
    assert y[3] == pytest.approx(H1, abs=1e-15)                     # the free tops: the shape's
    assert y[0] == pytest.approx(H0, abs=1e-15)
