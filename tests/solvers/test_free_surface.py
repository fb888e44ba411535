"""The free-surface models (docs/theory.md 4d) and the automatic mesh size (4e).

The traced tops must be streamlines of the computed flow (v.n = 0, checked on the FE field with
the mesh normal, independently of the tracing code), the contact must start where the entry top
meets the roll, the kinematic update must do what its formula says on data made by hand, and a
case without ``h_contact`` must get the automatic size.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from casebuild import shared_scope
from test_rolling import _case

from hotroll.fem.free_surface import StripShape, kinematic_update, roll_height, roll_slope
from hotroll.model.geometry import RollPass
from hotroll.solvers.steady import SteadyRun
from hotroll.workflows.runner import build_model, steady_settings


def _steady(**over) -> SteadyRun:
    case = _case(**{"solver.method": "steady", "friction.a_f": 3.0, **over})
    model, _ = build_model(case)
    return SteadyRun(model, steady_settings(case), case.plate.length)


def _rms_normal_velocity(run: SteadyRun) -> float:
    """RMS of v.n (mesh normal) over the free tops, per unit roll speed."""
    from ngsolve import BND, Integrate, specialcf

    mesh, u = run.mesh, run.form.nonlinear.velocity
    free = (1 - run.form.chi)
    n = specialcf.normal(2)
    top = mesh.Boundaries("top|arc|exit")
    vn2 = Integrate(free * (u * n) ** 2, mesh, BND, definedon=top, order=6)
    length = Integrate(free, mesh, BND, definedon=top)
    return math.sqrt(vn2 / length) / run.problem.rp.u_roll


@pytest.fixture(scope=shared_scope)
def traced():
    run = _steady()
    run.run()
    return run


def test_traced_tops_are_streamlines(traced):
    """At the converged shape v.n ~ 0 on the free tops up to discretisation error (measured
    RMS 4.1e-3 U at h = 0.02, 2.4e-3 U at h = 0.01: the corners where the tops meet the roll);
    the same flow on the flat tops, before any update, has 1.9e-2 U."""
    assert traced.result.converged and traced.state.status == "steady"
    assert traced.result.surface_moves[-1] < 1e-3 * traced.problem.h
    assert _rms_normal_velocity(traced) < 6e-3
    flat = _steady(**{"solver.max_iterations": 30})
    flat.s.max_outer = 0            # no surface update: the flat tops of the reference shape
    flat.run()
    assert _rms_normal_velocity(flat) > 3 * _rms_normal_velocity(traced)


def test_contact_starts_where_the_entry_top_meets_the_roll(traced):
    """The first contact node lies on the roll at x_c; the entry top sags ahead of the bite
    (x_c > x_touch) and reaches the roll there continuously; the exit top leaves the roll at
    the contact's last node x_e (the gap, or before it where the strip separates)."""
    rp, top, d = traced.problem.rp, traced.top, traced.d
    x_c = traced.shape.x_c
    assert rp.x_touch < x_c < rp.x_touch + 0.1 * rp.contact_length
    contact = top.vertex_positions(d, top.verts[top.vertex_contact])
    first = contact[np.argmin(contact[:, 0])]
    assert first[0] == pytest.approx(x_c, abs=1e-12)
    assert abs(rp.signed_distance(first[None])[0]) < 1e-12
    free = top.vertex_positions(d, top.verts[~top.vertex_contact])
    before = free[free[:, 0] < x_c]
    assert np.all(before[:, 1] <= rp.half_entry + 1e-3 * traced.problem.h)   # no bulge
    assert np.all(rp.signed_distance(free) > 0)  # no free node inside the roll
    last = contact[np.argmax(contact[:, 0])]      # traced from the last contact node
    x_e = traced.shape.end(rp)
    assert last[0] == pytest.approx(x_e, abs=1e-12) and x_e <= rp.axis_x
    assert abs(rp.signed_distance(last[None])[0]) < 1e-12
    assert np.interp(x_e, traced.shape.exit_x, traced.shape.exit_y) == pytest.approx(
        last[1], abs=1e-12 * rp.radius)


