"""The steady solver's estimate of a_f (3.15) counts the plate beyond its mesh
(SteadyRun._estimate_a_f): (3.15) is linear in int |v|^p dx, and the plate's rest is a rigid
block of the half entry thickness moving at the inlet's speed, so each metre of it adds
h0/2 |v_in|^p to the integral. On test_rolling's pass (viscoplastic, a_f estimated; cold
start) with 1 and 2 m of plate beyond the mesh: a_2 / a_1 = (V + 2 c) / (V + c), c = h0/2
|v_in|^p, V the mesh's own integral (integrated here)."""
from __future__ import annotations

import pytest

from hotroll.fem import quantities as Q
from tests.fem.test_primal_dual import _run


def test_the_plate_beyond_the_mesh_adds_the_entry_blocks_integral():
    from ngsolve import InnerProduct, Integrate

    run = _run(**{"friction.law": "viscoplastic", "friction.mu": None, "friction.a_f": None})
    rp, form = run.problem.rp, run.form
    p = form.m.Get() + 1.0
    u = form.nonlinear.velocity
    V = Integrate((InnerProduct(u, u) + 1e-300) ** (p / 2), run.mesh)
    c = rp.half_entry * abs(Q.face_flow(form, "in")["velocity"]) ** p
    a = []
    for rest in (1.0, 2.0):
        run.plate_length = run.upstream + rp.contact_length + rest
        a.append(run._estimate_a_f())
    assert a[1] < 1e6                                  # not the cap
    assert a[1] / a[0] == pytest.approx((V + 2.0 * c) / (V + c), rel=1e-9)
