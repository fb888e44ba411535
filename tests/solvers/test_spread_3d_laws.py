"""The 3D pass's laws and scalings (solvers/spread_3d.py, solvers/spread_fields.py, issue 53):
Case R of ../shared/notes/asymmetric-rolling.md (R = 250 mm, 10 -> 8 mm, Tresca 0.3) on its
coarse test mesh (h = 1 mm), a stock 10 mm wide (b0/h0 = 1): a Hensel-Spittel grade with its
strain (held, and carried through the 3D flow), with [thermal], with an entry temperature
across the width; the exact scalings in the roll speed and in K (Norton-Hoff m = 0.05). Split
from test_spread_3d.py so that the two files run on the two test workers.

Labels: [identity] what any converged discrete solution of this model satisfies; [exact] an
exact scaling or a field the discretisation holds exactly; [hand] signs and limits from the
mechanics; [estimate] a hand estimate with its measured accuracy."""
from __future__ import annotations

import numpy as np
import pytest
from test_full_strip import _setup  # the same directory (pytest puts it on the path)

from hotroll.solvers.spread_3d import Spread3D
from hotroll.solvers.steady import SteadyRun

B0 = 0.005       # m, the stock's half width


#: a Hensel-Spittel grade (a strain field; the strip's elasticity from its family), and the
#: same with [thermal] (the elements' temperature, its rate exponent m(T))
_THERMAL = {"thermal.htc_contact": 2.0e4, "thermal.roll_temperature": 400.0,
            "thermal.htc_air": 20.0, "thermal.emissivity": 0.8, "material.density": 7800.0,
            "material.specific_heat": 650.0, "material.conductivity": 30.0}


@pytest.mark.parametrize("extra", [{}, _THERMAL], ids=["strain", "strain-thermal"])
def test_the_held_edge_keeps_a_strain_law_its_temperature_and_the_elastic_strip(extra):
    """[identity] the strain and the temperature frozen across the width
    (solvers/spread_fields.py) and the strip's elasticity in the contact's constraint (its
    upwinding along the arc, ``RollingForm3D.arc_step``): with the edge held the 2D pass in
    every layer solves the 3D form, one Newton step, force and torque per width the 2D pass's
    to 1e-10 (the flow stress read as mid-width's everywhere would be off by the hardening;
    the elastic rate upwinded over the face's mesh_size by 2e-3)."""
    case, problem, st = _setup(**{"material.law": "hensel-spittel", "material.grade": "C45",
                                  "material.m": None, "material.K": None, **extra})
    run = SteadyRun(problem, st, case.plate.length)
    assert run.run().status == "steady"
    assert run.strain is not None and run.form.compliance
    assert (run.thermal is not None) == bool(extra)
    two = run.state.history[-1]
    held = Spread3D(run, B0, edge=B0, edge_held=True)
    assert held.solve() and held.iterations == 1
    f = held.figures()
    assert f["roll_force_per_width"] == pytest.approx(two["roll_force"], rel=1e-10)
    assert f["roll_torque"] / (2.0 * B0) == pytest.approx(two["roll_torque"], rel=1e-10)
    assert f["midplane_velocity_deviation"] <= 1e-10


@pytest.fixture(scope="module")
def c45():
    """Case R with C45's Hensel-Spittel law (a strain field; the strip's elasticity): the
    plane-strain pass solved, and its 3D pass with a free edge in one width layer (the strain
    carried, no entry temperature; its progress reports kept), shared by the two tests below
    (the suite's time: each 3D pass is ~25 s)."""
    case, problem, st = _setup(**{"material.law": "hensel-spittel", "material.grade": "C45",
                                  "material.m": None, "material.K": None})
    run = SteadyRun(problem, st, case.plate.length)
    assert run.run().status == "steady"
    moved = Spread3D(run, B0, edge=B0)
    moved.reports = []
    assert moved.solve(progress=moved.reports.append)
    return run, moved


