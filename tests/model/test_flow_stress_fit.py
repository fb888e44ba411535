"""The Hensel-Spittel fit of a flow-stress function (hotroll/model/flow_stress_fit.py, the
PyRolL plugin's bridge to the FE law): a function of the fitted form is recovered to rounding;
Freiberg's form (Spittel's S355J2 coefficients at strain + 0.1 and rate + 0.1, as
pyroll-freiberg-flow-stress evaluates them, written out here) is fitted within 5 %, and the
reported error is the largest on an independent finer grid within 10 %; bad ranges refused."""
from __future__ import annotations

import math

import numpy as np
import pytest

from hotroll.model.flow_stress import HenselSpittel
from hotroll.model.flow_stress_fit import fit_hensel_spittel

pytestmark = pytest.mark.mutation


def test_a_law_of_the_fitted_form_is_recovered():
    law = HenselSpittel(A=2.0e9, m1=-0.0025, m2=0.3, m3=0.05, m5=-0.001, m7=0.2, m8=1.2e-4)
    fit = fit_hensel_spittel(law.sigma, (0.0, 0.6), (1.0, 50.0), (1100.0, 1350.0))
    assert fit.max_rel_error < 1e-9
    for k, v in law.params().items():
        assert fit.law.params()[k] == pytest.approx(v, rel=1e-7, abs=1e-12)


def _freiberg_s355j2(e, r, T):
    """sigma of pyroll-freiberg-flow-stress 3.0.1 for S355J2 (Pa), its formula and numbers."""
    A, m1, m2, m4, m5, m7, m8 = 2852.66e6, -0.00244, 0.41934, 0.00088, -0.00149, 0.12169, 0.000127
    e, r, t = e + 0.1, r + 0.1, T - 273.15
    return (A * math.exp(m1 * t) * e ** m2 * math.exp(m4 / e) * (1 + e) ** (m5 * t)
            * math.exp(m7 * e) * r ** (m8 * t))


def test_freibergs_form_is_fitted_within_five_percent():
    box = ((0.0, 0.4), (2.0, 60.0), (1100.0, 1330.0))
    fit = fit_hensel_spittel(_freiberg_s355j2, *box)
    assert fit.max_rel_error < 0.05
    E, R, T = np.meshgrid(np.linspace(0.03, 0.4, 13), np.geomspace(2.0, 60.0, 13),
                          np.linspace(1100.0, 1330.0, 13), indexing="ij")
    got = fit.law.sigma(E.ravel(), R.ravel(), T.ravel())
    want = np.array([_freiberg_s355j2(*p) for p in zip(E.ravel(), R.ravel(), T.ravel())])
    assert np.max(np.abs(got / want - 1.0)) < 1.1 * fit.max_rel_error


@pytest.mark.parametrize("box", [((0.0, 0.4), (0.0, 60.0), (1100.0, 1300.0)),
                                 ((0.0, 0.4), (2.0, 60.0), (200.0, 1300.0)),
                                 ((0.5, 0.4), (2.0, 60.0), (1100.0, 1300.0))])
def test_bad_fitting_ranges_are_refused(box):
    with pytest.raises(ValueError, match="flow-stress fit"):
        fit_hensel_spittel(_freiberg_s355j2, *box)


def test_non_positive_stresses_are_refused():
    with pytest.raises(ValueError, match="non-positive"):
        fit_hensel_spittel(lambda e, r, T: -1.0, (0.0, 0.4), (2.0, 60.0), (1100.0, 1300.0))
