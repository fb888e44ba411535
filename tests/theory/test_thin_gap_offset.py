"""The velocity profile's forward-slip offset (theory/thin_gap.py) at two points worked out by
hand: at a neutral point on the gap (phi_n = 0) it is (1 + f) h_n / (6 R); it vanishes where
h_n / (6 R cos^3 phi_n) = (2/3) tan^2 phi_n, i.e. h_n = 4 R sin^2 phi_n cos phi_n."""
from __future__ import annotations

import math

import pytest

from hotroll.theory import profile_slip_offset


def test_the_offset_on_the_gap_is_h_over_6r():
    """R 0.5 m, h_n 6 mm, f = 0.02: 1.02 x 0.006 / 3 = 2.04e-3."""
    assert profile_slip_offset(0.5, 0.006, 0.0, 0.02) == pytest.approx(2.04e-3, rel=1e-14)


def test_the_offset_vanishes_where_the_two_terms_balance():
    phi, R = 0.1, 0.5
    h = 4.0 * R * math.sin(phi) ** 2 * math.cos(phi)
    assert profile_slip_offset(R, h, phi, 0.03) == pytest.approx(0.0, abs=1e-15)
