"""The flow's linear solver where its Jacobian is not symmetric (hotroll/fem/krylov.py): GMRES
preconditioned by the LDL^T factorisation of the lower triangle. Checked against a direct
solver with pivoting (UMFPACK) on the same matrix, a Coulomb pass's, whose multiplier-dependent
friction makes it non-symmetric; and the accuracy test's fallback on a broken state."""
from __future__ import annotations

import numpy as np

from tests.fem.test_primal_dual import _perturbed, _run


def _jacobian_and_rhs():
    run = _run()
    nl = run.form.nonlinear
    _perturbed(run, size=0.05)
    nl.prepare(1)
    nl.a_jacobian.Assemble()
    r = nl.gf.vec.CreateVector()
    r.FV().NumPy()[:] = np.random.default_rng(1).standard_normal(len(r)) * nl.free_mask
    return nl, r


def test_gmres_on_the_ldlt_reaches_the_direct_solution():
    from hotroll.fem.krylov import PreconditionedGMRES, apply_inverse

    nl, r = _jacobian_and_rhs()
    mat, free = nl.a_jacobian.mat, nl.freedofs
    x_direct, x_gmres, x_ldlt = r.CreateVector(), r.CreateVector(), r.CreateVector()
    apply_inverse(mat.Inverse(free, inverse="umfpack"), r, x_direct)
    gm = PreconditionedGMRES(mat, free)
    gm.Update()
    apply_inverse(gm, r, x_gmres)
    apply_inverse(mat.Inverse(free, inverse="sparsecholesky"), r, x_ldlt)
    ref = np.linalg.norm(x_direct.FV().NumPy())
    # the matrix is not symmetric: LDL^T of its lower triangle alone is far off ...
    assert np.linalg.norm(x_ldlt.FV().NumPy() - x_direct.FV().NumPy()) > 1e-3 * ref
    # ... GMRES on it reaches the direct solution, in a few iterations
    assert np.linalg.norm(x_gmres.FV().NumPy() - x_direct.FV().NumPy()) <= 1e-8 * ref
    assert 1 <= gm.iterations <= 30


def test_a_broken_state_fails_the_accuracy_test_instead_of_raising():
    """NaN in the matrix (a neighbour's broken state): GMRES's small least-squares system is
    singular; the solve gives NaN, the accuracy test fails and the next solver is tried (the
    steady solver then falls back to a cold start: test_steady)."""
    from hotroll.fem.krylov import PreconditionedGMRES, apply_inverse

    nl, r = _jacobian_and_rhs()
    gm = PreconditionedGMRES(nl.a_jacobian.mat, nl.freedofs)
    nl.gf.vec.FV().NumPy()[:] = np.nan
    nl.prepare(1)
    nl.a_jacobian.Assemble()
    gm.Update()
    out = r.CreateVector()
    apply_inverse(gm, r, out)
    assert not np.all(np.isfinite(out.FV().NumPy()))


def test_the_factors_alone_where_the_matrix_is_symmetric():
    """A symmetric matrix (a Laplacian): GMRES's first solve takes one iteration, the next
    applies the factors alone (no GMRES iteration) and is as accurate; on the non-symmetric
    Coulomb matrix the factors alone miss, and GMRES then starts from their solution and
    reaches the direct one."""
    from netgen.geom2d import unit_square
    from ngsolve import H1, BilinearForm, Mesh, dx, grad

    from hotroll.fem.krylov import PreconditionedGMRES, apply_inverse

    mesh = Mesh(unit_square.GenerateMesh(maxh=0.1))
    fes = H1(mesh, order=2, dirichlet="left|bottom")
    u, v = fes.TnT()
    a = BilinearForm(fes)
    a += (grad(u) * grad(v) + u * v) * dx
    a.Assemble()
    free = fes.FreeDofs()
    rng = np.random.default_rng(4)
    mask = np.array(list(free), dtype=bool)
    gm = PreconditionedGMRES(a.mat, free)
    exact = a.mat.Inverse(free, inverse="umfpack")
    for i in range(2):
        r = a.mat.CreateColVector()
        r.FV().NumPy()[:] = rng.standard_normal(len(r)) * mask
        x, ref = r.CreateVector(), r.CreateVector()
        apply_inverse(gm, r, x)
        ref.data = exact * r
        assert np.linalg.norm(x.FV().NumPy() - ref.FV().NumPy()) <= 1e-10 * np.linalg.norm(
            ref.FV().NumPy())
        assert gm.iterations == (1 if i == 0 else 0)
        assert gm.direct

    nl, r = _jacobian_and_rhs()
    mat = nl.a_jacobian.mat
    gm = PreconditionedGMRES(mat, nl.freedofs)
    gm.direct = True                          # the hint from a symmetric solve before
    x, ref = r.CreateVector(), r.CreateVector()
    apply_inverse(gm, r, x)
    apply_inverse(mat.Inverse(nl.freedofs, inverse="umfpack"), r, ref)
    scale = np.linalg.norm(ref.FV().NumPy())
    assert np.linalg.norm(x.FV().NumPy() - ref.FV().NumPy()) <= 1e-8 * scale
    assert gm.iterations >= 2 and not gm.direct
