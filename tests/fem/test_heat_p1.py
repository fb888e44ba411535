"""fem/heat_p1.py's steady volume terms in numpy against NGSolve's assembly of the same form,
on a solved thermal pass (its strip, flow, tau and temperature): the residual and the Jacobian
to rounding; and the operator solves the pass to the same temperatures."""
from __future__ import annotations

import numpy as np
import pytest
from casebuild import solved_steady_run


@pytest.fixture(scope="module")
def solved():
    run = solved_steady_run("thermal_pass")
    assert run.thermal.props.is_constant()          # the numpy volume's case
    return run


def _both(field, sources):
    """(numpy operator, NGSolve's full form) of the field's sources."""
    from hotroll.fem.heat_p1 import SteadyP1Operator

    a_np, _ = field._forms(*sources)
    hook, field.element_flow = field.element_flow, None
    try:
        a_ng, _ = field._forms(*sources)
    finally:
        field.element_flow = hook
    assert isinstance(a_np, SteadyP1Operator) and not isinstance(a_ng, SteadyP1Operator)
    return a_np, a_ng


def test_residual_and_jacobian_are_ngsolves(solved):
    th = solved.thermal
    f = th.field
    a_np, a_ng = _both(f, th.strip_sources())
    f._refresh(tau=True)
    # at the solved temperature and at a perturbed one (the Jacobian's linear part and the
    # boundary's radiation both move)
    base = f.values.copy()
    for scale in (0.0, 30.0):
        f.values[:] = base + scale * np.sin(np.arange(len(base)))
        r_np, r_ng = f.gf.vec.CreateVector(), f.gf.vec.CreateVector()
        a_np.Apply(f.gf.vec, r_np)
        a_ng.Apply(f.gf.vec, r_ng)
        x_np, x_ng = r_np.FV().NumPy(), r_ng.FV().NumPy()
        # the residual's terms are W/m of size rho c U dT h; they cancel to the residual
        assert np.max(np.abs(x_np - x_ng)) < 1e-11 * np.max(np.abs(x_ng)) + 1e-9
        a_np.AssembleLinearization(f.gf.vec)
        a_ng.AssembleLinearization(f.gf.vec)
        v_np = np.asarray(a_np.mat.CSR()[0])
        v_ng = np.asarray(a_ng.mat.CSR()[0])
        assert a_np.mat.nze == a_ng.mat.nze
        assert np.max(np.abs(v_np - v_ng)) < 1e-13 * np.max(np.abs(v_ng))
    f.values[:] = base


def test_the_same_steady_temperature(solved):
    """A full steady heat solve from the entry temperature with the numpy volume terms and
    with NGSolve's: the same field to the solve's tolerance."""
    th = solved.thermal
    f = th.field
    src = th.strip_sources()
    out = []
    for hook in (f.element_flow, None):
        saved, f.element_flow = f.element_flow, hook
        f._steady, f._system = None, None           # the forms built afresh
        try:
            f.gf.Set(f.bc.entry_temperature)
            info = f.solve_steady(*src, tol=1e-12, max_iter=30)
        finally:
            f.element_flow = saved
        assert info.change <= 1e-12
        out.append(f.values.copy())
    f._steady, f._system = None, None
    assert np.max(np.abs(out[0] - out[1])) < 1e-9 * np.max(out[1])


def test_another_velocity_takes_ngsolves_forms(solved):
    """The numpy volume terms describe the strip's own velocity: a solve given another
    velocity object (twice the strip's) is assembled by NGSolve, not by them (from the
    session's review: they had ignored the argument)."""
    from hotroll.fem.heat_p1 import SteadyP1Operator

    th = solved.thermal
    v, q, qf, chi = th.strip_sources()
    a, _ = th.field._forms(2.0 * v, q, qf, chi)
    assert not isinstance(a, SteadyP1Operator)
    a, _ = th.field._forms(v, q, qf, chi)
    assert isinstance(a, SteadyP1Operator)
