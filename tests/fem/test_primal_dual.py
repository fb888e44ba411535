"""The primal-dual Newton tangents of the Norton-Hoff law and of the friction laws
(fem/primal_dual.py, docs/theory.md 3.2b).

Independent checks: the residual on the dual's quadrature points is NGSolve's default one; with
nu = eps/E (and the friction's z = s/S) the tangent is Newton's (the assembled matrices agree,
here and in test_rolling's exact-Jacobian test for every friction law); each dual's update is
the first-order Taylor expansion of its primal value, so its error falls as the step squared
(a convergence rate); the coupled solve with them reaches the primal Newton's solution
(tightened tolerances: the same fixed point to 1e-6 asked, 3e-9 measured) in fewer iterations.
"""
from __future__ import annotations

import numpy as np
import pytest

from tests.solvers.test_rolling import _case


def _run(**overrides):
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.runner import build_model, steady_settings

    case = _case(**{"solver.method": "steady", "friction.law": "coulomb", "friction.mu": 0.3,
                    **overrides})
    model, _ = build_model(case)
    run = SteadyRun(model, steady_settings(case), case.plate.length)
    run._cold_start()
    return run


def _perturbed(run, seed=3, size=0.3):
    rng = np.random.default_rng(seed)
    vec = run.form.nonlinear.gf.vec.FV().NumPy()
    vec[:] *= 1.0 + size * rng.standard_normal(vec.size)
    return rng


def _primal_twin(run):
    """The run's form built again with the primal tangent, at the run's state (velocity,
    pressure, contact edges, a_f, the inlet/outlet split)."""
    from hotroll.fem.rolling_form import RollingForm

    f = run.form
    twin = RollingForm(run.mesh, f.rp, f.material, run.problem.friction, f.penalties,
                       free_surface=f.free_surface, consistency=f.consistency,
                       contact=f.contact, contact_regions="arc", primal_dual=False)
    twin.nonlinear.gf.vec.data = f.nonlinear.gf.vec
    twin.chi.vec.data = f.chi.vec
    twin.a_f.Set(f.a_f.Get())
    twin.x_split.Set(f.x_split.Get())
    return twin


def _dual_dx(form):
    """The volume measure on the dual's quadrature points."""
    from ngsolve import dx

    return dx(intrules=form.dual.intrules)


def test_the_residual_on_the_duals_points_is_ngsolves_default():
    """The volume terms integrated on the dual's points (``ORDER``) give the residual NGSolve
    integrates by default for these P2-P1 forms: the solutions are unchanged by the rule."""
    from ngsolve import BilinearForm, dx

    from hotroll.fem.forms import norton_hoff_volume

    run = _run()
    f = run.form
    _perturbed(run)
    (u, p, *lam), (v, q, *xi) = f.fes.TnT()
    vol = norton_hoff_volume(f.material, f.m_material, u, p, u, v, q, K=f.consistency)
    out = []
    for measure in (dx, dx(intrules=f.dual.intrules)):
        a = BilinearForm(f.fes)
        a += vol * measure
        r = f.nonlinear.gf.vec.CreateVector()
        a.Apply(f.nonlinear.gf.vec, r)
        out.append(r.FV().NumPy().copy())
    assert np.linalg.norm(out[1] - out[0]) <= 1e-13 * np.linalg.norm(out[0])


def test_with_nu_at_eps_over_e_the_tangent_is_newtons():
    """nu = eps/E at the iterate (``prepare(1)``): the primal-dual Jacobian equals the primal
    one (``primal_dual=False``) on the same state."""

    run = _run()
    f = run.form
    _perturbed(run)
    primal = _primal_twin(run)
    assert f.nonlinear.prepare(1) is False           # the residual is not touched
    mats = []
    for form in (f, primal):
        form.nonlinear.a_jacobian.Assemble()
        x = form.nonlinear.gf.vec.CreateVector()
        x.FV().NumPy()[:] = np.random.default_rng(5).standard_normal(x.size)
        mats.append((form.nonlinear.a_jacobian.mat * x).Evaluate().FV().NumPy().copy())
    assert np.linalg.norm(mats[0] - mats[1]) <= 1e-10 * np.linalg.norm(mats[1])
    assert not hasattr(primal.nonlinear, "prepare")


