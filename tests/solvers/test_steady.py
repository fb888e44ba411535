"""The direct steady solver's own machinery on the coarse case of test_rolling (h = 0.02 m).

The kinematic start is an exactly incompressible flow tangent to the strip's top; the solver
reaches m = 0.05 directly, conserving mass and power; a fixed point cut off before it settles is
reported as such; the factorisation is kept and refreshed between Newton solves.
"""
from __future__ import annotations

import numpy as np
import pytest
from test_rolling import _case

from hotroll.fem.nonlinear import newton
from hotroll.solvers.steady import SteadyRun
from hotroll.workflows.runner import build_model, run_case, steady_settings


def _steady_run(**settings) -> SteadyRun:
    case = _case(**{"solver.method": "steady", "friction.a_f": 3.0})
    model, _ = build_model(case)
    s = steady_settings(case)
    for key, value in settings.items():
        setattr(s, key, value)
    return SteadyRun(model, s, case.plate.length)


def test_kinematic_guess_is_incompressible_and_tangent():
    """Away from the kink of the top at the first touching point (where v_y jumps and the P2
    interpolation smears it over the elements there), the guess is divergence-free and tangent
    to the top up to interpolation error; its flux is that at 1 % forward slip."""
    from ngsolve import IfPos, Integrate, div, specialcf, x

    run = _steady_run()
    run._cold_start()
    u, mesh, rp, h = run.form.nonlinear.velocity, run.mesh, run.problem.rp, run.problem.h
    away = IfPos((x - rp.x_touch) ** 2 - (3 * h) ** 2, 1.0, 0.0)
    rms_div = (Integrate(away * div(u) ** 2, mesh, order=6) / Integrate(away, mesh)) ** 0.5
    assert rms_div < 5e-3 * rp.u_roll / rp.half_exit   # measured 2.9e-3 (a sign slip in H': 0.6)
    n = specialcf.normal(2)
    top = mesh.Boundaries("top|arc|exit")
    vn2 = Integrate(away * (u * n) ** 2, mesh, definedon=top, order=6)
    assert (vn2 / Integrate(away, mesh, definedon=top)) ** 0.5 < 1e-3 * rp.u_roll
    q_out = Integrate(u[0], mesh, definedon=mesh.Boundaries("out"))
    assert q_out == pytest.approx(1.01 * rp.u_roll * rp.half_exit, rel=1e-6)


def test_low_rate_sensitivity_converges_directly(tmp_path):
    """m = 0.05 (measured: 39 Newton iterations, no fallback to the continuation in m)."""
    s = run_case(_case(**{"solver.method": "steady", "material.m": 0.05}), tmp_path)
    assert s["converged"] and s["fixed_point_settled"]
    assert s["mass_flux_error"] < 0.01
    assert abs(s["power_balance_error"]) < 0.02
    assert 0.0 < s["forward_slip"] < 0.1 and s["roll_force"] > 0


def test_unsettled_fixed_point_is_reported():
    run = _steady_run(max_outer=1)
    state = run.run()
    assert run.result.stats[-1].converged          # Newton itself converged
    assert not run.result.settled and not run.result.converged
    assert state.status == "unsettled"


def test_factorisation_is_kept_and_refreshed():
    run = _steady_run()
    run.run()
    problem = run.form.nonlinear
    assert id(problem.a_jacobian) in problem.inverses
    kept = problem.inverses[id(problem.a_jacobian)]
    nv = problem.n_velocity_dofs()
    before = problem.gf.vec.FV().NumPy()[:nv].copy()
    st = newton(problem, 1e-5, 5)                    # at the solution: refactorised values
    assert st.converged and st.iterations <= 2
    assert problem.inverses[id(problem.a_jacobian)] is kept
    assert np.max(np.abs(problem.gf.vec.FV().NumPy()[:nv] - before)) < 1e-4 * run.problem.rp.u_roll


def test_sweep_warm_starts_agree_with_cold_solves(tmp_path):
    """A sweep in m, then in roll speed, on the report's 4 m plate: each case starts from the
    nearest solved one on the same mesh, in fewer Newton iterations, and lands on the cold
    solve's answer (both converge their free surface to 1e-3 h). The run is kept (no new mesh,
    no new forms) when only m or, on this isothermal pass with rigid rolls, the roll speed
    changes (a form Parameter since issue 34)."""
    from hotroll.workflows.sweep import Sweep

    plate = {"solver.method": "steady", "plate.length": 4.0}
    sweep, cases = Sweep(), {
        "m020": _case(**plate),
        "m025": _case(**plate, **{"material.m": 0.25}),
        "fast": _case(**plate, **{"material.m": 0.25,
                                  "pass.roll_angular_velocity": 1.25 * np.pi / 3})}
    warm, runs = {}, []
    for name, case in cases.items():
        warm[name] = run_case(case.with_overrides(name=name), tmp_path / f"warm_{name}",
                              sweep=sweep)
        runs.append(sweep._kept[1])
    assert [warm[n]["warm_start_from"] for n in cases] == [None, "m020", "m025"]
    assert runs[1] is runs[0] and runs[2] is runs[1]     # kept for m and for U
    for name in ("m025", "fast"):
        cold, w = run_case(cases[name], tmp_path / f"cold_{name}"), warm[name]
        assert w["converged"] and cold["converged"]
        assert w["nonlinear_iterations"] < cold["nonlinear_iterations"]
        # measured: 6 / 22 and 4 / 31 iterations, force and torque within 5e-5, slip 6e-7
        assert w["roll_torque"] == pytest.approx(cold["roll_torque"], rel=1e-3)
        assert w["roll_force"] == pytest.approx(cold["roll_force"], rel=1e-3)
        assert abs(w["forward_slip"] - cold["forward_slip"]) < 1e-4
        assert w["mass_flux_error"] < 0.01 and abs(w["power_balance_error"]) < 0.02


