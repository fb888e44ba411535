"""Entry and exit profiles through the thickness (issue 17: what a schedule hands from pass
to pass; model/profile.py, solvers/record_fields.py): the inlet takes the given temperature
profile exactly, a strain profile is carried along the streamlines (eta in = eta out in a
steady strip with rigid ends), the exit profile's mean is the run's own exit strain, and bad
profiles are refused."""
from __future__ import annotations

import math

import numpy as np
import pytest
from casebuild import build_case

from hotroll.config.case import CaseError
from hotroll.model.profile import ProfileError, ThicknessProfile
from hotroll.solvers.record_fields import exit_profiles
from hotroll.solvers.steady import SteadyRun
from hotroll.workflows.runner import build_model, steady_settings

BASE = {
    "name": "profile",
    "pass": {"roll_radius": 0.3, "entry_thickness": 0.1, "exit_thickness": 0.08,
             "roll_angular_velocity": 1.0},
    "plate": {"length": 0.5, "temperature": 1373.15},
    "material": {"law": "hensel-spittel", "A": 1.5e8, "m1": -0.0025, "m2": 0.05, "m3": 0.15,
                 "density": 7600.0, "specific_heat": 650.0, "conductivity": 30.0},
    "friction": {"law": "coulomb", "mu": 0.3},
    "mesh": {"h_contact": 0.008},
    "solver": {"method": "steady", "threads": 1},
    "output": {"figures": False, "vtk": False},
}
THERMAL = {"htc_contact": 2.0e4, "roll_temperature": 350.0, "htc_air": 20.0,
           "emissivity": 0.8}


def _solve(case):
    model, _ = build_model(case)
    run = SteadyRun(model, steady_settings(case), case.plate.length)
    run.run()
    assert run.result.converged
    return run


def test_the_inlet_takes_the_temperature_profile():
    """The strip mesh's inlet column holds T(eta) of the profile at its rows, to rounding;
    the exit profile is the outlet column, its surface colder than its centre."""
    prof = [[0.0, 1373.15], [0.7, 1365.0], [1.0, 1250.0]]
    case = build_case(BASE, "thermal", THERMAL, **{"plate.temperature_profile": prof})
    run = _solve(case)
    strip = run.thermal.strip
    inlet = run.thermal.field.values.reshape(strip.shape)[:, 0]
    want = ThicknessProfile.from_pairs(prof)(strip.eta)
    assert np.max(np.abs(inlet - want)) < 1e-9
    out = exit_profiles(run)
    assert out["eta"] == pytest.approx(list(strip.eta))
    T = np.asarray(out["temperature"])
    assert T[-1] < T[0] - 50.0


def test_a_strain_profile_is_carried_along_the_streamlines():
    """Entry strain 0 at the centre to 0.3 at the surface against a uniform 0.15 entry: in a
    steady strip with rigid ends the streamline at eta enters and leaves at the same eta, so
    the exit profiles differ by the entry profiles' difference, 0.3 eta - 0.15 (within 0.01,
    the flow changing a little with the hardening m2 = 0.05 and the SUPG transport); the
    exit profile's mean is the run's band-mean exit strain."""
    linear = build_case(BASE, **{"plate.strain_profile": [[0.0, 0.0], [1.0, 0.3]]})
    uniform = build_case(BASE, **{"plate.entry_strain": 0.15})
    a, b = exit_profiles(_solve(linear)), exit_profiles(_solve(uniform))
    eta = np.asarray(a["eta"])
    # no thermal strip mesh: the isothermal grid of 21 rows, eta = 0, 0.05, ..., 1
    assert a["eta"] == b["eta"] == pytest.approx([k / 20 for k in range(21)], abs=1e-15)
    diff = np.asarray(a["strain"]) - np.asarray(b["strain"])
    assert np.max(np.abs(diff - (0.3 * eta - 0.15))) < 0.01
    inc = 2.0 / math.sqrt(3.0) * math.log(0.1 / 0.08)
    mean = ThicknessProfile(tuple(eta), tuple(b["strain"])).mean()
    assert inc < mean - 0.15 < 1.25 * inc


