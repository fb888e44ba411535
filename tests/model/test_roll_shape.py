"""A flattened roll's geometry (model/geometry.py ``RollShape``) against the circle it must be
when the shape is Hitchcock's: a rigid roll of radius R' through the same lowest point."""
from __future__ import annotations

import math

import numpy as np
import pytest

from hotroll.model.geometry import RollPass, RollShape

R, RP = 0.35, 0.42            # nominal and flattened radius, m
H0, H1 = 0.006, 0.005


@pytest.fixture(scope="module")
def pair():
    theta = np.linspace(-0.1, 0.3, 400)
    shaped = RollPass(R, H0, H1, omega=10.0, axis_x=0.7, shape=RollShape.circle(R, RP, theta))
    circle = RollPass(RP, H0, H1, omega=10.0 * R / RP, axis_x=0.7)
    return shaped, circle


def test_a_circular_shape_is_the_bigger_circle(pair):
    shaped, circle = pair
    assert shaped.x_touch == pytest.approx(circle.x_touch, rel=1e-9, abs=1e-12)
    assert shaped.contact_length == pytest.approx(circle.contact_length, rel=1e-7)
    x = np.linspace(circle.x_touch, circle.axis_x, 50)
    assert np.allclose(shaped.height(x), circle.height(x), rtol=0, atol=1e-9 * R)
    pts = np.stack([x, circle.height(x)], -1)
    assert np.allclose(shaped.signed_distance(pts), 0.0, atol=1e-9 * R)
    assert np.allclose(shaped.normal(pts), circle.normal(pts), atol=1e-7)
    assert np.allclose(shaped.tangent(pts), circle.tangent(pts), atol=1e-7)
    # a point off the surface goes back onto it along the radius of the nominal roll
    off = pts + np.array([0.0, -1e-4])
    assert np.allclose(shaped.signed_distance(shaped.project(off)), 0.0, atol=1e-9 * R)
    assert np.all(shaped.signed_distance(off) > 0.0)       # below the roll: outside it


def test_the_rim_speed_is_nominal_and_the_lowest_point_is_the_gap(pair):
    shaped, circle = pair
    assert shaped.u_roll == pytest.approx(10.0 * R)
    assert shaped.height(np.array([shaped.axis_x]))[0] == pytest.approx(H1, abs=1e-12)
    x = np.linspace(shaped.x_touch, shaped.axis_x + 0.01, 200)
    assert shaped.height(x).min() >= H1 - 1e-12


def test_the_rigid_roll_is_untouched():
    rp = RollPass(R, H0, H1, omega=10.0, axis_x=0.7)
    assert rp.bite_angle == math.acos(1.0 - (H0 - H1) / R)
    pts = np.array([[0.69, 0.0052], [0.68, 0.0058]])
    assert np.array_equal(rp.normal(pts), (np.asarray(rp.centre) - pts)
                          / np.linalg.norm(np.asarray(rp.centre) - pts, axis=-1, keepdims=True))
    assert np.all(rp.tilt(pts) == 0.0)


def test_bad_shapes_are_refused():
    with pytest.raises(ValueError, match="increase"):
        RollShape([0.0, 0.2, 0.1, 0.3], np.zeros(4))
    with pytest.raises(ValueError, match="at least 4"):
        RollShape([0.0, 0.1], np.zeros(2))


def _two_dips(depth_second: float, tie: float) -> RollShape:
    """A roll surface with two lowest points (local maxima of h = (R + w) cos t, the height
    below the roll's centre) at t = -0.004 and -0.001 rad, 1 um proud of a gentle bowl, the
    second ``depth_second`` m less proud than the first."""
    t = np.linspace(-0.02, 0.05, 701)
    h = (R + 1e-6 * (np.exp(-((t + 0.004) / 5e-4) ** 2)
                     + (1.0 - depth_second / 1e-6) * np.exp(-((t + 0.001) / 5e-4) ** 2))
         - 2e-6 * (t / 0.02) ** 2)
    return RollShape(t, h / np.cos(t) - R, tie=tie)


def test_the_exit_is_the_lowest_point_unless_another_is_as_low_and_nearer_the_last():
    """Two dips 0.2 um apart in height: without a tie the lower one is the exit; with a tie of
    0.5 um the one nearest the last exit is kept (the surface set again, as the coupling
    does); with the last exit's dip 0.9 um less low, the lowest wins despite the tie."""
    near = _two_dips(0.2e-6, tie=0.0)
    assert near.lowest(R)[0] == pytest.approx(-0.004, abs=2e-4)
    s = _two_dips(0.2e-6, tie=0.5e-6)
    s._previous_t = -0.001                 # the last exit at the other dip
    assert s.lowest(R)[0] == pytest.approx(-0.001, abs=2e-4)
    s.set(s.theta, s.w, s.hoop)            # an update keeps the last exit as the reference
    assert s._previous_t == pytest.approx(-0.001, abs=2e-4)
    assert s.lowest(R)[0] == pytest.approx(-0.001, abs=2e-4)
    far = _two_dips(0.9e-6, tie=0.5e-6)    # the -0.001 dip 0.9 um less low: not the exit
    far._previous_t = -0.001
    assert far.lowest(R)[0] == pytest.approx(-0.004, abs=2e-4)
    assert s.copy().tie == 0.5e-6 and s.copy()._previous_t == s._previous_t


def test_the_bite_angle_follows_the_shape_it_is_cached_for():
    """The flattened bite angle is cached on the shape (issue 34): a new surface (``set``) must
    give the new circle's angle, not the old one."""
    theta = np.linspace(-0.1, 0.3, 400)
    shape = RollShape.circle(R, RP, theta)
    rp = RollPass(R, H0, H1, omega=10.0, axis_x=0.7, shape=shape)
    first = rp.bite_angle
    assert rp.bite_angle == first                               # cached, same value
    bigger = RollShape.circle(R, 1.5 * RP, theta)
    shape.set(theta, bigger.w, bigger.hoop)
    fresh = RollPass(R, H0, H1, omega=10.0, axis_x=0.7, shape=RollShape.circle(R, 1.5 * RP, theta))
    assert rp.bite_angle == pytest.approx(fresh._flattened_bite_angle(), rel=1e-12)
    assert rp.bite_angle > first * 1.05                        # a flatter roll bites longer


def test_a_copy_is_its_own_surface_and_the_touching_point_follows_set():
    """``copy`` shares the splines: setting a new surface on the copy leaves the original's
    values; the cached touching point follows a new surface (``set``) like the bite angle."""
    theta = np.linspace(-0.1, 0.3, 400)
    shape = RollShape.circle(R, RP, theta)
    rp = RollPass(R, H0, H1, omega=10.0, axis_x=0.7, shape=shape)
    x0, t = rp.x_touch, np.linspace(0.0, 0.2, 7)
    before = shape.offset(t)
    twin = shape.copy()
    assert np.array_equal(twin.offset(t), before) and np.array_equal(twin.w, shape.w)
    bigger = RollShape.circle(R, 1.5 * RP, theta)
    twin.set(theta, bigger.w, bigger.hoop)
    assert np.array_equal(shape.offset(t), before) and rp.x_touch == x0
    shape.set(theta, bigger.w, bigger.hoop)
    fresh = RollPass(R, H0, H1, omega=10.0, axis_x=0.7,
                     shape=RollShape.circle(R, 1.5 * RP, theta))
    assert rp.x_touch == fresh.x_touch < x0                    # a flatter roll bites longer
