"""The fitted law names where it came from (model/flow_stress_fit.py): its ``name``, which
``describe()`` carries into compare.json's inputs, is "fitted to a flow-stress function"."""
from __future__ import annotations

from hotroll.model.flow_stress import HenselSpittel
from hotroll.model.flow_stress_fit import fit_hensel_spittel


def test_the_fitted_law_is_named_a_fit():
    law = HenselSpittel(A=2.0e9, m1=-0.0025, m2=0.3, m3=0.05)
    fit = fit_hensel_spittel(law.sigma, (0.0, 0.6), (1.0, 50.0), (1100.0, 1350.0))
    assert fit.law.name == fit.law.describe()["name"] == "fitted to a flow-stress function"