def test_the_strain_is_carried_through_the_3d_flow(c45):
    """A Hensel-Spittel grade (C45: K rises with the strain) on the narrow bar, one width
    layer. [hand] The strip spreads, so its exit strain is not plane strain's: the homogeneous
    equivalent strain of the exit's shape, sqrt(2/3 (e_x^2 + e_y^2 + e_z^2)) with e_y =
    ln(h1/h0), e_z = ln(b1/b0) and e_x = -(e_y + e_z), is below plane strain's
    2/sqrt(3) ln(h0/h1); [estimate] the 3D exit strain's mean over the width is the 2D pass's
    exit strain (plane strain plus the redundant shear) times the ratio of the two homogeneous
    strains, within 5 % (measured 2.9 %: the same share of redundant shear). [hand] Less strain,
    less hardening: the force per width below the frozen strain's (the 2D pass's in every
    layer); the strain's fixed point settles with the surfaces (tolerance 1e-3)."""
    import math

    from hotroll.solvers.record import exit_strain
    from hotroll.solvers.spread_record import spread_record

    run, moved = c45
    frozen = Spread3D(run, B0, edge=B0, strain="frozen")
    assert frozen.solve() and frozen.strain is None
    assert moved.strain is not None
    assert "the carried fields changed" in moved.reports[-1]["message"]
    f, g = moved.figures(), frozen.figures()
    levels = spread_record(moved).exit_thickness
    eps = np.asarray(levels["strain"])
    assert eps.shape == (2,)
    h0, h1 = run.problem.rp.half_entry, run.problem.rp.half_exit
    e_y, e_z = math.log(h1 / h0), math.log(f["exit_half_width"] / B0)
    e_x = -(e_y + e_z)
    hom3 = math.sqrt(2.0 / 3.0 * (e_x ** 2 + e_y ** 2 + e_z ** 2))
    hom2 = 2.0 / math.sqrt(3.0) * math.log(h0 / h1)
    assert e_z > 0.0 and hom3 < hom2
    mean = 0.5 * (eps[0] + eps[1])                       # two levels, the width halved
    assert mean == pytest.approx(exit_strain(run) * hom3 / hom2, rel=0.05)
    assert f["roll_force_per_width"] < g["roll_force_per_width"]


def test_an_entry_temperature_across_the_width_is_carried_into_the_flow_stress(c45):
    """The entry temperature across the width (``Spread3D(entry_temperature=...)``: the
    case's ``spread.temperature_profile``, or over the cross-section its
    ``spread.temperature_section``, model/section.py). [identity] a uniform profile at the
    plate's temperature is no profile, and a section the same at every height is the profile
    across the width (1e-12, with the edge held). [exact] with the edge held (u_z = 0) the
    difference from mid-width's is carried along x unchanged from the set-up on: at every
    vertex the inlet's at its z (linear in z: P1 holds it; 1e-6 K of 100 K), and the held
    strip's force rises with it. Free edge, the section T0 - 100 zeta (0.5 + eta) (the edge
    50 K colder at mid-thickness, 150 K at the surface): [estimate] the force rises as the
    section's mean of the flow stress at the pass's mean strain rate and half its exit strain,
    sigma(T) / sigma(T0) over eta and zeta, within 2 % (measured 0.9 %; 0.5 % for a profile
    across the width alone: the mean weighs the heights alike, the force does not);
    [estimate] the outlet carries at each height what the inlet had there (a streamline
    keeps its share of the flux below it): the recorded exit offset at the edge within 1 % of
    the entry's range (measured 0.4 %), and at mid-width 0 within 1 %."""
    import math

    from hotroll.model.profile import ThicknessProfile
    from hotroll.model.section import SectionProfile
    from hotroll.solvers.record import exit_strain
    from hotroll.solvers.spread_record import spread_record

    run, moved = c45
    pb = run.problem
    T0, rp, flow = pb.temperature, pb.rp, pb.flow_stress

    def held_force(profile):
        s3 = Spread3D(run, B0, edge=0.5 * B0, edge_held=True, entry_temperature=profile)
        assert s3.solve()
        return s3.figures()["roll_force"]

    uniform = ThicknessProfile.from_pairs([[0.0, T0], [1.0, T0]])
    assert held_force(uniform) == pytest.approx(held_force(None), rel=1e-12)
    cold = ThicknessProfile.from_pairs([[0.0, T0], [1.0, T0 - 100.0]])
    same = SectionProfile((0.0, 1.0), (0.0, 1.0), ((T0, T0 - 100.0), (T0, T0 - 100.0)))
    held = Spread3D(run, B0, edge=0.5 * B0, edge_held=True, entry_temperature=cold)
    z = np.array([v.point[2] for v in held.mesh.vertices])
    assert np.max(np.abs(held.cooling.values + 100.0 * z / B0)) <= 1e-6   # carried at set-up
    assert held.solve()
    assert held.figures()["roll_force"] == pytest.approx(held_force(same), rel=1e-12)
    # [hand] colder edges are harder: the held strip's force above the plane-strain pass's
    assert held.figures()["roll_force_per_width"] > 1.05 * run.state.history[-1]["roll_force"]
    rate = rp.u_roll / rp.contact_length * 2.0 / math.sqrt(3.0) * math.log(
        rp.half_entry / rp.half_exit)
    eps = 0.5 * exit_strain(run)
    grid = np.linspace(0.0, 1.0, 11)
    section = SectionProfile(tuple(grid), tuple(grid), tuple(
        tuple(T0 - 100.0 * q * (0.5 + e) for q in grid) for e in grid))
    E, Z = np.meshgrid(np.linspace(0.0, 1.0, 201), np.linspace(0.0, 1.0, 201), indexing="ij")
    ratio = np.vectorize(lambda T: flow.sigma(eps, rate, T))(section(E, Z)) / flow.sigma(
        eps, rate, T0)
    mean = float(np.trapezoid(np.trapezoid(ratio, dx=0.005, axis=1), dx=0.005))
    s3 = Spread3D(run, B0, edge=B0, entry_temperature=section)
    assert s3.solve()
    assert s3.figures()["roll_force"] / moved.figures()["roll_force"] == pytest.approx(
        mean, rel=0.02)
    out = spread_record(s3).exit_temperature_offset
    assert out["zeta"] == [0.0, 1.0]                   # one width layer: mid-width and edge
    eta, v = np.asarray(out["eta"]), np.asarray(out["values"])
    assert np.max(np.abs(v[:, 1] + 100.0 * (0.5 + eta))) <= 0.01 * 150.0
    assert np.max(np.abs(v[:, 0])) <= 0.01 * 150.0