def test_with_another_nu_the_tangent_is_the_documented_one_and_symmetric():
    """nu and the friction's z after a step (not eps/E, s/S): the primal-dual Jacobian minus
    the primal one is the documented difference mu (m-1)(2/3) [((eps:d)(nu:v) + (nu:d)(eps:v))
    / 2E - (eps:d)(eps:v) / E^2] plus the friction's chi s 2 k_f' (S z - s) (d.t)(v.t) (written
    out here on their own, k_f' = dk_f/d(s^2) the law's), and that change is symmetric (the
    LDL^T factorisation of the flow's matrix relies on it)."""
    from ngsolve import BilinearForm, InnerProduct, sqrt

    from hotroll.fem.forms import strain_rate
    from hotroll.model.material import edot_squared

    run = _run()
    f = run.form
    rng = _perturbed(run)
    nl = f.nonlinear
    nl.prepare(1)
    nv = nl.n_velocity_dofs()
    nl.gf.vec.FV().NumPy()[:nv] *= 1.0 + 0.2 * rng.standard_normal(nv)
    nl.prepare(2)                                   # nu now lags eps/E by a step
    primal = _primal_twin(run)
    (u, _, *_), (v, _, *_) = f.fes.TnT()
    w = nl.velocity
    ew, eu, ev, nu = strain_rate(w), strain_rate(u), strain_rate(v), f.dual.cf
    E2 = f.material.eps0**2 + edot_squared(ew)
    mu = f.material.viscosity(edot_squared(ew), m=f.m_material, K=f.consistency)
    diff = BilinearForm(f.fes)
    diff += (mu * (f.m_material - 1.0) * (2.0 / 3.0)
             * (0.5 * (InnerProduct(ew, eu) * InnerProduct(nu, ev)
                       + InnerProduct(nu, eu) * InnerProduct(ew, ev)) / sqrt(E2)
                - InnerProduct(ew, eu) * InnerProduct(ew, ev) / E2)) * _dual_dx(f)
    _, t = f.roll_frame()
    slip = f.slip(w)
    kw = f.friction_arguments(w, lam=nl.gf.components[2] if f.exact else None)
    d_s2 = f.friction.coefficient_partials(slip * slip, **kw)[0]
    S = sqrt(slip * slip + f.v_reg * f.v_reg)
    friction = BilinearForm(f.fes)
    friction += (f.chi * slip * 2.0 * d_s2 * (S * f.friction_dual.z(slip, f.v_reg) - slip)
                 * (u * t) * (v * t)) * f.friction_measure()
    diff += (f.chi * slip * 2.0 * d_s2 * (S * f.friction_dual.z(slip, f.v_reg) - slip)
             * (u * t) * (v * t)) * f.friction_measure()
    friction.Assemble()
    out = []
    for a in (nl.a_jacobian, primal.nonlinear.a_jacobian, diff):
        a.Assemble()
    x, y = nl.gf.vec.CreateVector(), nl.gf.vec.CreateVector()
    x.FV().NumPy()[:] = rng.standard_normal(x.size)
    y.FV().NumPy()[:] = rng.standard_normal(y.size)
    for a in (nl.a_jacobian, primal.nonlinear.a_jacobian, diff):
        out.append((a.mat * x).Evaluate().FV().NumPy().copy())
    assert np.linalg.norm(out[2]) > 1e-3 * np.linalg.norm(out[0])   # nu is not eps/E
    # ... nor z s/S: the friction's part of the difference is there too
    assert np.linalg.norm((friction.mat * x).Evaluate().FV().NumPy()) > 1e-6 * np.linalg.norm(
        out[0])
    assert np.linalg.norm(out[0] - out[1] - out[2]) <= 1e-10 * np.linalg.norm(out[0])
    # the code's change of the tangent, J_pd - J_primal, is symmetric (the Coulomb and
    # boundary terms the two share are not, and cancel)
    xd = out[0] - out[1]
    yd = ((nl.a_jacobian.mat * y).Evaluate().FV().NumPy()
          - (primal.nonlinear.a_jacobian.mat * y).Evaluate().FV().NumPy())
    xv, yv = x.FV().NumPy(), y.FV().NumPy()
    assert np.dot(yv, xd) == pytest.approx(np.dot(xv, yd), rel=1e-9)


def _state_and_step(run):
    """(form, iterate, its vector u0, a random velocity step du) at a perturbed state."""
    f = run.form
    rng = _perturbed(run, size=0.05)
    gf = f.nonlinear.gf
    u0 = gf.vec.FV().NumPy().copy()
    du = np.zeros_like(u0)
    nv = f.nonlinear.n_velocity_dofs()
    du[:nv] = rng.standard_normal(nv) * np.abs(u0[:nv]).max()
    return f, gf, u0, du


