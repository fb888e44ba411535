"""The contact pressure along the arc (issue 50: "the pressure's ends"): the multiplier's nodal
forces over their lengths (``fem/quantities.nodal_traction``) carry no vertex dips, at the
entry corner either, and the entry value converges under refinement.

- [derived] the P1 multiplier's own nodal values ring where the traction changes abruptly:
  inverting the arc's P1 mass matrix against a concentrated corner load alternates with the
  ratio -(2 - sqrt3) = -0.27 per vertex (27 % at the lab pass's second vertex); the nodal
  forces are the same sums and do not ring;
- [derived] a rate-dependent strip's stress is singular at the entry corner, about r^-m (the
  flow turns there: its strain rate ~ 1/r, sigma ~ edot^m), so the corner's nodal value grows
  as h^-m under refinement, at most by 2^m per halving; its mean over a fixed length from the
  start (``entry_pressure``: 5 % of the contact) converges.
"""
from __future__ import annotations

import numpy as np
import pytest
from casebuild import shared_scope

import hotroll

#: the issue's lab pass: S355J2 at 1000 degC, 10 -> 7.5 mm, R 0.1 m, 1 m/s, Coulomb 0.3
LAB = {"pass.roll_radius": 0.1, "pass.entry_thickness": 0.010, "pass.exit_thickness": 0.0075,
       "pass.roll_angular_velocity": 10.0}
MESHES = (0.000625, 0.0003125, 0.00015625)


def _solve(name: str, **over):
    case = hotroll.example_case(name).with_overrides(
        **{"solver.threads": 1, "output.figures": False, "output.vtk": False, **over})
    return case, hotroll.solve(case)


def _vertices(res):
    c = res.contact
    v = np.asarray(c["vertex"]) == 1
    x, p = np.asarray(c["x"])[v], -np.asarray(c["normal_stress"])[v]
    order = np.argsort(x)
    return x[order], p[order]


def _largest_dip(p: np.ndarray) -> float:
    """The deepest vertex below both its neighbours, over the peak."""
    dip = np.minimum(p[:-2], p[2:]) - p[1:-1]
    return float(max(dip.max(initial=0.0), 0.0) / p.max())


@pytest.fixture(scope=shared_scope)
def lab_meshes():
    return [_solve("hot_strip_finishing", **LAB, **{"mesh.h_contact": h}) for h in MESHES]


@pytest.fixture(scope=shared_scope)
def lab_meshes_uniform():
    """The same without the refinement at the contact's start: the corner's element h, so
    the meshes are alike near the corner (refined, netgen's first arc edge is 79 %, 98 % and
    86 % of h/16: the corner's nodal value follows those, not h)."""
    return [_solve("hot_strip_finishing", **LAB, **{"mesh.h_contact": h,
                                                     "mesh.corner_refinement": 1.0})
            for h in MESHES]


@pytest.mark.parametrize("name,over", [("hot_strip_finishing", LAB), ("hot_strip_finishing", {}),
                                       ("thin_strip", {}), ("roughing_slab", {})],
                         ids=["lab", "finishing", "thin_strip", "roughing_slab"])
def test_no_vertex_dips_below_its_neighbours_on_the_arc(name, over):
    """Automatic mesh: no vertex lies more than 5 % of the peak below both its neighbours,
    the entry corner's neighbour included (the multiplier's own values: 27 % on the lab
    pass); the pressure is nowhere tensile beyond 1e-3 of the peak."""
    _, res = _solve(name, **over)
    assert res.summary["exit_code"] == 0, res.summary["failure"]
    _, p = _vertices(res)
    assert _largest_dip(p) <= 0.05
    assert p.min() >= -1e-3 * p.max()


def test_the_entry_pressure_converges_and_the_corner_grows_at_most_as_h_to_the_minus_m(
        lab_meshes, lab_meshes_uniform):
    """The lab pass on three meshes (h, h/2, h/4): ``entry_pressure`` converges (each change
    at most 0.7 of the one before: measured 0.22 on the default mesh refined at the contact's
    start, 0.61 without); on the meshes without the refinement (the corner's element h) the
    corner's nodal value grows by at most 2^m per halving (5 % slack; m = 0.127 at 1000 degC:
    measured 1.08 and 1.12 against 1.09); no dips on any."""
    for meshes in (lab_meshes_uniform, lab_meshes):
        entry = [res.summary["entry_pressure"] for _, res in meshes]
        assert abs(entry[2] - entry[1]) <= 0.7 * abs(entry[1] - entry[0])
    # [definition] the mean over the first 5 % of the arc's length, by hand from contact.csv
    c = lab_meshes[0][1].contact
    x, y, p = (np.asarray(c[k]) for k in ("x", "y", "normal_stress"))
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    t = np.linspace(0.0, 0.05 * s[-1], 2001)
    assert entry[0] == pytest.approx(-np.trapezoid(np.interp(t, s, p), t) / t[-1], rel=1e-4)
    m = lab_meshes[0][1].summary["m"]
    corners = [_vertices(res)[1][0] for _, res in lab_meshes_uniform]
    for a, b in zip(corners, corners[1:]):
        assert 1.0 < b / a <= 1.05 * 2.0**m
    for _, res in lab_meshes + lab_meshes_uniform:
        assert _largest_dip(_vertices(res)[1]) <= 0.05