def test_the_elastic_layer_carries_its_flux_across_the_width(c45):
    """The strip's elasticity in 3D (docs/theory.md 1e and 4l, ``RollingForm3D``): the layer
    carries F = c_e p (u.t t + u_z e_z), the roll is impermeable to u.n - div F, and the flux
    out through the contact's boundary lines is a line term (its start, its lateral edge
    ``arc_edge``; the searched ends have none: p_end = 0 there). [identity] tested with
    xi = 1 the arc's net flux is what the layer carries out at the levels' ends, F(end) at the
    search's tolerance: below 1e-7 of the inflow (measured -1.85e-8). [hand] the width term's
    own size, int d(c_e p u_z)/dz dA written out in the test, is at least 5e-6 of it
    (measured 1.2e-5): without the width terms the arc passed -1.21e-5 of the inflow
    (measured before them)."""
    from layer_terms import arc_flux, width_flux_divergence

    _, moved = c45
    f = moved.form
    assert f.compliance and moved.ends is not None and moved.face is not None
    arc, inflow = arc_flux(f)
    assert inflow > 0.0
    assert abs(width_flux_divergence(f)) >= 5e-6 * inflow
    assert abs(arc) <= 1e-7 * inflow


def test_the_elastic_layers_terms_are_conservative(c45):
    """[identity of the conservative form] for any flow with p = 0 on the contact's end line
    (the layer carries nothing out there) and u_z = 0 on ``zsym``, the layer's terms tested
    with xi = 1 balance: int div F dA (the rate, its test function 1) = the start line's
    int F.nu dl + the lateral edge's, to 1e-10 of the inflow (measured 7e-13), here the
    solved flow with its multiplier set to 0 at the end line's vertices. The start's term is
    1.4e-4 of the inflow and the edge's 1.3e-7 (the edge is a stream line: F.nu = c_e p
    u.nu, small; its F_z part alone, int c_e p u_z dl written out, is 1.2e-5, at least 5e-6
    asserted), so a term off by 10 % breaks the balance."""
    import ngsolve as ng
    from layer_terms import arc_flux, edge_flux, layer_terms

    _, moved = c45
    f = moved.form
    _, inflow = arc_flux(f)
    assert abs(edge_flux(f)) >= 5e-6 * inflow
    mesh, gf = f.mesh, f.nonlinear.gf
    on = {b: {v.nr for el in mesh.Elements(ng.BND) if el.mat == b for v in el.vertices}
          for b in ("arc", "exit")}
    end = on["arc"] & on["exit"]
    assert len(end) == len(moved.z)                    # one vertex per width level
    keep = gf.vec.CreateVector()
    keep.data = gf.vec
    try:
        x, first = gf.vec.FV().NumPy(), f.fes.Range(2).start
        for el in mesh.Boundaries("arc").Elements():
            for v, d in zip(el.vertices, f.fes.components[2].GetDofNrs(el)):
                if v.nr in end and d >= 0:
                    x[first + d] = 0.0
        terms = layer_terms(f)
    finally:
        gf.vec.data = keep
    assert abs(terms["start"]) >= 1e-5 * inflow and abs(terms["edge"]) >= 1e-8 * inflow
    assert abs(terms["rate"] - terms["start"] - terms["edge"]) <= 1e-10 * inflow