def test_the_duals_update_is_second_order_accurate():
    """After a step t du from u0 with nu = eps0/E0, nu+ is the linearisation of eps/E about
    eps0: its distance from eps(u0 + t du)/E falls as t^2 (ratio 4 per halving), where a wrong
    term (its second term x 1.1) leaves it first order."""
    from hotroll.fem.primal_dual import NortonHoffDual

    run = _run()
    f, gf, u0, du = _state_and_step(run)
    exact = NortonHoffDual(run.mesh, f.material.eps0)
    exact.attach(f.nonlinear.velocity)
    errors = []
    for t in (4e-6, 2e-6, 1e-6):
        gf.vec.FV().NumPy()[:] = u0
        f.nonlinear.prepare(1)
        gf.vec.FV().NumPy()[:] = u0 + t * du
        f.nonlinear.prepare(2)
        exact.prepare(1)
        errors.append(np.abs(f.dual.gf.vec.FV().NumPy() - exact.gf.vec.FV().NumPy()).max())
    rates = [errors[i] / errors[i + 1] for i in range(2)]
    assert errors[0] > 0.0
    assert rates == pytest.approx([4.0, 4.0], rel=0.1)


def _solved(run) -> tuple[dict, int, bool]:
    """(figures, Newton iterations, converged) of the run's solve."""
    run.record = False
    res = run.solve()
    return run.measure(res.stats[-1], 0), res.iterations, res.converged


def _same_solution_in_fewer_iterations(out: dict) -> None:
    """out[True] (with the dual) and out[False]: both converged, force, torque and slip equal
    to 1e-6, fewer iterations with the dual."""
    (a, ia, ca), (b, ib, cb) = out[True], out[False]
    assert ca and cb
    for key in ("roll_force", "roll_torque", "forward_slip"):
        assert a[key] == pytest.approx(b[key], rel=1e-6), key
    assert ia < ib, (ia, ib)


def test_the_primal_dual_solve_reaches_the_primal_solution_in_fewer_iterations(monkeypatch):
    """The coupled steady solve of test_rolling's coarse case with Coulomb friction, with the
    primal-dual and with the primal tangent, Newton's, a_f's and the free tops' tolerances
    1000 times tighter: the same force, torque and forward slip (measured 1.5e-9-3e-9 apart:
    the residual, and so the fixed point, is the same) and fewer Newton iterations with the
    dual (a guard: measured 18 against 23)."""
    from functools import partial

    import hotroll.solvers.steady as S
    from hotroll.fem.rolling_form import RollingForm

    out = {}
    for dual in (True, False):
        monkeypatch.setattr(S, "RollingForm", partial(RollingForm, primal_dual=dual))
        run = _run()
        for key in ("tol", "a_f_rtol", "surface_tol"):        # every tolerance / 1000
            setattr(run.s, key, getattr(run.s, key) / 1000.0)
        run.s.max_outer *= 3
        out[dual] = _solved(run)
    _same_solution_in_fewer_iterations(out)


def test_the_friction_duals_update_is_second_order_accurate():
    """After a step t du from u0 with z = s0/S0 (d = 0), the stored departure d = z+ - s/S of
    the friction's dual from the primal value is the linearisation's error: it falls as t^2
    (ratio 4 per halving), where a wrong update (its second term x 1.1) leaves it first order.
    Coulomb friction: q = 0, the steepest of the laws at the neutral point."""
    run = _run()
    f, gf, u0, du = _state_and_step(run)
    errors = []
    for t in (4e-6, 2e-6, 1e-6):
        gf.vec.FV().NumPy()[:] = u0
        f.nonlinear.prepare(1)
        assert not np.any(f.friction_dual.d.vec.FV().NumPy())       # d = 0: z = s/S
        gf.vec.FV().NumPy()[:] = u0 + t * du
        f.nonlinear.prepare(2)
        errors.append(np.abs(f.friction_dual.d.vec.FV().NumPy()).max())
    rates = [errors[i] / errors[i + 1] for i in range(2)]
    assert errors[0] > 0.0
    assert rates == pytest.approx([4.0, 4.0], rel=0.1)


def test_the_friction_dual_reaches_the_same_solution_in_fewer_iterations(monkeypatch):
    """Viscoplastic friction (q = m = 0.2, a_f fixed) on the flat-topped strip from the slab
    guess: with the friction's dual and with it held at the primal value (d = 0 at every
    iterate: Newton's friction tangent), Newton's tolerance 1000 times tighter: the same force,
    torque and forward slip (asked 1e-6) and fewer iterations with the dual (a guard: on
    Example 1 with a_f = 14.5, 10 against 18; here 10 against 17)."""
    from hotroll.fem.primal_dual import FrictionDual

    out = {}
    keep = FrictionDual.prepare
    for dual in (True, False):
        if not dual:
            def primal(self, iteration):
                keep(self, 1)
                return False
            monkeypatch.setattr(FrictionDual, "prepare", primal)
        run = _run(**{"friction.law": "viscoplastic", "friction.mu": None, "friction.a_f": 3.0,
                      "plate.free_surface": "constrained"})
        run.s.tol /= 1000.0
        out[dual] = _solved(run)
    _same_solution_in_fewer_iterations(out)
