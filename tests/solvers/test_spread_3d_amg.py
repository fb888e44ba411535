"""GMRES with smoothed-aggregation AMG on the 3D strip's Newton systems (fem/amg.py, issue 53),
on Case R's bar (tests/solvers/test_spread_3d.py).

Labels: [hand] the rigid-body modes of the velocity's layout have no strain rate (a property
of the modes, computed by NGSolve from the coefficient vector, not from the layout's
assumption); [reference] the solution against UMFPACK's of the same matrix; [plumb] where
GMRES cannot reach the tolerance the accuracy test fails and Newton takes the next solver."""
from __future__ import annotations

import numpy as np
import pytest

from hotroll.fem import amg
from hotroll.fem.extruded_mesh import extrude, width_axis
from hotroll.fem.mesh import structured_triangle_mesh


def test_the_layouts_rigid_modes_have_no_strain_rate():
    """[hand] the six modes of ``VelocityLayout`` set as a P2 VectorH1 field on a graded
    prism mesh: int eps(u):eps(u) = 0 (to rounding) and int |u|^2 > 0 for each; the first is
    u = e_x, the fourth u = (y - y_c, -(x - x_c), 0) at a point."""
    from ngsolve import CF, GridFunction, InnerProduct, Integrate, Sym, VectorH1, grad, x, y

    mesh = extrude(structured_triangle_mesh(np.linspace(0.0, 2.0, 5), np.linspace(0.0, 1.0, 3)),
                   width_axis(0.5, 0.1))
    V = VectorH1(mesh, order=2)
    points = np.array([v.point for v in mesh.vertices])
    modes = amg.VelocityLayout(V.ndof, points).rigid_modes()
    g = GridFunction(V)
    for k in range(6):
        g.vec.FV().NumPy()[:] = modes[:, k]
        eps = Sym(grad(g))
        assert Integrate(InnerProduct(eps, eps), mesh) <= 1e-26
        assert Integrate(g * g, mesh) > 0.1
    g.vec.FV().NumPy()[:] = modes[:, 0]
    assert Integrate(InnerProduct(g - CF((1.0, 0.0, 0.0)), g - CF((1.0, 0.0, 0.0))), mesh) < 1e-26
    c = points.mean(axis=0)
    g.vec.FV().NumPy()[:] = modes[:, 3]
    rot = CF((y - c[1], -(x - c[0]), 0.0))
    assert Integrate(InnerProduct(g - rot, g - rot), mesh) < 1e-24


@pytest.fixture(scope="module")
def jacobian():
    """Case R's first 3D Newton system (one width layer, the 2D solution in it)."""
    from test_full_strip import _setup  # the same directory

    from hotroll.fem.nonlinear import _Workspace
    from hotroll.solvers.spread_3d import Spread3D
    from hotroll.solvers.steady import SteadyRun

    case, problem, st = _setup()
    run = SteadyRun(problem, st, case.plate.length)
    assert run.run().status == "steady"
    s3 = Spread3D(run, 0.005, edge=0.005, linear_solver=amg.NAME)
    nl = s3.form.nonlinear
    nl.prepare(1)
    ws = _Workspace(nl)
    nl.a_newton.Apply(nl.gf.vec, ws.r)
    nl.a_jacobian.Assemble()
    return s3, nl, ws


