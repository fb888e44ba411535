"""The primal Newton tangent (``fem/forms.py: norton_hoff_tangent``, RollingForm(primal_dual=
False)) takes the form's consistency ratio K(eps, T)/K_ref as the primal-dual one does: on the
state of tests/fem/test_primal_dual.py, both forms built with a ratio of 2 (a material twice
as hard as the reference) and nu = eps/E, the assembled Jacobians agree (the identity that
test checks for a ratio of 1, where the material's own K would pass too)."""
from __future__ import annotations

import numpy as np

from tests.fem.test_primal_dual import _perturbed, _run


def _form(run, primal_dual: bool):
    from hotroll.fem.rolling_form import RollingForm

    f = run.form
    g = RollingForm(run.mesh, f.rp, f.material, run.problem.friction, f.penalties,
                    free_surface=f.free_surface, consistency=2.0, contact=f.contact,
                    contact_regions="arc", primal_dual=primal_dual)
    g.nonlinear.gf.vec.data = f.nonlinear.gf.vec
    g.chi.vec.data = f.chi.vec
    g.a_f.Set(f.a_f.Get())
    g.x_split.Set(f.x_split.Get())
    return g


def test_with_a_consistency_of_2_the_primal_tangent_is_the_primal_dual_one():
    run = _run()
    _perturbed(run)
    dual, primal = _form(run, True), _form(run, False)
    dual.nonlinear.prepare(1)
    out = []
    for form in (dual, primal):
        form.nonlinear.a_jacobian.Assemble()
        x = form.nonlinear.gf.vec.CreateVector()
        x.FV().NumPy()[:] = np.random.default_rng(5).standard_normal(x.size)
        out.append((form.nonlinear.a_jacobian.mat * x).Evaluate().FV().NumPy().copy())
    assert np.linalg.norm(out[0] - out[1]) <= 1e-10 * np.linalg.norm(out[1])