def test_flat_shape_is_the_reference_mesh(traced):
    """The map of the flat shape is the reference strip (arc midpoints on the roll), after a
    solve has moved the mesh to a traced shape and back."""
    rp, solved = traced.problem.rp, traced.shape
    traced.shape = StripShape.flat(rp)
    traced._set_shape()
    d_flat = traced.d.copy()
    traced.shape = solved                    # the module's fixture back to its solved shape
    traced._set_shape()
    assert np.allclose(d_flat, traced.d_ref, rtol=0, atol=1e-14)
    assert not np.allclose(traced.d, traced.d_ref, rtol=0, atol=1e-6)
    top = traced.top
    mids = top.midpoint_positions(d_flat, np.nonzero(top.region == "arc")[0])
    assert np.allclose(rp.signed_distance(mids), 0.0, atol=1e-12)
    flat = top.midpoint_positions(d_flat, np.nonzero(top.region == "top")[0])
    assert np.allclose(flat[:, 1], rp.half_entry, atol=1e-14)


def test_kinematic_update_by_hand():
    """Entry nodes with v_y/v_x = -s ((x - x0)/L)^2 over the last L before x_c (0 before) trace
    to h0 - s L / 3 at x_c (the cubic rule, ``_trace``, is exact on each quadratic piece and,
    measured, to rounding across the slope's C1 kink at x0 too); the contact start moves by
    gap / roll slope; the exit top is traced from the gap, its slope linear in x after it."""
    rp = RollPass(0.6, 0.25, 0.2, 1.0)
    shape = StripShape.flat(rp)
    x_c, s, L = shape.x_c, 0.01, 0.05
    xs = np.linspace(x_c - 0.3, x_c, 61)
    x0 = x_c - L
    vx = np.full_like(xs, 0.5)
    vy = np.where(xs > x0, -s * ((xs - x0) / L) ** 2 * vx, 0.0)
    ex = np.linspace(rp.axis_x + 0.01, rp.axis_x + 0.2, 20)
    x = np.concatenate([xs[:-1], [x_c, 0.9, rp.axis_x], ex])
    # the exit's slope c (x - X_roll) from 0 at the gap: the top c (x - X_roll)^2 / 2 above it
    c = 0.05
    y_ex = rp.half_exit + 0.5 * c * (ex - rp.axis_x) ** 2
    y = np.concatenate([np.full(len(xs) - 1, rp.half_entry), roll_height(rp, [x_c, 0.9]),
                        [rp.half_exit], y_ex])
    v = np.stack([np.concatenate([vx, [0.6, 0.6], np.full(len(ex), 0.62)]),
                  np.concatenate([vy, [-0.1, 0.0], 0.62 * c * (ex - rp.axis_x)])], axis=1)
    part = np.concatenate([np.zeros(len(xs) - 1), [1, 1, 1], np.full(len(ex), 2)]).astype(int)
    new, residual = kinematic_update(rp, shape, np.stack([x, y], 1), v, part, xs[0],
                                     (rp.x_touch - 0.1, rp.axis_x - 0.1))
    gap = -s * L / 3.0
    assert residual == pytest.approx(abs(gap), rel=1e-9)
    assert new.x_c - x_c == pytest.approx(gap / roll_slope(rp, x_c), rel=1e-9)
    assert np.interp(new.x_c, new.entry_x, new.entry_y) == pytest.approx(
        roll_height(rp, new.x_c), abs=1e-12)
    assert np.allclose(np.interp(ex, new.exit_x, new.exit_y), y_ex, rtol=0, atol=1e-15)


