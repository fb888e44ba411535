"""The 3D outlet's temperature difference from mid-width's (solvers/spread_record.exit_offset,
issue 53) on a made-up outlet: two heights, the levels of an edge zone (no 3D solve).

Labels: [hand] the values by hand."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from hotroll.solvers.spread_record import exit_offset


def test_an_edge_zones_offset_is_zero_up_to_its_cut_and_read_over_the_deformed_outlet():
    """[hand] a 2D mesh of 3 vertices (two on the outlet, x = 1, at y = 0 and 0.5), four
    width levels at z = 0, 0.6, 0.8, 1.0 (an edge zone cut at 0.6 of the half width, its
    interior one layer carrying the cut's values), the outlet's heights 0 and 0.4 (deformed),
    the edge bulging to 1.1 at the top: eta 0 and 1, zeta the levels over the edge's z at each
    height, averaged; the values less mid-width's (the carried residue)."""
    nv, z = 3, np.array([0.0, 0.6, 0.8, 1.0])
    P = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.5]])
    X3 = np.zeros((nv * 4, 3))
    for k, zk in enumerate(z):
        X3[k * nv:(k + 1) * nv, :2] = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.4]]
        X3[k * nv:(k + 1) * nv, 2] = zk
    X3[3 * nv + 2, 2] = 1.1                         # the edge's top vertex bulges out
    theta = np.zeros(nv * 4)
    theta[[1, 2, nv + 1, nv + 2]] = 0.5              # the interior's residue
    theta[[2 * nv + 1, 2 * nv + 2]] = [-4.5, -9.5]
    theta[[3 * nv + 1, 3 * nv + 2]] = [-19.5, -29.5]
    s3 = SimpleNamespace(run2d=SimpleNamespace(mesh=SimpleNamespace(nv=nv)), z=z,
                         cooling=SimpleNamespace(values=theta))
    out = exit_offset(s3, X3, np.isclose(P[:, 0], 1.0), P)
    assert out["eta"] == [0.0, 1.0]
    assert out["zeta"] == pytest.approx([0.0, 0.5 * (0.6 + 0.6 / 1.1), 0.5 * (0.8 + 0.8 / 1.1),
                                         1.0])
    assert np.max(np.abs(np.asarray(out["values"]) - [[0.0, 0.0, -5.0, -20.0],
                                                      [0.0, 0.0, -10.0, -30.0]])) <= 1e-12
