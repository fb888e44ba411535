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
