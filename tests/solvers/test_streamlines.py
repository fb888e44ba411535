"""The streamline histories of a steady pass (issue 33, solvers/streamlines.py) under an exact
scaling of the equations: a flow stress that does not depend on T (Hensel-Spittel with
m1 = 0: a power law in the rate) and Coulomb friction make the flow scale with the roll speed:
doubling it doubles every velocity and halves every time, so each streamline's pass strain is
unchanged and its mean ln(edot) rises by ln 2 exactly. The temperature (no exchange with the
roll or the air) rises by the plastic and the friction work only: with rho c a thousand times
steel's, by less than 2 K, so every mean 1/T equals the entry's to 2e-3.

The two runs' flows scale to 1.5e-6 (the force ratio 2^0.15); their thermal strips do not
(the rows follow the heat layer's depth, sqrt(alpha l / U)), and the streamlines are traced on
them. The centre's and the surface's streamlines are the same lines in both: there the means
agree to 1.3e-4 in strain and 9e-4 in ln(edot) (measured; asserted 1e-3 and 2e-3). Between,
the streamlines sit at other heights and one of them may cross the shear band from the bite's
corner (its rate 1.5-2.4x its neighbours' on this mesh): a profile's spike moves from eta
0.79 to 0.82. Over the section the means agree to 0.3 % and 0.004 (asserted 0.5 % and 0.01)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from hotroll.config.case import case_from_dict
from hotroll.workflows.runner import run_case


def _case(omega: float):
    return case_from_dict({
        "name": f"adiabatic_{omega:g}",
        "pass": {"roll_radius": 0.3, "entry_thickness": 0.1, "exit_thickness": 0.08,
                 "roll_angular_velocity": omega},
        "plate": {"length": 0.5, "temperature": 1373.15},
        "material": {"law": "hensel-spittel", "A": 1.5e8, "m1": 0.0, "m2": 0.1,
                     "m3": 0.15, "density": 7600.0, "specific_heat": 6.5e5,
                     "conductivity": 30.0},
        "friction": {"law": "coulomb", "mu": 0.3},
        "mesh": {"h_contact": 0.008},
        "solver": {"method": "steady", "threads": 1},
        "output": {"figures": False, "vtk": False},
        "thermal": {"htc_contact": 0.0, "roll_temperature": 350.0, "htc_air": 0.0,
                    "emissivity": 0.0},
    })


@pytest.mark.parametrize("factor", [2.0])
def test_streamline_means_scale_exactly_with_the_roll_speed(tmp_path, factor):
    slow = run_case(_case(1.0), tmp_path / "slow", resume=False)["exit_profile"]
    fast = run_case(_case(factor), tmp_path / "fast", resume=False)["exit_profile"]
    eta = np.asarray(slow["eta"])

    def at(prof, key):                  # the strip's rows follow the heat layer's depth
        return np.interp(eta, prof["eta"], prof[key])

    def mean(prof, key):                # over the section (eta), trapezoids
        e, v = np.asarray(prof["eta"]), np.asarray(prof[key])
        return float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(e)))

    for i in (0, -1):                   # the centre line and the surface
        assert fast["pass_strain"][i] == pytest.approx(slow["pass_strain"][i], rel=1e-3)
        assert fast["log_rate_mean"][i] - slow["log_rate_mean"][i] == pytest.approx(
            math.log(factor), abs=2e-3)
    assert slow["pass_strain"][0] > 0.2
    assert mean(fast, "pass_strain") == pytest.approx(mean(slow, "pass_strain"), rel=5e-3)
    assert mean(fast, "log_rate_mean") - mean(slow, "log_rate_mean") == pytest.approx(
        math.log(factor), abs=0.01)
    for prof in (slow, fast):
        assert np.allclose(prof["inverse_temperature_mean"], 1.0 / 1373.15, rtol=2e-3)
    # the plastic and friction work heat every streamline a little: above the entry's T
    assert np.all(1.0 / np.asarray(slow["inverse_temperature_mean"]) > 1373.15)


def test_the_bilinear_interpolation_is_scipys():
    """``streamlines.bilinear`` against scipy's RegularGridInterpolator (linear) on an uneven
    grid, at random points inside it, its nodes and its edges (1e-12)."""
    from scipy.interpolate import RegularGridInterpolator

    from hotroll.solvers.streamlines import bilinear

    rng = np.random.default_rng(0)
    a = np.cumsum(rng.uniform(0.1, 1.0, 9)) - 0.5
    b = np.cumsum(rng.uniform(0.01, 0.3, 14))
    v = rng.standard_normal((len(a), len(b)))
    pa = np.concatenate([rng.uniform(a[0], a[-1], 200), a, np.full(3, a[-1])])
    pb = np.concatenate([rng.uniform(b[0], b[-1], 200), rng.uniform(b[0], b[-1], len(a)),
                         [b[0], b[-1], b[5]]])
    ref = RegularGridInterpolator((a, b), v)(np.stack([pa, pb], -1))
    assert np.allclose(bilinear(a, b, v, pa, pb), ref, rtol=0, atol=1e-12)
