"""The free surface after a contact's end against its roll (issue 52 session 3:
``solvers/contact_end.overlap_after``), the outcome it leads to (``results/outcome.py:
contact_problem``, exit code 10) and the end search's guard on a noise-flat secant
(``fem/free_surface.ContactEndSearch``).

Labels: [hand] closed forms of a straight line leaving a circle; [plumb] what the summary's
keys make of the exit code."""
from __future__ import annotations

import math

import numpy as np
import pytest

from hotroll.fem.free_surface import ContactEndSearch
from hotroll.model.geometry import RollPass
from hotroll.results.outcome import EXIT_CODES, OVERLAP_LIMIT_H, contact_problem, exit_code
from hotroll.solvers.contact_end import overlap_after

R, H1 = 0.36, 0.01


def _line(beta: float, x0: float = 1.0, n: int = 121):
    """A straight free surface leaving the roll's lowest point (x0, H1) at slope beta towards
    the roll (own frame: y towards it), sampled every 0.5 mm from the gap to 60 mm past it."""
    x = np.linspace(x0, x0 + 0.06, n)
    return np.c_[x, H1 + beta * (x - x0)]


@pytest.mark.parametrize("beta", [0.01, 0.042])
def test_a_line_inclined_into_the_roll_leaves_it_where_the_chord_ends(beta):
    """[hand] a line through the circle's lowest point at slope beta meets the circle again
    at x = 2 R beta / (1 + beta^2) past it, and lies inside it at most R (sqrt(1 + beta^2) - 1)
    deep (at x = R beta / sqrt(1 + beta^2)); sampled every 0.5 mm: the depth (the deepest
    sample) to 2 % of itself, the crossing interpolated between its two samples to 3e-3 of
    the chord (the nearer sample alone is up to 0.25 mm off, 3-7 % of the chord)."""
    rp = RollPass(R, 0.0125, H1, omega=5.0)
    depth, leaves = overlap_after(_line(beta), rp, 1.0, 1e-7)
    assert depth == pytest.approx(R * (math.sqrt(1 + beta**2) - 1), rel=2e-2)
    assert leaves - 1.0 == pytest.approx(2 * R * beta / (1 + beta**2), rel=3e-3)


def test_a_line_leaving_the_roll_is_outside_it():
    """[hand] inclined away from the roll (beta < 0) or straight (the roll rises away: x^2/2R):
    no depth, no stretch inside; a surface after the end only (points before x_e ignored:
    the contact itself lies on the roll)."""
    rp = RollPass(R, 0.0125, H1, omega=5.0)
    for beta in (-0.01, 0.0):
        depth, leaves = overlap_after(_line(beta), rp, 1.0, 1e-7)
        assert depth == 0.0 and leaves is None
    inside_before = np.r_[np.c_[[0.99, 0.995], [H1 + 1e-3, H1 + 1e-3]], _line(-0.01)]
    assert overlap_after(inside_before, rp, 1.0, 1e-7) == (0.0, None)


def test_a_stretch_inside_that_starts_later_is_not_a_wrap():
    """[hand] a surface that leaves the roll (by more than tol) and comes back into it later
    reports its depth, but no stretch from the end to follow: the contact does not jump."""
    rp = RollPass(R, 0.0125, H1, omega=5.0)
    xy = _line(-0.01)
    x = xy[:, 0] - 1.0
    xy[:, 1] = H1 - 0.01 * x + 2.0 * x**2           # out first, then curling into the roll
    depth, leaves = overlap_after(xy, rp, 1.0, 1e-6)
    assert depth > 1e-4 and leaves is None


def test_the_outcome_of_a_strip_inside_a_roll():
    """[plumb] overlap above OVERLAP_LIMIT_H contact elements, or a contact end held at its
    range's end (`bound`, on either roll): exit code 10 with the reason; at the limit and
    below, or ends of other kinds: none."""
    h = 1e-3
    base = {"h_contact": h, "rolls": [{"side": "upper", "contact_end_kind": "separation"},
                                      {"side": "lower", "contact_end_kind": "wrap"}]}
    assert contact_problem({**base, "roll_overlap": OVERLAP_LIMIT_H * h}) is None
    why = contact_problem({**base, "roll_overlap": 1.1 * OVERLAP_LIMIT_H * h})
    assert why.startswith("contact not resolved: the strip's free surface lies 22 um")
    bound = {**base, "roll_overlap": 0.0, "rolls": [base["rolls"][0],
                                                    {"side": "lower", "contact_end_kind": "bound"}]}
    assert "the lower roll's contact end is held at the end of its allowed range" in \
        contact_problem(bound)
    assert "with the strip still pressing on the roll" in contact_problem(bound)
    half = contact_problem({"contact_end_kind": "bound", "contact_end_pressure": -2.5e6})
    assert half == ("contact not resolved: the roll's contact end is held at the end of its "
                    "allowed range with a tensile contact stress there (-2.5 MPa): the strip "
                    "would leave the roll before it")
    s = {"converged": False, "contact_unresolved": True, "status": "steady",
         "roll_force": 1.0, "roll_torque": 1.0}
    assert exit_code(s) == 10 and EXIT_CODES[10] == "contact not resolved"


