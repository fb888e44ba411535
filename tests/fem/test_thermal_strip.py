"""The temperature's strip mesh (hotroll/fem/strip_mesh.py, issue 16) against known answers:
the Graetz series on the strip mesh itself with its convergence rate under refinement, the
stream-function velocity's flux and tangency, and the grading rules by hand. Steel-like data
as in test_thermal.py."""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest
from test_thermal import ALPHA, K, graetz_theta

from hotroll.fem.strip_mesh import FIRST_CELL, ThermalStrip, graded_axis, layer_thickness, top_rows
from hotroll.fem.thermal_field import TemperatureField
from hotroll.model.thermal_properties import ThermalBoundary, ThermalProperties

ngsolve = pytest.importorskip("ngsolve")
pytestmark = pytest.mark.mutation

STEEL = ThermalProperties(7800.0, 650.0, K)


def flat_pass(H: float, L: float, U: float, lc: float):
    """The geometry a ThermalStrip reads from a pass, for a flat channel of half-height H from
    x = 0 to L: the 'contact' from 0.2 L over lc, the 'gap' at 0.2 L + lc."""
    return SimpleNamespace(contact_length=lc, half_exit=H, half_entry=H, x_touch=0.2 * L,
                           axis_x=0.2 * L + lc, u_roll=U)


def plug_strip(H, L, U, lc, refine, h=None):
    rp = flat_pass(H, L, U, lc)
    top = np.array([[0.0, H], [L, H]])
    strip = ThermalStrip(rp, top, h or H / 3.0, layer_thickness(rp, ALPHA), refine)
    strip.place(strip.reference)
    y = strip.reference[:, 1]
    strip.set_stream_function((U * y).reshape(strip.shape), total=U * H)
    return strip


def test_graetz_series_on_the_strip_mesh():
    """Plug flow U through the strip mesh of a flat channel (rows graded to the top from
    delta / 8, delta = sqrt(alpha l_c / U); columns l_c / 40 in the fine zone, growing
    outside), velocity curl psi of psi = U y, cooled through h = Bi k / H from where the roll
    would touch: the Graetz series with axial conduction (test_thermal.graetz_theta) from
    there, over the strip's fine columns. Rolling-like, U H / alpha = 2000, Bi = 5. Measured
    max |theta error| 1.15e-3, 6.0e-4, 2.9e-4 (1.3e-4 at 8) at refinements 1, 2, 4: first
    order, rate 0.99 (SUPG's
    O(h) streamline diffusion; test_thermal.py's graded rectangle measures 1.8 with finer
    columns)."""
    from ngsolve import IfPos, x

    H, T0, Tr, bi = 0.01, 1300.0, 300.0, 5.0
    U, L = 2000.0 * ALPHA / H, 12.0 * H
    bc = ThermalBoundary(T0, Tr, 300.0, bi * K / H, 0.0, 0.0)
    x0 = flat_pass(H, L, U, 4.0 * H).x_touch           # the cooling starts where a roll would
    cooled = IfPos(x - x0, 1.0, 0.0)
    xs, ys = np.meshgrid(np.linspace(x0 + 0.05 * L, 0.6 * L, 15), np.linspace(0.0, H, 9))
    # (upstream the top is insulated: T0 there up to the axial conduction's alpha / U = H/2000)
    exact = graetz_theta(xs.ravel() - x0, ys.ravel(), H, U, bi)
    assert exact.min() < 0.8          # a real cooling over the strip's fine columns
    errors = []
    for refine in (1.0, 2.0, 4.0):
        strip = plug_strip(H, L, U, 4.0 * H, refine)
        field = TemperatureField(strip.mesh, STEEL, bc, inlet="left", top="top",
                                 outlet="right")
        info = field.solve_steady(strip.velocity(), 0.0, 0.0, cooled)
        assert info.change < 1e-10
        pts = strip.mesh(xs.ravel(), ys.ravel() / H)       # logical (x, eta = y / H)
        theta = (np.asarray(field.gf(pts)).ravel() - Tr) / (T0 - Tr)
        errors.append(float(np.max(np.abs(theta - exact))))
    rate = math.log2(errors[0] / errors[2]) / 2.0
    assert errors[0] < 2.5e-3 and errors[2] < 6e-4
    assert errors[1] < errors[0] and errors[2] < errors[1]
    assert rate > 0.8, errors