def test_the_elastic_layers_jacobian_is_its_residuals_derivative(c45):
    """[identity] Newton's Jacobian of the layer's terms in 3D (the flux rate along the arc
    with its width term, the conormal line terms on the start and the lateral edge; F is
    bilinear in (u, p)) applied to a random direction is the central difference of their
    residual along it (quadratic: exact up to round-off), at the solved state moved at random
    (u_z everywhere): 1e-10 (measured 2.8e-12, 5.1e-12)."""
    from layer_terms import layer_jacobian_error

    _, moved = c45
    for seed in (0, 1):
        assert layer_jacobian_error(moved.form, seed=seed) <= 1e-10


@pytest.fixture(scope="module")
def base() -> dict:
    """Case R's 3D pass unchanged (one width layer), the reference of both scalings."""
    return _scaled_pass(lambda p: p)


def _scaled_pass(change) -> dict:
    """The figures of Case R's 3D pass (one width layer: the cheapest free edge) with its
    ``Problem`` changed by ``change`` (a function of the problem)."""
    case, problem, st = _setup()
    run = SteadyRun(change(problem), st, case.plate.length)
    assert run.run().status == "steady"
    s3 = Spread3D(run, B0, edge=B0)
    assert s3.solve()
    return s3.figures()


def test_the_3d_pass_keeps_the_exact_scaling_in_the_roll_speed(base):
    """[scaling] the roll speed, the law's eps0 and the friction's v_reg x 100 (time x 1/100):
    the reduced problem is the same, so the spread and the exit half widths are the same (to
    the surfaces' tolerance: 1e-7), the force and the torque x 100^m (Norton-Hoff), the fluxes
    x 100 (one width layer)."""
    from dataclasses import replace

    def faster(p, c=100.0):
        return replace(p, rp=replace(p.rp, omega=c * p.rp.omega),
                       friction=replace(p.friction, v_reg=c * p.friction.v_reg),
                       material=replace(p.material, eps0=c * p.material.eps0))

    a, b = base, _scaled_pass(faster)
    m = 0.05
    assert b["spread"] == pytest.approx(a["spread"], rel=1e-7)
    for key in ("roll_force", "roll_torque"):
        assert b[key] == pytest.approx(100.0**m * a[key], rel=1e-7)
    for key in ("flux_in", "flux_out"):
        assert b[key] == pytest.approx(100.0 * a[key], rel=1e-7)


def test_the_3d_pass_keeps_the_exact_scaling_in_k(base):
    """[scaling] K x 1000 (every stress x 1000, the reduced problem the same): the spread,
    the exit half widths and the fluxes the same to 1e-9, the roll force and torque x 1000
    (one width layer: the cheapest free edge)."""
    from dataclasses import replace

    a = base
    b = _scaled_pass(lambda p: replace(p, material=replace(p.material, K=1000.0 * p.material.K)))
    for key in ("spread", "flux_in", "flux_out"):
        assert b[key] == pytest.approx(a[key], rel=1e-9)
    assert b["exit_half_width_profile"] == pytest.approx(a["exit_half_width_profile"], rel=1e-9)
    for key in ("roll_force", "roll_torque"):
        assert b[key] == pytest.approx(1000.0 * a[key], rel=1e-9)