def test_warm_start_from_another_mesh_is_refused():
    from hotroll.workflows.sweep import Sweep

    coarse = _steady_run()
    coarse.run()
    sweep = Sweep()
    sweep.solved.append(("coarse", {"m": 0.2}, coarse.warm_start()))
    case = _case(**{"solver.method": "steady", "friction.a_f": 3.0, "mesh.h_contact": 0.018})
    model, _ = build_model(case)
    fine = sweep.steady_run(case, model)
    assert sweep.nearest(case, fine) == (None, None)
    with pytest.raises(ValueError, match="another mesh"):
        fine.solve(warm=coarse.warm_start())


def test_failed_warm_start_falls_back_to_a_cold_solve(tmp_path):
    """A warm start that does not converge (here a neighbour's state broken to NaN) is solved
    again from cold, lands on the cold answer and says so in the summary."""
    from dataclasses import replace

    from hotroll.workflows.sweep import Sweep

    case = _case(**{"solver.method": "steady", "friction.a_f": 3.0})
    cold = run_case(case, tmp_path / "cold")
    sweep = Sweep()
    run_case(case.with_overrides(name="first"), tmp_path / "first", sweep=sweep)
    name, params, state = sweep.solved[0]
    broken = replace(state, solution=np.full_like(state.solution, np.nan))
    sweep.solved[0] = (name, params, broken)
    s = run_case(case.with_overrides(name="second"), tmp_path / "second", sweep=sweep)
    assert s["warm_start_from"] == "first" and s["warm_start_failed"]
    assert s["converged"] and not cold["warm_start_failed"]
    for key in ("roll_force", "roll_torque", "forward_slip", "neutral_angle"):
        assert s[key] == pytest.approx(cold[key], rel=1e-4), key


def test_warm_start_never_crosses_free_surface_models():
    """A constrained case does not start from a traced neighbour's (sagged) shape: the sweep
    skips it, and the run refuses it."""
    from hotroll.workflows.sweep import Sweep

    traced = _steady_run()
    traced.run()
    sweep = Sweep()
    sweep.solved.append(("traced", {"m": 0.2}, traced.warm_start()))
    case = _case(**{"solver.method": "steady", "friction.a_f": 3.0,
                    "plate.free_surface": "constrained"})
    model, _ = build_model(case)
    run = sweep.steady_run(case, model)
    assert run.mesh_key == traced.mesh_key                 # same mesh, other model
    assert sweep.nearest(case, run) == (None, None)
    with pytest.raises(ValueError, match="free tops"):
        run.solve(warm=traced.warm_start())


@pytest.mark.parametrize("friction", [{"friction.a_f": 3.0},
                                      {"friction.law": "coulomb", "friction.mu": 0.3}])
def test_a_form_moved_to_another_roll_speed_is_the_form_built_for_it(friction):
    """``RollingForm.set_roll_speed`` (a tandem stand's speed found inside its solve, issue 34):
    the form built at omega and moved to 1.3 omega has the residual and the Jacobian of the
    form built at 1.3 omega, at the same velocity, pressure and contact pressure, to rounding
    (the roll speed, v_reg, the penalties' viscosity scale and the multiplier's scale)."""
    cases = [_case(**{"solver.method": "steady", **friction, "pass.roll_angular_velocity": w})
             for w in (10.0, 13.0)]
    runs = []
    for case in cases:
        model, _ = build_model(case)
        runs.append(SteadyRun(model, steady_settings(case), case.plate.length))
    moved, built = runs
    assert moved.mesh_key == built.mesh_key
    moved.form.set_roll_speed(built.problem.rp, built.problem.friction.v_reg)
    assert moved.form.lam_scale == pytest.approx(built.form.lam_scale, rel=1e-14)
    built._kinematic_guess()
    nl_b, nl_m = built.form.nonlinear, moved.form.nonlinear
    state = nl_b.gf.vec.FV().NumPy()
    rng = np.random.default_rng(1)
    state[nl_b.pressure_range()] = rng.uniform(-1.0, 1.0, len(state[nl_b.pressure_range()]))
    lam = nl_b.multiplier_range()
    state[lam] = built.problem.rp.u_roll * rng.uniform(0.0, 1.0, len(state[lam]))
    nl_m.gf.vec.FV().NumPy()[:] = state
    r_b, r_m = nl_b.gf.vec.CreateVector(), nl_m.gf.vec.CreateVector()
    nl_b.a_newton.Apply(nl_b.gf.vec, r_b)
    nl_m.a_newton.Apply(nl_m.gf.vec, r_m)
    a, b = r_b.FV().NumPy(), r_m.FV().NumPy()
    assert np.linalg.norm(a - b) <= 1e-12 * np.linalg.norm(a)
    nl_b.prepare(1)      # the primal-dual tangent's nu = eps/E at the state (its rank-one
    nl_m.prepare(1)      # term is then in both matrices, not zero)
    assert np.abs(built.form.dual.gf.vec.FV().NumPy()).max() > 0.1
    nl_b.a_jacobian.Assemble()
    nl_m.a_jacobian.Assemble()
    x = rng.uniform(-1.0, 1.0, len(state))
    xb, xm = nl_b.gf.vec.CreateVector(), nl_m.gf.vec.CreateVector()
    xb.FV().NumPy()[:] = x
    xm.FV().NumPy()[:] = x
    jb, jm = (nl_b.a_jacobian.mat * xb).Evaluate(), (nl_m.a_jacobian.mat * xm).Evaluate()
    jb, jm = jb.FV().NumPy(), jm.FV().NumPy()
    assert np.linalg.norm(jb - jm) <= 1e-12 * np.linalg.norm(jb)
