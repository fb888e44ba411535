"""Known-answer checks of the FE core: Taylor-Hood P2/P1 + Norton-Hoff + Picard/Newton.

The problems (hotroll.solvers.verification) use the same spaces, volume form, continuation in
m and solvers as the rolling problem. Measured values (ngsolve 6.2.2608, structured meshes,
eps0 = 1e-6, tol = 1e-10) are quoted next to each assertion.
"""

import math
from functools import lru_cache

import numpy as np
import pytest

from hotroll.solvers.verification import compression, poiseuille


@lru_cache(maxsize=None)
def flow(h, m, method="newton", K=1.0, G=1.0):
    return poiseuille(h, m, K=K, G=G, method=method, max_it=100)


# --- power-law Poiseuille flow -----------------------------------------------------------------
@pytest.mark.parametrize("m, u_tol, p_tol", [
    (0.5, 3e-4, 6e-4),   # measured u 9.0e-5, p 2.1e-4, flux 1.7e-5, 9 Newton iterations
    (0.2, 2e-3, 1e-3),   # measured u 6.0e-4, p 3.2e-4, flux 1.9e-4, 12 Newton iterations
])
def test_poiseuille_newton(m, u_tol, p_tol):
    res = flow(1 / 8, m)
    assert res["converged"] and res["iterations"] <= 20
    assert res["u_error"] < u_tol
    assert res["p_error"] < p_tol
    assert res["flux_error"] < 1e-3


def test_poiseuille_convergence():
    """P2 velocity: L2 rate 3, P1 pressure: rate 2.

    For m = 0.5 the exact profile is H^3 - y^3, a polynomial on the half channel (y >= 0), so
    there is no regularity limit; the eps0 = 1e-6 regularisation only acts where |u'| = y^2 <
    ~1e-6, i.e. y < ~1e-3, and changes the velocity there by < ~1e-9, far below the errors.
    Measured (h = 1/4, 1/8, 1/16): u 7.6e-4, 9.0e-5, 1.1e-5 (rates 3.08, 3.05);
    p 8.4e-4, 2.1e-4, 5.3e-5 (rates 2.02, 1.98); h = 1/32 continues with 3.02 (u).
    """
    res = [flow(1 / n, 0.5) for n in (4, 8, 16)]
    u_rates = [math.log2(a["u_error"] / b["u_error"]) for a, b in zip(res, res[1:])]
    p_rates = [math.log2(a["p_error"] / b["p_error"]) for a, b in zip(res, res[1:])]
    assert min(u_rates) >= 2.8, u_rates
    assert min(p_rates) >= 1.8, p_rates
    assert res[-1]["flux_error"] < 5e-6   # measured 1.2e-6


def test_picard_matches_newton_and_contracts():
    """Picard converges linearly with factor ~ 1 - m (measured 0.50 for m = 0.5, 32 iterations
    to tol 1e-10); it reaches the Newton solution (measured relative difference 6e-11)."""
    from ngsolve import InnerProduct, Integrate

    newton_res = flow(1 / 8, 0.5)
    picard_res = flow(1 / 8, 0.5, method="picard")
    assert picard_res["converged"] and picard_res["iterations"] <= 45
    assert newton_res["iterations"] < picard_res["iterations"]
    upd = np.array(picard_res["updates"])
    ratios = upd[2:] / upd[1:-1]
    assert np.all(ratios < 0.6), ratios           # measured 0.43 ... 0.50
    mesh = newton_res["mesh"]
    d = picard_res["velocity"] - newton_res["velocity"]
    u = newton_res["velocity"]
    rel = math.sqrt(Integrate(InnerProduct(d, d), mesh) / Integrate(InnerProduct(u, u), mesh))
    assert rel < 1e-6
    assert abs(picard_res["u_error"] - newton_res["u_error"]) < 1e-6


# --- frictionless plane-strain compression -----------------------------------------------------
@pytest.mark.parametrize("m", [0.2, 1.0])
@pytest.mark.parametrize("method", ["newton", "picard"])
def test_compression_exact(m, method):
    """The P2 space holds v = r (x, -y): exact to round-off (measured 1e-15 velocity, 3e-13
    force and pressure; the eps0 = 1e-6 regularisation changes the stress by ~1e-13). No
    parameter is 1 (K, r, a, b), so that a product and a quotient differ."""
    res = compression(1 / 4, m, K=3.0, r=0.7, a=1.5, b=0.75, method=method)
    assert res["converged"]
    assert res["u_error"] < 1e-6
    assert res["force_exact"] == pytest.approx(-2.0 * 3.0 * (2 * 0.7) ** m * 1.5)
    assert res["pressure_exact"] == pytest.approx(3.0 * (2 * 0.7) ** m)
    assert abs(res["force"] / res["force_exact"] - 1.0) < 1e-6
    assert abs(res["pressure"] / res["pressure_exact"] - 1.0) < 1e-6
    # the mesh: round(a/h) x round(b/h) = 6 x 3 cells, two triangles each: 28 vertices and
    # 63 edges; P2 velocity (2 x (28 + 63)) and P1 pressure (28): 210 DOFs (counted by hand)
    assert res["dofs"] == 210