def test_the_end_search_ignores_a_noise_flat_secant():
    """[hand] two ends 2 um apart whose p_end differ by 1e-5 of the pressure's fall over the
    last element (a secant 1e5 times flatter than the line): the step is the line's, the zero
    of p through the last two vertices, not the secant's 1.4 mm; a secant as steep as the
    line is taken."""
    h = 2.8e-3
    x = np.array([1.0, 1.0 + h])
    search = ContactEndSearch()
    search.step(x, np.array([1.547, 3.361e-3]), (0.9, 1.1))
    x2 = x + 2e-6
    new, _ = search.step(x2, np.array([1.547, 3.35e-3]), (0.9, 1.1))
    line = x2[-1] + 3.35e-3 * h / (1.547 - 3.35e-3)
    assert new == pytest.approx(line, abs=1e-12)
    steep = ContactEndSearch()
    steep.step(x, np.array([1.547, 0.1]), (0.9, 1.1))
    x3 = x + 1e-4
    new, _ = steep.step(x3, np.array([1.547, 0.05]), (0.9, 1.1))
    assert new == pytest.approx(x3[-1] - 0.05 * 1e-4 / (0.05 - 0.1), abs=1e-12)


def test_overlap_at_the_ends_of_the_samples():
    """[hand] samples at or before the end only (the end's own sample belongs to the contact,
    even inside the roll): nothing after it; the line at beta = 0.042 sampled to 20 mm past
    the gap (its chord ends at 30.2 mm): inside up to its last sample, where it is said to
    leave, its depth the chord's, R (sqrt(1 + beta^2) - 1) at 15.1 mm."""
    rp = RollPass(R, 0.0125, H1, omega=5.0)
    at_end = np.c_[[0.99, 0.995, 1.0], [H1 + 1e-3] * 3]
    assert overlap_after(at_end, rp, 1.0, 1e-7) == (0.0, None)
    beta = 0.042
    xy = _line(beta)[:41]
    depth, leaves = overlap_after(xy, rp, 1.0, 1e-7)
    assert depth == pytest.approx(R * (math.sqrt(1 + beta**2) - 1), rel=2e-2)
    assert leaves == xy[-1, 0] == pytest.approx(1.02, abs=1e-12)


def test_overlap_of_samples_in_any_order_and_sparse():
    """[hand] the line at beta = 0.042 bent back out of the roll 40 mm past the gap (after its
    chord ends, at 30.2 mm), its samples shuffled: the chord's depth and crossing as in order
    (sorted by x, not by height). Sampled every 20 mm: only the sample at 20 mm inside, by
    d(x) = beta x - R + sqrt(R^2 - x^2) = 0.284 mm; the crossing interpolated between it and
    the one at 40 mm (d = -0.549 mm)."""
    rp = RollPass(R, 0.0125, H1, omega=5.0)
    beta = 0.042
    xy = _line(beta)
    s = xy[:, 0] - 1.0
    xy[s > 0.04, 1] = H1 + beta * 0.04 - 0.1 * (s[s > 0.04] - 0.04)
    xy = xy[np.random.default_rng(52).permutation(len(xy))]
    depth, leaves = overlap_after(xy, rp, 1.0, 1e-7)
    assert depth == pytest.approx(R * (math.sqrt(1 + beta**2) - 1), rel=2e-2)
    assert leaves - 1.0 == pytest.approx(2 * R * beta / (1 + beta**2), rel=3e-3)

    def d(x):
        return beta * x - R + math.sqrt(R * R - x * x)
    depth, leaves = overlap_after(_line(beta, n=4), rp, 1.0, 1e-7)
    assert depth == pytest.approx(d(0.02), rel=1e-9)
    assert leaves - 1.0 == pytest.approx(0.02 + 0.02 * d(0.02) / (d(0.02) - d(0.04)), rel=1e-9)


def test_overlap_tol_and_a_surface_back_on_the_roll():
    """[hand] the line at beta = 0.042, its first sample past the end lowered 30 um (out of
    the roll by t = 9.4 um): with tol = t (out by no more than tol) the stretch still starts
    at the end and leaves where the chord ends; with tol = its depth nothing lies inside by
    more than tol. Its sample 10 mm past the gap put on the roll (y = the roll's height, and
    inside again after it): the stretch leaves there, not where the chord ends."""
    rp = RollPass(R, 0.0125, H1, omega=5.0)
    beta = 0.042
    xy = _line(beta)
    xy[1, 1] -= 3e-5
    t = -float((xy[1:, 1] - rp.height(xy[1:, 0]))[0])
    assert t == pytest.approx(3e-5 - beta * 5e-4 + R - math.sqrt(R * R - 25e-8), rel=1e-6)
    depth, leaves = overlap_after(xy, rp, 1.0, t)
    assert leaves - 1.0 == pytest.approx(2 * R * beta / (1 + beta**2), rel=3e-3)
    assert overlap_after(xy, rp, 1.0, depth) == (depth, None)
    xy = _line(beta)
    xy[20, 1] = rp.height(xy[20, 0])
    assert overlap_after(xy, rp, 1.0, 1e-7)[1] == pytest.approx(xy[20, 0], abs=1e-12)


