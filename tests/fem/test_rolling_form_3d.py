"""The rolling form on the 3D strip (fem/rolling_form_3d.py, issue 53 stage 1) in its
plane-strain limit: the lateral face held (u_z = 0), the strip's shape, contact, friction
parameter and tensions those of a solved 2D pass (Case R of ../shared/notes/asymmetric-
rolling.md, h = 1 mm, Tresca 0.3, m = 0.05), extruded across the width.

Labels: [identity] the 2D solution, the same in every layer, solves the 3D form (any 3D form
that contains the 2D one in plane strain must give this, to the Newton's tolerance; it is
not an independent reference for the 3D terms that vanish in plane strain); [hand] the slip
vector and the friction's coefficient at a point, computed by hand."""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "solvers"))

HALF_WIDTH = 0.01


@pytest.fixture(scope="module")
def plane_strain():
    import ngsolve as ng
    from test_full_strip import _setup

    from hotroll.fem.extruded_mesh import LayerCopy, extrude, width_axis
    from hotroll.fem.nonlinear import newton
    from hotroll.fem.penalties import PenaltyTable
    from hotroll.fem.rolling_form_3d import RollingForm3D
    from hotroll.model.material import NortonHoff
    from hotroll.solvers.steady import SteadyRun

    case, problem, st = _setup()
    run = SteadyRun(problem, st, case.plate.length)
    assert run.run().status == "steady"
    f2 = run.form
    assert newton(f2.nonlinear, 1e-11, 30).converged      # the 2D pass to round-off
    ref2 = ng.Mesh(run.mesh.ngmesh.Copy())                 # its undeformed reference mesh
    mesh = extrude(ref2, width_axis(HALF_WIDTH, 0.004))
    mat = problem.material
    f3 = RollingForm3D(mesh, problem.rp, NortonHoff(1.0, mat.m, mat.eps0), problem.friction,
                       PenaltyTable(problem.h), tensions=problem.reduced_tensions,
                       edge_held=True)
    copy = LayerCopy(ref2, mesh)
    disp = ng.GridFunction(f3.fes.components[0])
    copy.vector(run.disp, disp)
    mesh.SetDeformation(disp)
    for name in ("a_f", "m", "x_split", "U", "v_reg", "_mu", "_lam"):
        getattr(f3, name).Set(getattr(f2, name).Get())
    # the contact indicator: each arc quadrilateral takes its 2D edge's
    nv = ref2.nv
    flat = {tuple(sorted(v.nr for v in e.vertices)): e.nr for e in ref2.edges}
    chi2, chi3 = f2.chi.vec.FV().NumPy(), f3.chi.vec.FV().NumPy()
    for el in mesh.Elements(ng.BND):
        vs = sorted(v.nr for v in el.vertices)
        low = [v % nv for v in vs if v // nv == vs[0] // nv]
        if len(vs) == 4 and len(low) == 2:
            chi3[f3.chi.space.GetDofNrs(el)[0]] = chi2[flat[tuple(sorted(low))]]
    g2, g3 = f2.nonlinear.gf, f3.nonlinear.gf
    copy.vector(g2.components[0], g3.components[0])
    for c in (1, 2):
        copy.copy(g2.components[c].space, g2.components[c].vec.FV().NumPy(),
                  g3.components[c].space, g3.components[c].vec.FV().NumPy())
    return problem, run, f3, g3.vec.FV().NumPy().copy()


def test_the_extruded_2d_solution_solves_the_3d_form(plane_strain):
    """[identity] one Newton step from the 2D solution in every layer moves it by less than
    1e-8 U (the 2D pass's own Newton moves it by 6e-10 U: both at round-off), and u_z stays 0."""
    from hotroll.fem.nonlinear import newton

    problem, _, f3, start = plane_strain
    g3 = f3.nonlinear.gf
    g3.vec.FV().NumPy()[:] = start
    st = newton(f3.nonlinear, 1e-11, 3)
    U = problem.rp.u_roll
    assert st.converged and st.iterations <= 2
    assert np.abs(g3.vec.FV().NumPy() - start).max() <= 1e-8 * U
    n3 = f3.fes.components[0].ndof // 3
    assert np.abs(g3.components[0].vec.FV().NumPy()[2 * n3:]).max() <= 1e-12 * U


def test_force_per_width_is_the_2d_force(plane_strain):
    """[identity] after the 3D form's own Newton from the 2D solution, the contact
    pressure's vertical resultant over the 3D arc divided by the half width is the 2D arc's
    (per unit width): 1e-8."""
    import ngsolve as ng

    from hotroll.fem.nonlinear import newton
    from hotroll.fem.reproducible import integrate

    problem, run, f3, start = plane_strain
    f3.nonlinear.gf.vec.FV().NumPy()[:] = start
    assert newton(f3.nonlinear, 1e-11, 3).converged
    f2 = run.form
    n2, _ = f2.roll_frame()
    n3, _ = f3.roll_frame()
    u2, u3 = f2.nonlinear.velocity, f3.nonlinear.velocity
    force2 = integrate(f2.pressure(u2) * n2[1], run.mesh, ng.BND,
                       definedon=run.mesh.Boundaries("arc"))
    force3 = integrate(f3.pressure(u3) * n3[1], f3.mesh, ng.BND,
                       definedon=f3.mesh.Boundaries("arc"))
    assert abs(force2) > 0.0
    assert force3 / HALF_WIDTH == pytest.approx(force2, rel=1e-8)


def test_the_slip_is_a_vector_in_the_rolls_tangent_plane(plane_strain):
    """[hand] at a point under the roll, for u = (a, b, c): v_s = (u.t - U) t + c e_z with t
    the tangent of the roll's circle at that angle; the law's coefficient takes |v_s|^2
    (Tresca: factor k / sqrt(|v_s|^2 + v_reg^2), here with k = 1)."""
    import ngsolve as ng

    problem, _, f3, _ = plane_strain
    rp = problem.rp
    theta = 0.5 * rp.bite_angle
    cx, cy = rp.centre
    r = rp.radius + 0.25 * rp.half_exit              # inside the strip, under the roll
    px, py = cx - r * math.sin(theta), cy - r * math.cos(theta)
    mip = f3.mesh(px, py, 0.5 * HALF_WIDTH)
    # where the deformed mesh puts that point: the tangent there, by hand
    X, Y = ng.x(mip), ng.y(mip)
    angle = math.atan2(cx - X, cy - Y)
    t = np.array([math.cos(angle), -math.sin(angle)])       # along U_roll, into the gap
    assert abs(angle - theta) < 0.1 * theta and t[0] > 0.99
    a, b, c = 0.9, -0.05, 0.2
    U = f3.U.Get()
    want = ((a * t[0] + b * t[1] - U) * np.array([t[0], t[1], 0.0]) + np.array([0, 0, c]))
    u = ng.CF((a, b, c))
    assert np.array(f3.slip(u)(mip)) == pytest.approx(want, abs=1e-12)
    s2 = float(np.dot(want, want))
    coef = f3.friction_coefficient(u, k=ng.CF(1.0))(mip)
    assert coef == pytest.approx(problem.friction.factor / math.sqrt(s2 + f3.v_reg.Get() ** 2),
                                 rel=1e-12)