def test_compression_with_a_large_regularisation():
    """eps0 as large as the strain rate r: v = r (x, -y) is still the solution (a uniform
    field balances any law), the stress that of the regularised law (2.21): edot^2 = 2/3 eps:eps
    = 4 r^2 / 3, so p = K (2r)^m (1 + 3 eps0^2 / (4 r^2))^((m - 1)/2) = (7/4)^(-0.4) K (2r)^m
    (hand-derived; eps0 -> 0 gives test_compression_exact's K (2r)^m)."""
    r, m = 0.01, 0.2
    res = compression(1 / 4, m, r=r, eps0=r)
    assert res["converged"] and res["u_error"] < 1e-6
    factor = (7 / 4) ** ((m - 1) / 2)
    assert res["pressure"] == pytest.approx(factor * (2 * r) ** m, rel=1e-6)
    assert res["force"] == pytest.approx(-2 * factor * (2 * r) ** m, rel=1e-6)


# --- unit independence -------------------------------------------------------------------------
@pytest.mark.parametrize("m", [0.2, 0.5])
def test_poiseuille_unit_independent(m):
    """The forms keep the physical K: K = G = 1e8 must give the same velocity (measured 1e-15)."""
    ref, big = flow(1 / 8, m), flow(1 / 8, m, K=1e8, G=1e8)
    a, b = ref["velocity"].vec.FV().NumPy(), big["velocity"].vec.FV().NumPy()
    assert np.max(np.abs(a - b)) / np.max(np.abs(a)) < 1e-8
    assert big["iterations"] == ref["iterations"]
    assert big["p_error"] == pytest.approx(ref["p_error"], rel=1e-6)


@pytest.mark.parametrize("m", [0.2, 1.0])
def test_compression_unit_independent(m):
    ref, big = compression(1 / 4, m), compression(1 / 4, m, K=1e8)
    # the defaults are the unit problem (K = r = a = b = 1: p = 2^m, F = -2^(m+1), a 4 x 4
    # mesh of 25 vertices and 56 edges: 2 x 81 + 25 = 187 DOFs)
    assert ref["pressure"] == pytest.approx(2.0 ** m, rel=1e-6)
    assert ref["force"] == pytest.approx(-2.0 ** (m + 1), rel=1e-6)
    assert ref["dofs"] == 187
    assert big["u_error"] < 1e-6
    assert big["force"] / (1e8 * ref["force"]) == pytest.approx(1.0, abs=1e-10)
    assert big["pressure"] / (1e8 * ref["pressure"]) == pytest.approx(1.0, abs=1e-10)