def test_stream_function_velocity_carries_the_flux_and_follows_the_top():
    """A strip placed on a curved, stretched shape (top y = H (1 - 0.3 sin(pi x / L)^2)) with
    an arbitrary flux profile below each vertex: curl psi carries exactly `total` through the
    inlet and the outlet, nothing through the top and the symmetry line, and its divergence
    is zero (P1 psi: the velocity is constant per triangle)."""
    from ngsolve import BND, Integrate, specialcf

    H, L, U = 0.02, 0.2, 1.0
    strip = plug_strip(H, L, U, 0.05, 1.0)
    X, Y = strip.reference[:, 0], strip.reference[:, 1]
    shape = H * (1.0 - 0.3 * np.sin(np.pi * X / L) ** 2) / H
    strip.place(np.stack([X + 0.01 * np.sin(np.pi * X / L) * Y / H, Y * shape], -1))
    eta = strip.logical_points[:, 1]
    flux = (eta + 0.4 * eta**2 * (1.0 - eta) * np.cos(3 * X / L)).reshape(strip.shape)
    total = 0.0123
    strip.set_stream_function(flux, total)
    v, n, mesh = strip.velocity(), specialcf.normal(2), strip.mesh
    def through(region):
        return Integrate(v * n, mesh, BND, definedon=mesh.Boundaries(region))
    assert -through("left") == pytest.approx(total, rel=1e-12)
    assert through("right") == pytest.approx(total, rel=1e-12)
    for region in ("top", "bottom"):
        assert abs(through(region)) < 1e-14
        assert Integrate((v * n) ** 2, mesh, BND, definedon=mesh.Boundaries(region)) < 1e-24
    from ngsolve import grad
    g = grad(strip.psi)
    assert Integrate(g * g, mesh) > 0.0          # a real flow


def test_grading_rules_by_hand():
    """graded_axis: every break is a node, spacing <= fine between the breaks, growing by at
    most 1.3 outside up to coarse; top_rows: the top row `first` thick, each next at most 1.2
    times the last, none above `largest`, from 0 to 1."""
    breaks = [0.3, 0.35, 0.5, 0.6]
    X = graded_axis(0.0, 1.0, breaks, fine=0.01, coarse=0.1)
    assert X[0] == 0.0 and X[-1] == 1.0 and np.all(np.diff(X) > 0)
    for b in breaks:
        assert np.min(np.abs(X - b)) < 1e-12
    inside = (X[:-1] >= 0.3 - 1e-12) & (X[1:] <= 0.6 + 1e-12)
    assert np.max(np.diff(X)[inside]) <= 0.01 + 1e-12
    d = np.diff(X)
    assert np.max(d) <= 0.1 * 1.5 + 1e-12       # (the last step to an end: up to 1.5 coarse)
    assert np.all(d[1:-1] / d[:-2] < 1.3 + 1e-9) and np.all(d[:-2] / d[1:-1] < 1.3 + 1e-9)
    eta = top_rows(0.001, 0.05)
    assert eta[0] == 0.0 and eta[-1] == 1.0
    rows = np.diff(eta)[::-1]                           # from the top
    assert rows[0] == pytest.approx(0.001, rel=1e-12)
    assert np.all(rows[1:-1] / rows[:-2] <= 1.2 + 1e-12)
    assert np.max(rows[:-1]) <= 0.05 + 1e-12
    with pytest.raises(ValueError, match="first"):
        top_rows(0.1, 0.05)