def test_automatic_mesh_size(tmp_path):
    """A case without h_contact gets l_c/12, at most a sixth of the exit half-thickness;
    Example 1's file keeps the report's C2."""
    from test_rolling import BASE

    from hotroll.config.case import case_from_dict, load_case
    from hotroll.examples import example_path

    d = {k: dict(v) if isinstance(v, dict) else v for k, v in BASE.items()}
    d["mesh"] = {}
    case = case_from_dict(d)
    rp = case.pass_.roll_pass()
    assert case.mesh.h_contact == "auto"
    assert case.mesh.h == pytest.approx(min(rp.contact_length / 12, rp.half_exit / 6))
    d["pass"] = dict(d["pass"], roll_radius=0.35, entry_thickness=0.025, exit_thickness=0.02)
    thin = case_from_dict(d)
    assert thin.mesh.h == pytest.approx(0.01 / 6)            # the thickness governs
    assert thin.dt == pytest.approx(thin.mesh.h / 6)
    assert "h_contact = \"auto\"" in thin.to_toml()
    assert load_case(example_path("example1")).mesh.h_contact == "C2"


def test_smoothed_profile_keeps_linear_data_and_integrals():
    """The plotted contact profile (P1 projection of the P2 nodal values): a linear profile is
    reproduced exactly, a vertex/midpoint zigzag is removed, and the integral along the arc
    (the force of the profile) is kept."""
    from hotroll.fem.quantities import smoothed

    t = np.linspace(0.0, 1.0, 41)                       # 20 edges: vertex, midpoint, ...
    prof = {"x": 0.2 * np.cos(t), "y": 0.2 * np.sin(t)}
    s = 0.2 * t                                         # arc length
    linear = 3.0 - 2.0 * s
    assert np.allclose(smoothed(prof, linear), linear, atol=1e-12)
    zigzag = linear + np.where(np.arange(41) % 2 == 1, 0.5, 0.0)    # midpoints lifted
    sm = smoothed(prof, zigzag)
    vertex = np.arange(0, 41, 2)
    assert np.ptp(np.diff(sm[vertex])) < 0.1 * np.ptp(np.diff(zigzag))

    def integral(v):       # Simpson on each edge = the integral of the P2 / P1 profile
        L = np.diff(s[vertex])
        return float(np.sum(L * (v[0:-1:2] + 4 * v[1::2] + v[2::2]) / 6))

    assert integral(sm) == pytest.approx(integral(zigzag), rel=1e-12)


def test_hotroll_run_defaults_to_traced_tops_and_the_automatic_mesh(tmp_path):
    """`hotroll run` on a case that names neither the free-surface model nor the mesh: traced
    tops, h = min(l_c/12, half_exit/6), a converged steady solve with units in the table."""
    import json

    from typer.testing import CliRunner

    from hotroll.cli import app

    case = tmp_path / "pass.toml"
    case.write_text(
        "[pass]\nroll_radius = 0.35\nentry_thickness = 0.025\nexit_thickness = 0.02\n"
        "roll_angular_velocity = 3.0\n[plate]\nlength = 1.0\n[material]\nK = 2.0e8\n"
        "m = 0.15\n[friction]\na_f = 5.0\n[output]\nfigures = false\nvtk = false\n")
    result = CliRunner().invoke(app, ["run", str(case), "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert "N/m" in result.output
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    rp = RollPass(0.35, 0.0125, 0.01, 3.0)
    assert s["free_surface"] == "traced" and s["method"] == "steady" and s["converged"]
    assert s["h_contact"] == pytest.approx(min(rp.contact_length / 12, rp.half_exit / 6))
    # balance: measured 5.0e-4 with exact contact (9e-5 with the penalty): Newton's residual
    # floor of the near-rigid zones (eps0^(m-1), m = 0.15) at the converged velocity
    assert s["mass_flux_error"] < 0.01 and s["balance_error"] < 1e-3
    assert s["symmetry_stress_force_y"] == pytest.approx(s["roll_force"], rel=0.02)
