"""fem/point_search.py against NGSolve's own point search, on a graded Netgen mesh (the steady
solver's) and on random points, outside points included."""
from __future__ import annotations

import numpy as np
import pytest

from hotroll.fem import point_search as PS


@pytest.fixture(scope="module")
def graded():
    """The steady strip's mesh of a thin finishing pass (graded: fine along the arc)."""
    from hotroll.config.case import load_case
    from hotroll.examples import example_path
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.runner import build_model, steady_settings

    case = load_case(example_path("hot_strip_finishing")).with_overrides(
        **{"solver.method": "steady"})
    model, _ = build_model(case)
    return SteadyRun(model, steady_settings(case), case.plate.length).mesh


def test_the_same_points_as_ngsolves_search(graded):
    mesh = graded
    mesh.UnsetDeformation()
    pts = np.asarray(mesh.ngmesh.Coordinates())[:, :2]
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    rng = np.random.default_rng(1)
    xy = lo + (hi - lo) * rng.random((20000, 2))
    # every vertex and edge midpoint too: points on the triangles' edges and corners
    from hotroll.fem.mesh import mesh_triangles

    tris = mesh_triangles(mesh)
    mids = 0.5 * (pts[tris] + pts[np.roll(tris, 1, axis=1)]).reshape(-1, 2)
    xy = np.vstack([xy, pts, mids])
    theirs = mesh(xy[:, 0], xy[:, 1])
    mine = PS.mesh_points(mesh, xy[:, 0], xy[:, 1])
    assert mine.dtype == theirs.dtype
    inside = theirs["nr"] >= 0
    assert 0.3 < inside.mean() < 1.0        # the strip is not its bounding box
    # inside one triangle alone the triangle is unique; on an edge or a corner (the vertices
    # and midpoints) NGSolve's own choice is taken: the same triangles everywhere
    assert np.array_equal(mine["nr"], theirs["nr"])
    assert np.max(np.abs(mine["x"][inside] - theirs["x"][inside])) < 1e-12
    assert np.max(np.abs(mine["y"][inside] - theirs["y"][inside])) < 1e-12
    # ... and the same position: x v0 + y v1 + (1 - x - y) v2 of the triangle found
    v = pts[tris[mine["nr"][inside]]]
    lx, ly = mine["x"][inside, None], mine["y"][inside, None]
    found = lx * v[:, 0] + ly * v[:, 1] + (1.0 - lx - ly) * v[:, 2]
    assert np.max(np.abs(found - xy[inside])) < 1e-12 * float(np.max(np.abs(pts)))
    # the numpy search alone: on the same triangle wherever NGSolve's is unambiguous
    elem, _ = PS.for_mesh(mesh).find(xy[:, 0], xy[:, 1])
    assert np.array_equal(elem >= 0, inside)
    assert (elem[:20000] == theirs["nr"][:20000])[inside[:20000]].mean() > 0.999

def test_a_field_evaluated_on_the_points_found(graded):
    """A continuous P2 field (NGSolve's evaluation) is the same on either search's points
    inside the triangles (the edge midpoints go to NGSolve's search in both: their part of
    the check compares NGSolve with itself; the band next to the edges is the next test's)."""
    from ngsolve import H1, GridFunction, sin, x, y

    mesh = graded
    mesh.UnsetDeformation()
    gf = GridFunction(H1(mesh, order=2))
    gf.Set(sin(40.0 * x) * y + x * x)
    pts = np.asarray(mesh.ngmesh.Coordinates())[:, :2]
    from hotroll.fem.mesh import mesh_triangles

    tris = mesh_triangles(mesh)
    xy = np.einsum("k,nkd->nd", np.array([0.2, 0.3, 0.5]), pts[tris])     # inside each one
    xy = np.vstack([xy, 0.5 * (pts[tris[:, 0]] + pts[tris[:, 1]])])   # on the edges
    a = np.asarray(gf(PS.mesh_points(mesh, xy[:, 0], xy[:, 1]))).ravel()
    b = np.asarray(gf(mesh(xy[:, 0], xy[:, 1]))).ravel()
    assert np.max(np.abs(a - b)) < 1e-12 * np.max(np.abs(b))