def test_the_strip_is_fine_over_the_contact_and_a_quarter_of_it_either_side():
    """The temperature's columns: at most the fine size from a quarter contact length before
    the touching point to a quarter after the gap (both nodes), growing outside."""
    H, lc = 0.01, 0.04
    strip = plug_strip(H, 12.0 * H, 1.0, lc, 1.0)
    rp, X = strip.rp, strip.X
    lo, hi = rp.x_touch - 0.25 * lc, rp.axis_x + 0.25 * lc
    fine = np.max(np.diff(X)[(X[:-1] >= lo - 1e-12) & (X[1:] <= hi + 1e-12)])
    for edge in (lo, hi):
        assert np.min(np.abs(X - edge)) < 1e-12
    after = X[X > hi + 1e-12]
    before = X[X < lo - 1e-12]
    # outside, the first column is fine and the next ones grow (by 1.3)
    assert after[0] - hi == pytest.approx(fine) and after[1] - after[0] > 1.2 * fine
    assert lo - before[-1] == pytest.approx(fine) and before[-1] - before[-2] > 1.2 * fine


def test_layer_thickness_and_first_row_by_hand():
    """delta = sqrt(alpha l_c / U); the strip's top row is delta / 8 thick (in units of the
    exit half-thickness, for a flat strip exactly)."""
    rp = flat_pass(0.02, 0.3, 2.0, 0.05)
    delta = layer_thickness(rp, ALPHA)
    assert delta == pytest.approx(math.sqrt(ALPHA * 0.05 / 2.0), rel=1e-12)
    strip = ThermalStrip(rp, np.array([[0.0, 0.02], [0.3, 0.02]]), 0.004, delta)
    assert (1.0 - strip.eta[-2]) * 0.02 == pytest.approx(FIRST_CELL * delta, rel=1e-9)
    # the roll gap is a column, and logical() inverts the reference map
    assert np.min(np.abs(strip.X - rp.axis_x)) < 1e-12
    X, eta = strip.logical(strip.reference)
    assert X == pytest.approx(strip.logical_points[:, 0], abs=1e-12)
    assert eta == pytest.approx(strip.logical_points[:, 1], abs=1e-12)


def test_element_temperature_has_the_mean_consistency_by_hand():
    """The temperature a mechanics element takes from the strip vertices inside it is the one
    whose consistency is their weighted mean: for Hensel-Spittel K ~ exp(m1 T),
    T_e = ln(sum w exp(m1 T) / sum w) / m1, by hand; without a law the plain weighted mean.
    Two elements: one chilled at its top (900 K on a third of its weight, 1300 K elsewhere),
    one uniform."""
    from hotroll.model.flow_stress import HenselSpittel
    from hotroll.solvers.thermal_coupling import ThermalCoupling

    m1 = -0.0025
    vals = np.array([900.0, 1300.0, 1300.0, 1250.0, 1250.0])
    w = np.array([1.0, 1.0, 1.0, 2.0, 3.0])
    owner = np.array([0, 0, 0, 1, 1])
    ns = SimpleNamespace(mesh=SimpleNamespace(ne=2), _owner=owner, entry_strain=0.0,
                         flow=HenselSpittel(A=1.5e8, m1=m1, m3=0.15))
    T = ThermalCoupling._element_means(ns, vals, w)
    expect0 = math.log((math.exp(m1 * 900.0) + 2.0 * math.exp(m1 * 1300.0)) / 3.0) / m1
    assert T[0] == pytest.approx(expect0, rel=1e-9)     # 1118.9 K: harder than the mean 1166.7
    assert T[0] < (900.0 + 2 * 1300.0) / 3.0
    assert T[1] == pytest.approx(1250.0, rel=1e-12)
    ns.flow = None
    plain = ThermalCoupling._element_means(ns, vals, w)
    assert plain == pytest.approx([(900.0 + 2600.0) / 3.0, 1250.0], rel=1e-12)


