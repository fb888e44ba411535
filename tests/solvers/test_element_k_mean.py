"""An element's temperature for the flow stress (ThermalCoupling._element_means): the one
whose consistency K(eps_entry, T) is the weighted mean of K over the strip vertices inside it,
found between the coldest and the hottest of them. By hand for a K concave in T, K = 2 -
(T / 1000 K)^2 (a law falling with T, but not convex like Hensel-Spittel's exponential):
vertices at 1000 and 1400 K, equal weights: mean K = (1 + 0.04) / 2 = 0.52, so T = 1000 K
sqrt(1.48) = 1216.55 K, above the plain mean 1200 K (a convex K puts it below)."""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from hotroll.solvers.thermal_coupling import ThermalCoupling


def test_a_concave_laws_element_temperature_is_its_k_mean():
    flow = SimpleNamespace(consistency=lambda eps, T: 2.0 - (np.asarray(T) / 1000.0) ** 2)
    coupling = SimpleNamespace(mesh=SimpleNamespace(ne=1), _owner=np.zeros(2, dtype=int),
                               flow=flow, entry_strain=0.0, _mid=None)
    T = ThermalCoupling._element_means(coupling, np.array([1000.0, 1400.0]), np.ones(2))
    assert T[0] == pytest.approx(1000.0 * math.sqrt(1.48), rel=1e-8)