def test_the_end_search_secant_at_its_guards_edges():
    """[hand] dyadic numbers, exact in floating point (h = 2^-8 m). Two ends exactly one
    element apart, p_end 0.1875 then 0.0625 under a line falling by 0.5 over the last
    element: the secant, exactly a quarter as steep as the line, is taken: its zero half an
    element on (the line's: an eighth). The same end twice (no secant: the line's zero);
    the same p_end twice on a pressure rising to the end (a flat secant, not taken: the
    contact goes on an element)."""
    h = 2.0**-8
    x = np.array([1.0, 1.0 + h])
    search = ContactEndSearch()
    search.step(x, np.array([0.5, 0.1875]), (0.9, 1.1))
    new, _ = search.step(x + h, np.array([0.5625, 0.0625]), (0.9, 1.1))
    assert new == 1.0 + 2.5 * h
    same = ContactEndSearch()
    for _ in range(2):
        new, res = same.step(x, np.array([0.5, 0.1875]), (0.9, 1.1))
        assert new == 1.0 + h + 0.1875 * h / 0.3125 and res == new - (1.0 + h)
    flat = ContactEndSearch()
    flat.step(x, np.array([0.5, 0.75]), (0.9, 1.1))
    new, _ = flat.step(x + 0.5 * h, np.array([0.5, 0.75]), (0.9, 1.1))
    assert new == 1.0 + 2.5 * h


def test_the_outcome_of_both_causes_in_full():
    """[plumb] overlap and a held end on each roll: every reason, joined by "; "; the depth
    in um and the stress in MPa to three digits (22.349995 um: 22.3; -1.2350005 MPa: -1.24),
    the depth in elements (over / h); a held end with a zero contact stress is not tensile."""
    why = contact_problem({"h_contact": 1e-3, "roll_overlap": 2.2349995e-5, "rolls": [
        {"side": "upper", "contact_end_kind": "bound", "contact_end_pressure": 0.0},
        {"side": "lower", "contact_end_kind": "bound", "contact_end_pressure": -1.2350005e6}]})
    assert why == (
        "contact not resolved: the strip's free surface lies 22.3 um (0.0223 elements) inside a "
        "roll past its contact's end (limit 0.02 elements); the upper roll's contact end is held "
        "at the end of its allowed range (half a contact length before the gap, or past it: a "
        "quarter for an elastic strip, half for one that curls onto the roll, at most a "
        "quarter of the exit length solver.steady_exit_length) with the strip "
        "still pressing on the roll: it would follow the roll further than the model does "
        "(asymmetric: a smaller speed or radius ratio, or less friction, curls it less); the "
        "lower roll's contact end is held at the end of its allowed range with a tensile "
        "contact stress there (-1.24 MPa): the strip would leave the roll before it")


def test_the_winkler_prediction_only_from_the_exit_zone():
    """[hand] An elastic layer of compliance c (m per unit of reduced pressure) under a
    pressure p at x_ref at or past the gap, on a roll of radius R: the roll has risen by c p
    at x = 1 + sqrt(R^2 - (sqrt(R^2 - (x_ref - 1)^2) - c p)^2), the prediction's x - x_ref
    within 1 % (its root interpolated on a grid of a contact length / 256).
    From an end 8 mm before the gap (the roll still descending) ``exit_zone`` predicts
    nothing (the strip is plastic there; without it the rule sent the roughing pass's 3D ends
    to the point as far past the gap, issue 53); the end search then takes the line's step,
    the zero of p through the last two vertices, not the mirror point."""
    from hotroll.solvers.contact_end import winkler_end

    rp = RollPass(R, 0.0125, H1, omega=5.0)
    c, p = 2e-6, 0.5
    for x_ref in (1.0, 1.004):
        x = winkler_end(rp, lambda y: c, x_ref, p, exit_zone=True)
        exact = 1.0 + math.sqrt(R**2 - (math.sqrt(R**2 - (x_ref - 1.0) ** 2) - c * p) ** 2)
        assert x - x_ref == pytest.approx(exact - x_ref, rel=1e-2)
    assert winkler_end(rp, lambda y: c, 0.992, p, exit_zone=True) is None
    mirror = winkler_end(rp, lambda y: c, 0.992, p)
    assert mirror > 1.008                       # past the mirror point 1.008 of the old rule
    h = 0.01
    x = np.array([0.992 - h, 0.992])
    new, _ = ContactEndSearch().step(
        x, np.array([2.4, p]), (0.9, 1.1),
        lambda x_ref, p_ref: winkler_end(rp, lambda y: c, x_ref, p_ref, exit_zone=True))
    assert new == pytest.approx(0.992 + p * h / (2.4 - p), abs=1e-12)