def test_the_couplings_supg_parameter_and_load_are_the_forms_on_the_placed_strip():
    """What the coupling gives ``TemperatureField`` on its strip (constant properties):
    ``element_flow`` + ``p1_supg_tau`` against the L2 projection of the field's tau CF of the
    strip's velocity curl psi, element by element, and ``p1_supg_load`` against the assembly
    of int q (w + tau v.grad w) for a P1 source q, on a strip placed onto a bent, thinning
    channel (thin top rows: the positions' last digits matter). Measured 1.1e-14 (tau) and
    3e-15 of the largest load entry."""
    from ngsolve import CF, H1, GridFunction, LinearForm, dx, grad, x, y

    from hotroll.fem.heat_p1 import p1_supg_load, p1_supg_tau
    from hotroll.fem.mesh import mesh_triangles

    H, L, U, lc = 0.01, 0.06, 2.0, 0.01
    strip = plug_strip(H, L, U, lc, refine=1.0)
    X, Y = strip.reference[:, 0], strip.reference[:, 1]
    squeeze = 1.0 - 0.3 * np.clip((X - 0.2 * L) / lc, 0.0, 1.0)
    strip.place(np.stack([X + 0.02 * Y, Y * squeeze + 1e-3 * np.sin(X / L)], -1))
    bc = ThermalBoundary(1300.0, 350.0, 300.0, 2e4, 20.0, 0.8)
    field = TemperatureField(strip.mesh, STEEL, bc, inlet="left", top="top", outlet="right")
    t = mesh_triangles(strip.mesh)
    grads, det, v = strip.element_flow(t)
    tau = p1_supg_tau(grads, det, v, 7800.0 * 650.0, K)
    field._tau_gf.Set(field._tau(strip.velocity()))
    expected = field._tau_gf.vec.FV().NumPy()
    np.testing.assert_allclose(tau, expected, rtol=1e-13, atol=0.0)
    q = GridFunction(H1(strip.mesh, order=1))
    q.Set(1e9 * (1.0 + x / L) * (1.0 + 30.0 * y))
    w = field.space.TestFunction()
    f = LinearForm(field.space)
    f += (q * (w + field._tau_gf * (CF(strip.velocity()) * grad(w)))) * dx
    f.Assemble()
    load = f.vec.FV().NumPy()
    mine = p1_supg_load(t, grads, det, v, expected, q.vec.FV().NumPy(), strip.nv)
    assert np.max(np.abs(mine - load)) < 1e-13 * np.max(np.abs(load))
    strip.mesh.UnsetDeformation()


def test_structured_mesh_from_arrays_is_ngsolves():
    """``structured_triangle_mesh`` (arrays) builds the same points, triangles (order and
    orientation) and named boundaries as NGSolve's MakeStructured2DMesh mapped onto the axes."""
    from ngsolve.meshes import MakeStructured2DMesh

    from hotroll.fem.mesh import mesh_triangles, structured_triangle_mesh

    X = np.sort(np.random.default_rng(3).uniform(0.0, 2.0, 9))
    Y = np.array([0.0, 0.1, 0.5, 0.55, 1.0])
    nx, ny = len(X) - 1, len(Y) - 1
    ref = MakeStructured2DMesh(quads=False, nx=nx, ny=ny,
                               mapping=lambda a, b: (X[int(round(a * nx))], Y[int(round(b * ny))]))
    mesh = structured_triangle_mesh(X, Y)
    assert np.array_equal([v.point for v in mesh.vertices], [v.point for v in ref.vertices])
    assert np.array_equal(mesh_triangles(mesh), mesh_triangles(ref))
    assert mesh.GetMaterials() == ref.GetMaterials()
    for name in ("bottom", "right", "top", "left"):
        segs = [[v.nr for v in el.vertices] for el in mesh.Boundaries(name).Elements()]
        assert segs == [[v.nr for v in el.vertices] for el in ref.Boundaries(name).Elements()]
        assert len(segs) == (nx if name in ("bottom", "top") else ny)
