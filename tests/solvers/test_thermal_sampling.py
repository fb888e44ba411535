"""The heat sources' sampling on the thermal strip (``solvers/thermal_sampling.py``).

[identity] The half model's symmetry row samples its dual cell [0, eta_1/2] at the points of
the full strip's mid-plane cell [-eta_1/2, eta_1/2] folded onto y >= 0, with the same weights:
so the full strip of two equal rolls integrates a source symmetric in y as the half model does
(with the half cell's own Gauss points the two models' plastic heat differed by 4-9e-6 at
the fixed point's limit, thermal_pass)."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from hotroll.solvers.thermal_sampling import CELL_POINTS, strip_samples


def _cells(eta: np.ndarray, full: bool):
    X = np.linspace(0.0, 1.0, 5)
    strip = SimpleNamespace(X=X, eta=eta, full=full, shape=(len(eta), len(X)),
                            top_height=lambda x: np.ones_like(x))

    def find(points):
        return {"nr": np.zeros(len(points), dtype=int), "points": np.asarray(points)}

    found, weights = strip_samples(strip, find, n_elements=1).cells
    y = found["points"][:, 1].reshape(len(eta), len(X), CELL_POINTS, CELL_POINTS)
    return y, weights


def test_the_symmetry_rows_points_are_the_full_strips_mid_cell_folded():
    half_eta = np.array([0.0, 0.3, 0.7, 1.0])
    y_half, w_half = _cells(half_eta, full=False)
    y_full, w_full = _cells(np.concatenate([-half_eta[:0:-1], half_eta]), full=True)
    mid = len(half_eta) - 1                                  # the full strip's eta = 0 row
    assert np.allclose(y_half[0], np.abs(y_full[mid]), rtol=0.0, atol=1e-15)
    assert np.all(y_full[mid] != 0.0) and np.all(y_half[0] > 0.0)
    np.testing.assert_array_equal(w_half, w_full)
    # the other rows are each dual cell's own Gauss points, the same in both models
    assert np.allclose(y_half[1:], y_full[mid + 1:], rtol=0.0, atol=1e-15)