def test_outside_points_and_degenerate_input():
    """Two triangles of the unit square: points outside get -1; one point; no points."""
    s = PS.TriangleSearch(np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float),
                          np.array([[0, 1, 2], [0, 2, 3]]))
    elem, local = s.find([0.75, 0.25, 1.5, -0.1, 0.5], [0.25, 0.75, 0.5, 0.5, 0.5])
    assert list(elem[:2]) == [0, 1] and list(elem[2:4]) == [-1, -1] and elem[4] in (0, 1)
    # (0.75, 0.25) in triangle 0 (v0 (0,0), v1 (1,0), v2 (1,1)): x v0 + y v1 + (1-x-y) v2
    x, y = local[0]
    assert np.allclose(x * np.array([0, 0]) + y * np.array([1, 0]) + (1 - x - y) * np.array([1, 1]),
                       [0.75, 0.25], atol=1e-15)
    assert s.find([], [])[0].shape == (0,)


def test_p2_values_at_points_are_ngsolves(graded):
    """spaces.P2PointValues (the Lagrange interpolant of the nodal values) against NGSolve's
    evaluation of a P2 vector field with random coefficients, inside the triangles and on
    their edges."""
    from ngsolve import GridFunction, VectorH1

    from hotroll.fem.mesh import mesh_triangles
    from hotroll.fem.spaces import P2Nodes, P2PointValues

    mesh = graded
    mesh.UnsetDeformation()
    V = VectorH1(mesh, order=2)
    gf = GridFunction(V)
    gf.vec.FV().NumPy()[:] = np.random.default_rng(2).standard_normal(V.ndof)
    pts = np.asarray(mesh.ngmesh.Coordinates())[:, :2]
    tris = mesh_triangles(mesh)
    rng = np.random.default_rng(3)
    lam = rng.dirichlet((1.0, 1.0, 1.0), size=len(tris))
    xy = np.einsum("nk,nkd->nd", lam, pts[tris])
    xy = np.vstack([xy, 0.5 * (pts[tris[:, 1]] + pts[tris[:, 2]])])
    mp = PS.mesh_points(mesh, xy[:, 0], xy[:, 1])
    values = P2PointValues(P2Nodes(mesh, V.ndof // 2), tris, mp["nr"],
                           np.stack([mp["x"], mp["y"]], -1))
    ours = values(gf.vec.FV().NumPy())
    theirs = np.asarray(gf(mp)).reshape(-1, 2)
    assert np.max(np.abs(ours - theirs)) < 1e-12 * np.max(np.abs(theirs))


def test_near_an_edge_ngsolves_triangle_is_kept(graded):
    """Points 1.2e-6 and 3e-6 (barycentric) inside each triangle, next to one of its edges:
    NGSolve's own tolerance gives some of them to the neighbour (1 % at 1.2e-6, measured);
    mesh_points must give NGSolve's triangle for every one (a strain rate jumps there)."""
    from hotroll.fem.mesh import mesh_triangles

    mesh = graded
    mesh.UnsetDeformation()
    pts = np.asarray(mesh.ngmesh.Coordinates())[:, :2]
    tris = mesh_triangles(mesh)
    rng = np.random.default_rng(5)
    for eps in (1.2e-6, 3e-6):
        lam = np.empty((len(tris), 3))
        edge = rng.integers(0, 3, len(tris))
        split = 0.2 + 0.6 * rng.random(len(tris))
        rows = np.arange(len(tris))
        lam[rows, edge] = eps
        lam[rows, (edge + 1) % 3] = (1 - eps) * split
        lam[rows, (edge + 2) % 3] = (1 - eps) * (1 - split)
        xy = np.einsum("nk,nkd->nd", lam, pts[tris])
        theirs = mesh(xy[:, 0], xy[:, 1])["nr"]
        assert np.array_equal(PS.mesh_points(mesh, xy[:, 0], xy[:, 1])["nr"], theirs)
