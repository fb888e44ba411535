"""``p1_supg_tau`` on one triangle worked out by hand, at a Peclet number between the series
branch (Pe < 1e-2) and the large ones the strip's tests reach (tests/fem/test_thermal.py):
the right triangle (0, 0), (1, 0), (0, 1) with v = (1, 0) has v.grad N = (-1, 1, 0), so
h_v = 2 |v| / 2 = 1 and Pe = |v| h_v rho c / (2 k)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from hotroll.fem.heat_p1 import p1_gradients, p1_supg_tau


@pytest.mark.parametrize("pe", [0.02, 0.5, 1.0])
def test_tau_is_h_over_2v_times_coth_pe_minus_one_over_pe(pe):
    """rho c = 2 Pe, k = 1: tau = h / (2 |v|) (coth Pe - 1/Pe) = (coth Pe - 1/Pe) / 2, to
    round-off (the series pe/3 - pe^3/45 is 4e-4 off at Pe = 0.5)."""
    grads, det = p1_gradients(np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]),
                              np.array([[0, 1, 2]]))
    tau = p1_supg_tau(grads, det, np.array([[1.0, 0.0]]), 2.0 * pe, 1.0)
    expected = 0.5 * (1.0 / math.tanh(pe) - 1.0 / pe)
    assert tau[0] == pytest.approx(expected, rel=1e-9)