def test_amg_gmres_solves_the_3d_jacobian_as_umfpack(jacobian):
    """[reference] the Newton direction by AMG-GMRES to a relative residual of 1e-10 equals
    UMFPACK's to 1e-7 (weighted norm), in fewer than ``MAX_STEPS`` iterations (measured 69
    at 1e-10); a looser tolerance stops earlier and meets it."""
    s3, nl, ws = jacobian
    mat, free = nl.a_jacobian.mat, nl.freedofs
    ref = ws.r.CreateVector()
    ref.data = mat.Inverse(free, inverse="umfpack") * ws.r
    inv = amg.BlockAMG(mat, free, nl.layout)
    out = ws.r.CreateVector()
    inv.solve(ws.r, out, 1e-10, ws.weights())
    tight = inv.iterations
    assert tight < amg.MAX_STEPS
    diff = out.CreateVector()
    diff.data = out - ref
    assert ws.norm(diff) <= 1e-7 * ws.norm(ref)
    inv.solve(ws.r, out, 1e-3, ws.weights())
    assert inv.iterations < tight
    res = out.CreateVector()
    res.data = mat * out - ws.r
    assert ws.norm(res) <= 1e-3 * ws.norm(ws.r)


def test_a_direction_that_misses_is_refused_and_the_next_solver_taken(jacobian, monkeypatch):
    """[plumb] Newton's accuracy test (``nonlinear._accurate``) accepts AMG-GMRES's direction
    at a forcing term of 1e-4; with the Schur complement's coupling dropped (a planted fault)
    and 30 iterations GMRES stops short of 1e-8 and the test refuses it, so Newton takes the
    next solver (``nonlinear._linear_step``)."""
    from hotroll.fem.nonlinear import _accurate

    s3, nl, ws = jacobian
    rnorm = ws.norm(ws.r)
    inv = amg.BlockAMG(nl.a_jacobian.mat, nl.freedofs, nl.layout)
    assert _accurate(inv, nl.a_jacobian, ws, rnorm, 1e-4)
    monkeypatch.setattr(amg, "MAX_STEPS", 30)
    inv._bt = inv._bt * 0.0
    assert not _accurate(inv, nl.a_jacobian, ws, rnorm, 1e-8)


def test_the_3d_pass_with_amg_is_the_umfpack_pass_at_any_thread_count(monkeypatch):
    """[identity] the pass solved with AMG-GMRES on 1 and 2 threads: the same bits (scipy,
    pyamg, SuperLU and BLAS on one thread); against UMFPACK's pass the same fixed point to the
    couplings' tolerance (spread within surface_tol h, force 1e-5), every Newton direction
    AMG-GMRES's (no fall-back: the kept inverse is still the AMG one; a fall-back keeps the
    direct solver's from then on)."""
    from test_full_strip import _setup  # the same directory

    from hotroll.fem import reproducible
    from hotroll.solvers.spread_3d import Spread3D
    from hotroll.solvers.steady import SteadyRun
    from hotroll.solvers.threads import solver_threads

    monkeypatch.setattr(reproducible, "others_running", lambda: 0)
    case, problem, st = _setup()
    run = SteadyRun(problem, st, case.plate.length)
    assert run.run().status == "steady"
    out = {}
    for solver, n in (("umfpack", 1), (amg.NAME, 1), (amg.NAME, 2)):
        with solver_threads(n):
            s3 = Spread3D(run, 0.005, edge=0.005, linear_solver=solver)
            assert s3.solve()
        f = s3.figures()
        out[solver, n] = (f["spread"], f["roll_force"], f["roll_torque"], f["flux_out"])
        if solver == amg.NAME:     # a fall-back would have kept the direct solver's
            kinds = {type(v).__name__ for v in s3.form.nonlinear.inverses.values()}
            assert kinds == {"BlockAMG"}
    assert out[amg.NAME, 1] == out[amg.NAME, 2]
    a, b = out["umfpack", 1], out[amg.NAME, 1]
    assert abs(b[0] - a[0]) <= run.s.surface_tol * run.problem.h
    assert b[1] == pytest.approx(a[1], rel=1e-5)


def test_amg_needs_the_velocity_layout(jacobian):
    """[plumb] a 2D problem (no layout) asking for the AMG solver is refused by name."""
    _, nl, _ = jacobian
    with pytest.raises(ValueError, match="amg"):
        amg.make_inverse(nl.a_jacobian.mat, nl.freedofs, amg.NAME)
