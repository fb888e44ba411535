"""The unilateral contact's active set (hotroll/fem/contact_set.py) on a solved run whose strip
leaves the roll before the gap (Example 1, coarse: h/l_c about 1.8): its normal velocity against
an independent assembly of its definition, and the friction's support against the set."""
from __future__ import annotations

import numpy as np
import pytest
from casebuild import example1_coarse, shared_scope
from test_contact import with_

from hotroll.config.case import case_from_dict
from hotroll.solvers.steady import SteadyRun
from hotroll.workflows.runner import build_model, steady_settings


@pytest.fixture(scope=shared_scope)
def unilateral() -> SteadyRun:
    case = case_from_dict(with_(example1_coarse("unilateral"), **{"contact.unilateral": True}))
    model, _ = build_model(case)
    run = SteadyRun(model, steady_settings(case), case.plate.length)
    run.run()
    return run


def test_the_normal_velocity_is_its_definition(unilateral):
    """g_j / m_j with g_j = int phi_j u.n ds and m_j = int phi_j ds over the arc (the
    multiplier's P1 hat functions, the roll's normal), assembled here from the converged
    velocity, equals what the active set reads from the residual's constraint rows (1e-9)."""
    from ngsolve import LinearForm, ds

    form, active = unilateral.form, unilateral.active
    L = form.fes.components[2]
    xi = L.TestFunction()
    n, _ = form.roll_frame()
    g = LinearForm(L)
    g += xi * (form.nonlinear.velocity * n) * ds("arc", bonus_intorder=2)
    g.Assemble()
    m = LinearForm(L)
    m += xi * ds("arc")
    m.Assemble()
    _, local = form.multiplier_vertices()
    expected = g.vec.FV().NumPy()[local] / m.vec.FV().NumPy()[local]
    scale = form.rp.u_roll
    assert np.allclose(active.normal_velocity(), expected, rtol=0, atol=1e-9 * scale)
    # the strip leaves the roll: the released nodes move away from it (u.n < 0)
    assert (~active.active).any() and active.active.any()
    assert np.all(expected[~active.active] < 0.0)
    # linear in the velocity: at half the solution, half the normal velocity (read afresh)
    vec = form.nonlinear.gf.vec
    saved = vec.FV().NumPy().copy()
    try:
        vec.FV().NumPy()[:] *= 0.5
        assert np.allclose(active.normal_velocity(), 0.5 * expected, rtol=0, atol=1e-9 * scale)
    finally:
        vec.FV().NumPy()[:] = saved


def test_an_update_says_whether_the_set_changed(unilateral):
    """From all nodes active (``reset``) at the converged solution, one update releases the
    nodes the strip has left (multiplier 0, moving off the roll) and says so; the next update
    changes nothing and says so."""
    active = unilateral.active
    converged = active.active.copy()
    active.reset()
    assert active.active.all()
    assert active.update() is True
    assert np.array_equal(active.active, converged)
    assert active.update() is False


def test_friction_acts_on_the_active_contact_only(unilateral):
    """The friction indicator is 1 on the arc's edges whose two vertices are active and 0 on
    every other top edge: the released stretch is a free surface (no friction)."""
    run = unilateral
    on = np.zeros(run.mesh.nv, dtype=bool)
    on[run.active.active_vertices()] = True
    expected = run.arc & on[run.top.ea] & on[run.top.eb]
    chi = run.form.chi.vec.FV().NumPy()[run.top.edge]
    assert np.array_equal(chi == 1.0, expected)
    assert (run.arc & ~expected).any()


def test_the_steady_solution_has_no_time_and_records_its_solves(unilateral):
    """The steady solver's Solution: no time (NaN, not the report's scheme's seconds), one
    history row per solve with its Newton iterations and final residual (below the solver's
    tolerance for the last, converged one)."""
    import math

    state, stats = unilateral.state, unilateral.last_stats
    assert math.isnan(state.time) and state.step == len(state.history) - 1
    last = state.history[-1]
    assert math.isnan(last["time"])
    assert last["iterations"] == stats.iterations and last["residual"] == stats.residual
    assert last["solver_converged"] and last["residual"] <= unilateral.s.tol
