"""The Poiseuille verification's velocity error is relative (solvers/verification.py): the
power-law flow is homogeneous, so doubling the pressure gradient G scales the exact and the
FE velocity alike by 2^(1/m) (4 for m = 0.5) and leaves the relative
L2 error as it is; an absolute error would grow by that factor."""
from __future__ import annotations

import pytest

from hotroll.solvers.verification import poiseuille


def test_the_velocity_error_does_not_change_with_the_pressure_gradient():
    ref, steep = poiseuille(1 / 8, 0.5), poiseuille(1 / 8, 0.5, G=2.0)
    assert ref["converged"] and steep["converged"]
    assert steep["flux"] == pytest.approx(4.0 * ref["flux"], rel=1e-8)
    assert steep["u_error"] == pytest.approx(ref["u_error"], rel=1e-6)
    assert 1e-6 < ref["u_error"] < 3e-4             # measured 9.0e-5 (tests/fem/test_fe_core.py)