def test_profile_arithmetic():
    p = ThicknessProfile.from_pairs([[0.0, 1.0], [0.5, 3.0], [1.0, 3.0]])
    assert p.mean() == pytest.approx(0.5 * 2.0 + 0.5 * 3.0)
    assert p.weights().tolist() == [0.25, 0.5, 0.25]
    assert p([0.25, 2.0, -1.0]).tolist() == [2.0, 3.0, 1.0]
    assert p.scaled(2.0).mean() == pytest.approx(2 * p.mean())
    assert ThicknessProfile.uniform(4.0).is_uniform and not p.is_uniform
    for bad in ([[0.0, 1.0]], [[0.0, 1.0], [0.9, 2.0]], [[0.0, 1.0], [0.0, 2.0], [1.0, 2.0]],
                [[0.0, 1.0], [1.0, float("nan")]]):
        with pytest.raises(ProfileError):
            ThicknessProfile.from_pairs(bad)


def test_folding_a_whole_thickness_profile_by_hand():
    """[hand] ``fold``: a whole-thickness profile (eta -1..1, an asymmetric pass's) as the
    mean of its two halves at every |eta| of either: a linear a + b eta folds to the constant
    a; nodes of one half only (0.3 below, 0.5 above) are both kept; the section mean over
    [-1, 1] is kept exactly (piecewise linear, by hand: the two trapezoid sums)."""
    lin = ThicknessProfile.fold([-1.0, 1.0], [1300.0, 1100.0])
    assert lin.eta == (0.0, 1.0) and lin.values == (1200.0, 1200.0)
    eta = [-1.0, -0.3, 0.0, 0.5, 1.0]
    vals = [10.0, 4.0, 2.0, 3.0, 6.0]
    f = ThicknessProfile.fold(eta, vals)
    assert f.eta == (0.0, 0.3, 0.5, 1.0)
    # f(0.3) = (4 + (2 + 0.6 x 1)) / 2; f(0.5) = (3 + (4 + 6 x 0.2 / 0.7)) / 2 ...
    assert f(0.3)[()] == pytest.approx(0.5 * (4.0 + 2.6))
    assert f(0.5)[()] == pytest.approx(0.5 * (3.0 + 4.0 + 6.0 * 0.2 / 0.7))
    whole = sum(0.5 * (a + b) * (e1 - e0) for a, b, e0, e1 in
                zip(vals[:-1], vals[1:], eta[:-1], eta[1:])) / 2.0
    assert f.mean() == pytest.approx(whole, rel=1e-14)
    for bad in ([0.0, 1.0], [-1.0, 0.5], [-1.0, 0.0, 0.0, 1.0]):
        with pytest.raises(ProfileError):
            ThicknessProfile.fold(bad, [1.0] * len(bad))


def test_a_whole_thickness_exit_profile_is_folded_by_hand():
    """[hand] ``folded``: an asymmetric pass's exit profile (eta -1..1) as the half thickness's,
    each list the mean of its two halves (the shear strain, odd about the middle, left out;
    None kept); a half-thickness profile is returned as it is."""
    from hotroll.model.profile import folded

    full = {"eta": [-1.0, 0.0, 1.0], "temperature": [1000.0, 1300.0, 1100.0],
            "strain": None, "shear_strain": [0.1, 0.0, -0.1], "pass_strain": [0.4, 0.2, 0.6]}
    half = folded(full)
    assert half["eta"] == [0.0, 1.0] and half["strain"] is None and "shear_strain" not in half
    assert half["temperature"] == [1300.0, 1050.0] and half["pass_strain"] == [0.2, 0.5]
    own = {"eta": [0.0, 1.0], "temperature": [1.0, 2.0]}
    assert folded(own) is own and folded(None) is None


@pytest.mark.parametrize("dotted,field", [
    ({"plate.temperature_profile": [[0.0, 1300.0], [1.0, 1200.0]]},
     "plate.temperature_profile: needs a [thermal] section"),
    ({"plate.strain_profile": [[0.0, 0.1], [1.0, 0.2]], "solver.method": "transient"},
     "plate.strain_profile: needs solver.method"),
    ({"plate.strain_profile": [[0.0, -0.1], [1.0, 0.2]]}, "plate.strain_profile"),
    ({"plate.strain_profile": [[0.2, 0.1], [1.0, 0.2]]}, "plate.strain_profile"),
])
def test_bad_profiles_name_the_field(dotted, field):
    with pytest.raises(CaseError) as e:
        build_case(BASE, **dotted)
    assert field in str(e.value)