def test_nodal_update_measure_reads_p2_nodes():
    """The stopping test of (3.8c) reads velocities at the P2 nodes: for an interpolated
    quadratic field, vertex and midpoint values equal the field there (the edge DOFs are bubble
    coefficients, 8 times the midpoint deviation, and must not enter the test as velocities)."""
    import ngsolve as ng
    from netgen.geom2d import unit_square

    from hotroll.fem.forms import NonlinearProblem
    from hotroll.fem.spaces import P2Nodes, taylor_hood

    mesh = ng.Mesh(unit_square.GenerateMesh(maxh=0.3))
    fes = taylor_hood(mesh, dirichlety="")
    (u, p), (v, q) = fes.TnT()
    problem = NonlinearProblem(fes, lambda u, p, w, v, q: ng.InnerProduct(u, v) * ng.dx)
    f = (ng.x * ng.x - 0.5 * ng.y, 2 * ng.x * ng.y)
    problem.gf.components[0].Set(ng.CoefficientFunction(f))
    vec = problem.gf.vec.FV().NumPy()
    nodes = P2Nodes(mesh, fes.components[0].ndof // 2)
    vals = nodes.values(vec)
    pts = np.array([v.point for v in mesh.vertices])
    mids = 0.5 * (pts[nodes.ea] + pts[nodes.eb])
    xy = np.concatenate([pts, mids])
    exact = np.array([xy[:, 0] ** 2 - 0.5 * xy[:, 1], 2 * xy[:, 0] * xy[:, 1]])
    assert np.allclose(vals, exact, atol=1e-12)
    assert problem.max_nodal_velocity(problem.gf.vec) == pytest.approx(np.abs(exact).max(),
                                                                        rel=1e-12)
    # a single edge DOF is a bubble coefficient: the measure is NGSolve's value at the midpoint
    problem.gf.vec[:] = 0.0
    problem.gf.vec[mesh.nv] = 1.0
    mid = mids[0]
    at_mid = problem.gf.components[0](mesh(float(mid[0]), float(mid[1])))
    assert problem.max_nodal_velocity(problem.gf.vec) == pytest.approx(abs(at_mid[0]),
                                                                        rel=1e-12)
    assert abs(at_mid[0]) < 0.2


def test_solve_runs_the_method_it_is_given(monkeypatch):
    """``solver.nonlinear`` picks the iteration: "picard" runs Picard's, "newton" Newton's
    (stand-ins record which one ran); anything else is refused naming the field."""
    import hotroll.fem.nonlinear as N

    ran = []
    monkeypatch.setattr(N, "picard", lambda problem, tol, max_it: ran.append(("picard", tol, max_it)))
    monkeypatch.setattr(N, "newton", lambda problem, tol, max_it: ran.append(("newton", tol, max_it)))
    N.solve(None, "picard", 1e-8, 7)
    N.solve(None, "newton", 1e-9, 5)
    assert ran == [("picard", 1e-8, 7), ("newton", 1e-9, 5)]
    with pytest.raises(ValueError, match="solver.nonlinear must be 'newton' or 'picard', got 'x'"):
        N.solve(None, "x", 1e-8, 7)


def test_a_steady_mesh_made_again_is_an_independent_copy_of_the_same_mesh():
    """``build_steady_mesh`` keeps its last meshes (issue 34: a tandem stand's mass-flow
    re-solve meshes the same strip again): the second mesh has the same vertices, elements and
    boundaries, and deforming it leaves the first where it was."""
    import ngsolve

    from hotroll.fem.mesh import MeshSpec, build_steady_mesh
    from hotroll.model.geometry import RollPass

    rp = RollPass(0.3, 0.004, 0.0032, omega=10.0, axis_x=0.0)
    spec = MeshSpec(h=0.0004, fine_length=0.0, core_factor=4.0)
    a = build_steady_mesh(rp, 0.02, 0.02, spec, margin=0.004)
    b = build_steady_mesh(rp, 0.02, 0.02, spec, margin=0.004)
    pa = np.array([v.point for v in a.vertices])
    pb = np.array([v.point for v in b.vertices])
    assert np.array_equal(pa, pb) and a.ne == b.ne
    assert sorted(a.GetBoundaries()) == sorted(b.GetBoundaries())
    assert a.ngmesh is not b.ngmesh
    disp = ngsolve.GridFunction(ngsolve.VectorH1(b, order=1))
    disp.vec[:] = 1e-3
    b.SetDeformation(disp)
    b.ngmesh.Coordinates()[:, 0] += 1.0          # a change to the copy's own points
    assert np.array_equal(np.array([v.point for v in a.vertices]), pa)
    faster = build_steady_mesh(RollPass(0.3, 0.004, 0.0032, omega=20.0, axis_x=0.0), 0.02,
                               0.02, spec, margin=0.004)      # the roll speed is not geometry
    assert np.array_equal(np.array([v.point for v in faster.vertices]), pa)


@pytest.mark.parametrize("multiplier", [False, True])
def test_the_residual_norm_weighs_the_pressure_rows_alone(multiplier):
    """``pressure_range`` is the pressure's block of DOFs: after the velocity's, before a
    contact multiplier's (NGSolve's product space numbers its factors in turn). The residual's
    norm (``nonlinear._Workspace.norm``) weighs those rows alone by ``pressure_row_scale``:
    with 1 on every velocity row, 2 on every pressure row, 5 on every multiplier row and a
    weight of 3 it is sqrt(n_u + (3 x 2)^2 n_p + 5^2 n_l) (by hand; every DOF free here)."""
    import ngsolve as ng
    from netgen.geom2d import unit_square

    from hotroll.fem.forms import NonlinearProblem
    from hotroll.fem.nonlinear import _Workspace
    from hotroll.fem.spaces import taylor_hood

    mesh = ng.Mesh(unit_square.GenerateMesh(maxh=0.4))
    fes = taylor_hood(mesh, dirichlety="", multiplier_on="top" if multiplier else None)

    def integrand(u, p, w, v, q, *lam_xi):
        form = ng.InnerProduct(u, v) * ng.dx + p * q * ng.dx
        if lam_xi:
            lam, xi = lam_xi
            form += lam * xi * ng.ds("top")
        return form

    problem = NonlinearProblem(fes, integrand, pressure_row_scale=3.0)
    n_u, n_p = fes.components[0].ndof, fes.components[1].ndof
    n_l = fes.ndof - n_u - n_p
    assert (n_l > 0) == multiplier and n_u == 2 * (mesh.nv + mesh.nedge) and n_p == mesh.nv
    pr = problem.pressure_range()
    assert (pr.start, pr.stop) == (n_u, n_u + n_p)
    assert problem.free_mask.all()
    ws = _Workspace(problem)
    a = ws.r.FV().NumPy()
    a[:n_u], a[n_u:n_u + n_p], a[n_u + n_p:] = 1.0, 2.0, 5.0
    assert ws.norm(ws.r) == pytest.approx(math.sqrt(n_u + 36.0 * n_p + 25.0 * n_l), rel=1e-14)
