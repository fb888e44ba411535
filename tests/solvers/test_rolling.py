"""Short, coarse rolling runs of the report's geometry through the whole pipeline.

h = 0.02 m (4x coarser than Table 2's C1), a 1 m plate and 0.2 s of rolling, so that the plate
head has passed the exit section; the direct steady solver on the same mesh size. Checks
conservation (mass flux, power balance), the neutral point, the slip and normal-stress signs,
the outlet-driven state, the force balance, and steady = transient within stated bounds.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from casebuild import shared_scope

from hotroll.config.case import case_from_dict
from hotroll.workflows.runner import run_case

BASE = {
    "name": "coarse",
    "pass": {"roll_radius": 0.6, "entry_thickness": 0.5, "exit_thickness": 0.4,
             "roll_angular_velocity": math.pi / 3},
    "plate": {"length": 1.0},
    "material": {"K": 1.0, "m": 0.2},
    "mesh": {"h_contact": 0.02},
    "solver": {"method": "transient", "end_time": 0.2, "threads": 1},
    "output": {"figures": False, "vtk": False},
}


def _case(**over):
    d = json.loads(json.dumps(BASE))
    for dotted, value in over.items():
        sec, key = dotted.split(".")
        d.setdefault(sec, {})[key] = value
    return case_from_dict(d)


def _run(tmp_path_factory, name, **over):
    out = tmp_path_factory.mktemp(name)
    summary = run_case(_case(**over), out)
    contact = np.genfromtxt(out / "contact.csv", delimiter=",", names=True)
    return summary, contact, out


@pytest.fixture(scope=shared_scope)
def slipping(tmp_path_factory):
    """Fixed a_f = 3: a real backward-slip zone and a forward-slip zone near the exit."""
    return _run(tmp_path_factory, "af3", **{"friction.a_f": 3.0})


@pytest.fixture(scope=shared_scope)
def estimated(tmp_path_factory):
    """a_f from (3.15) at every step, as in the report."""
    return _run(tmp_path_factory, "estimate")


@pytest.fixture(scope=shared_scope)
def settled(tmp_path_factory):
    """The report's scheme with a_f = 3 run to its automatic steady state (traced tops;
    measured: 165 steps, 23 s on one thread)."""
    return _run(tmp_path_factory, "af3_steady_state", **{"friction.a_f": 3.0,
                                                         "solver.end_time": 3.0})


@pytest.fixture(scope=shared_scope)
def settled_constrained(tmp_path_factory):
    return _run(tmp_path_factory, "af3_constrained", **{"friction.a_f": 3.0,
                                                        "solver.end_time": 3.0,
                                                        "plate.free_surface": "constrained"})


@pytest.fixture(scope=shared_scope)
def steady_constrained(tmp_path_factory):
    return _run(tmp_path_factory, "steady_constrained", **{
        "solver.method": "steady", "friction.a_f": 3.0, "plate.free_surface": "constrained"})


@pytest.fixture(scope=shared_scope)
def steady_constrained_penalty(tmp_path_factory):
    """The constrained steady solve with the report's penalty contact: the transient's model
    (``settled_constrained``), for the two to be compared like with like."""
    return _run(tmp_path_factory, "steady_constrained_penalty", **{
        "solver.method": "steady", "friction.a_f": 3.0, "plate.free_surface": "constrained",
        "contact.method": "penalty"})


@pytest.fixture(scope=shared_scope)
def steady_slipping(tmp_path_factory):
    """Held to the arc (bilateral) as the report's scheme holds it ((2.28a): the same model)."""
    return _run(tmp_path_factory, "steady_af3", **{"solver.method": "steady",
                                                     "friction.a_f": 3.0,
                                                     "contact.unilateral": False})


@pytest.fixture(scope=shared_scope)
def steady_slipping_penalty(tmp_path_factory):
    """The steady solver with the report's penalty contact (``[contact] method``)."""
    return _run(tmp_path_factory, "steady_af3_penalty", **{
        "solver.method": "steady", "friction.a_f": 3.0, "contact.method": "penalty"})


@pytest.fixture(scope=shared_scope)
def steady_estimated(tmp_path_factory):
    return _run(tmp_path_factory, "steady_estimate", **{"solver.method": "steady"})


ALL = ["slipping", "estimated", "steady_slipping", "steady_estimated"]


@pytest.mark.parametrize("fixture", ALL)
def test_conservation(fixture, request):
    s, _, _ = request.getfixturevalue(fixture)
    assert s["mass_flux_error"] < 0.01          # measured 0.6 %
    # roll power = plastic + friction + penalty power: (3.6) tested with v, an identity of the
    # discrete equations for any friction law, so it checks convergence and that the reported
    # powers are the ones the equations contain (measured < 1e-4); the physics checks of the
    # powers are in test_figures.py (torque x omega against the dissipation, rate scaling)
    assert s["power_balance_error"] < 0.02
    assert s["roll_power"] > 0 and s["plastic_power"] > 0 and s["friction_power"] >= 0


@pytest.mark.parametrize("fixture", ALL)
def test_neutral_point_inside_arc(fixture, request):
    """a_f = 3: the neutral point on the arc. a_f from (3.15) (about 1e4) sticks the arc: the
    slip (about 1e-8 U) changes sign at random, so the neutral angle is null with the reason and
    the sticking zone is the arc; the flux's neutral angle is on the arc either way."""
    s, c, _ = request.getfixturevalue(fixture)
    x_touch = 1.0 - math.sqrt(0.6**2 - 0.55**2)
    bite = math.acos(1 - 0.05 / 0.6)
    if "estimated" in fixture:
        assert s["neutral_angle"] is None and s["neutral_point"] is None
        assert "sticking zone" in s["neutral_angle_reason"]
        assert 0.0 <= s["sticking_zone"][1] < s["sticking_zone"][0] <= 1.25 * bite
    else:
        assert x_touch < s["neutral_point"][0] < 1.0 and s["neutral_angle_reason"] is None
        assert 0.0 < s["neutral_angle"] < bite
    assert 0.0 < s["neutral_angle_flux"] < bite
    assert s["forward_slip"] > 0 and s["exit_velocity"] > s["entry_velocity"]


@pytest.mark.parametrize("fixture", ["settled", "steady_slipping"])
def test_slip_changes_sign_at_neutral_point(fixture, request):
    s, c, _ = request.getfixturevalue(fixture)
    before = c["angle"] > s["neutral_angle"]
    assert before.sum() >= 5 and (~before).sum() >= 1
    # the summary's neutral angle is a window mean, the profile the last step's: a node
    # next to it may slip by a few 1e-7 m/s either way
    noise = 1e-5 * s["roll_surface_speed"]
    assert np.all(c["v_slip"][before] < noise)
    assert np.all(c["v_slip"][~before] > -noise)
    # friction pulls the plate in before the neutral point and holds it back after it
    moving = np.abs(c["v_slip"]) > noise
    assert np.all(c["shear_stress"][before & moving] > 0)
    assert np.all(c["shear_stress"][~before & moving] < 0)


@pytest.mark.parametrize("fixture", ALL)
def test_normal_stress_compressive(fixture, request):
    _, c, _ = request.getfixturevalue(fixture)
    # all but the entry and exit zones of 2h = 0.04 m, where the boundary condition changes
    # (the report's oscillations at the entry and exit points; with the traction-free steady
    # tops the entry overshoot reaches the second contact node)
    inner = (c["x"] < 1.0 - 0.04) & (c["x"] > c["x"][0] + 0.03)
    assert np.all(c["normal_stress"][inner] < 0)
    assert np.all(c["normal_stress_corrected"][inner] < 0)


def test_estimate_gives_large_a_f_and_sticking(estimated, slipping):
    s, c, _ = estimated
    # the seed notes' independent check: (3.15) drives a_f to O(1e3..1e4); the arc sticks
    assert s["a_f"] > 100
    inner = np.abs(c["v_slip"][2:-2])
    assert np.median(inner) < 1e-2 * np.median(np.abs(slipping[1]["v_slip"][2:-2]))


def test_outputs_written(slipping):
    """The files of a transient run, one history row per step (resume after a kill is in
    test_behaviour.py)."""
    s, _, out = slipping
    for name in ("summary.json", "contact.csv", "top.csv", "history.csv", "fields.npz",
                 "case.toml", "checkpoint/state.npz"):
        assert (out / name).exists(), name
    hist = np.genfromtxt(out / "history.csv", delimiter=",", names=True)
    assert len(hist) == s["steps"] and list(hist["step"]) == list(range(s["steps"]))


def test_linear_solver_failure_keeps_finished_steps(tmp_path, monkeypatch):
    """A step whose linear systems cannot be solved ends the run as 'failed' with the reason;
    the finished steps' history, fields and summary are written, not lost."""
    import hotroll.solvers.transient as T
    from hotroll.fem.nonlinear import LinearSolveError

    real, calls = T.solve, {"n": 0}

    def failing(*args, **kw):
        calls["n"] += 1
        if calls["n"] == 4:       # initial solve + a_f iterations are separate; fail a step
            raise LinearSolveError("no direct solver (test)")
        return real(*args, **kw)

    monkeypatch.setattr(T, "solve", failing)
    s = run_case(_case(**{"friction.a_f": 3.0, "solver.end_time": 0.05}), tmp_path)
    assert s["status"] == "failed" and not s["converged"]
    assert "no direct solver (test)" in s["failure"]
    hist = np.genfromtxt(tmp_path / "history.csv", delimiter=",", names=True)
    assert len(hist) == s["steps"] >= 2 and np.all(np.isfinite(hist["roll_force"]))
    assert (tmp_path / "fields.npz").exists() and (tmp_path / "checkpoint/state.npz").exists()


def test_tangled_mesh_is_detected():
    """An element turned inside out by the Lagrangian update stops the run with its place."""
    from hotroll.solvers.transient import TangledMeshError, TransientRun
    from hotroll.workflows.runner import build_model

    model, settings = build_model(_case(**{"friction.a_f": 3.0}))
    run = TransientRun(model, settings)
    run._check_mesh()                                  # the initial mesh is fine
    X = run.top.X0[: run.mesh.nv]
    i = int(np.argmin(np.hypot(X[:, 0] - 0.5, X[:, 1] - 0.1)))   # a vertex inside the plate
    ns = run.form.fes.components[0].ndof // 2
    run.d[ns + i] = 0.5                                # pushed far up through its neighbours
    run.mesh.SetDeformation(run.disp)
    with pytest.raises(TangledMeshError, match="inside out"):
        run._check_mesh()


def test_contact_is_bilateral_until_the_exit():
    """(3.9) with the bilateral constraint (2.28a): a contact node that drifts 5 tol off the
    roll between projections stays in contact (and is put back on the roll by the next
    projection); without ``bilateral`` the report's distance rule releases it; a node past
    the exit point M is always released; a far node never gets caught."""
    from hotroll.solvers.transient import TransientRun
    from hotroll.workflows.runner import build_model

    model, settings = build_model(_case(**{"friction.a_f": 3.0}))
    run = TransientRun(model, settings)
    top, rp, tol = run.top, model.rp, settings.contact_tol
    P = top.vertex_positions(run.d)
    on = np.nonzero(top.vertex_contact & (P[:, 0] < rp.axis_x - 0.05))[0]
    assert len(on) >= 3
    k = on[len(on) // 2]
    r = np.hypot(*(P[k] - rp.centre))
    off = np.array(rp.centre) + (P[k] - rp.centre) * (r + 5 * tol) / r   # 5 tol off the roll
    assert rp.signed_distance(off[None])[0] == pytest.approx(5 * tol, rel=1e-6)
    for bilateral, kept in ((False, False), (True, True)):
        top.vertex_contact[k] = True
        top.set_vertices(run.d, top.verts[[k]], off[None])
        top.detect(rp, run.d, tol, project_contact=False, bilateral=bilateral)
        assert top.vertex_contact[k] == kept
    top.detect(rp, run.d, tol, project_contact=True, bilateral=True)
    assert abs(rp.signed_distance(top.vertex_positions(run.d)[[k]])[0]) < 1e-12
    far = int(np.argmin(P[:, 0]))                      # the tail corner, far upstream
    assert not top.vertex_contact[far]
    last = int(np.argmax(np.where(top.vertex_contact, P[:, 0], -np.inf)))   # at M
    top.set_vertices(run.d, top.verts[[last]], np.array([[rp.axis_x + 2 * tol, rp.half_exit]]))
    top.detect(rp, run.d, tol, project_contact=False, bilateral=True)
    assert not top.vertex_contact[last]


def _history(drift: float, n: int = 120, seed: int = 0) -> list:
    """Rows like the report's histories: a spike every 10 steps (the contact projection),
    1 % random noise, and a relative linear drift of ``drift`` over the n rows."""
    rng = np.random.default_rng(seed)
    rows = []
    for i in range(n):
        f = (1.0 + drift * i / n) * (1.0 + 0.2 * (i % 10 == 0) + 0.01 * rng.standard_normal())
        rows.append({"roll_force": 0.5 * f, "roll_torque": 0.1 * f,
                     "strain_rate_measure": 0.09 * f, "forward_slip": 0.03 * f,
                     "neutral_angle": 0.04 * f})
    return rows


def test_steady_criterion_separates_drift_from_periodic_noise():
    from hotroll.solvers.settling import steady_reached

    args = (60, 10, 2e-3, 0.39)
    assert steady_reached(_history(0.0), *args)         # +-20 % spikes, no drift: steady
    assert not steady_reached(_history(0.05), *args)    # 2.5 % between windows: not yet
    assert not steady_reached(_history(0.0)[:100], *args)   # fewer than two windows
    late = _history(0.0)
    late[-1]["forward_slip"] = math.nan                 # head not past the exit section
    assert not steady_reached(late, *args)


def test_free_exit_surface_penalises_vertical_motion_only():
    """(3.2d) on a wrinkled exit surface: a rigid horizontal translation costs nothing (the
    flat exit's normal e_y), while the wrinkled mesh normal would penalise it; before the gap
    the mesh normal is kept."""
    from ngsolve import BND, Integrate, specialcf

    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.runner import build_model, steady_settings

    case = _case(**{"solver.method": "steady"})
    model, _ = build_model(case)
    run = SteadyRun(model, steady_settings(case), case.plate.length)
    ns, rp = run.form.fes.components[0].ndof // 2, model.rp
    X = run.top.X0
    for i in run.top.verts:                            # a saw-tooth of amplitude h/4
        run.d[ns + i] += 0.25 * model.h * (-1) ** int(round(X[i, 0] / model.h))
    run.mesh.SetDeformation(run.disp)
    vel = run.form.nonlinear.gf.components[0]
    vel.Set((rp.u_roll, 0.0))
    mesh, nh = run.mesh, specialcf.normal(2)

    def on(region, cf):
        return float(Integrate(cf, mesh, BND, definedon=mesh.Boundaries(region)))

    length = on("exit", 1.0)
    assert on("exit", run.form.free_normal(vel) ** 2) < 1e-12 * rp.u_roll**2 * length
    assert on("exit", (vel * nh) ** 2) > 1e-2 * rp.u_roll**2 * length
    assert abs(on("top", run.form.free_normal(vel) ** 2) - on("top", (vel * nh) ** 2)) < 1e-12


@pytest.mark.parametrize("pair, bounds", [
    # measured (h = 0.02, a_f = 3): force +0.8 %, torque +2.8 %, slip +0.17 points,
    # neutral angle +0.004 rad
    (("steady_slipping_penalty", "settled"), {"force": 0.03, "torque": 0.05, "slip": 3e-3,
                                              "angle": 0.01, "plastic": 0.05}),
    # exact contact (issue 30) against the report's penalty scheme on this coarse mesh
    # (h = 0.02): measured force -1.1 %, torque -2.4 %, slip -0.22 points, neutral angle
    # -0.021 rad, plastic power +5.4 % (the penalty's leak moves the slip and the neutral
    # point); on M2 see
    # docs/validation/contact.md
    (("steady_slipping", "settled"), {"force": 0.02, "torque": 0.04, "slip": 6e-3,
                                      "angle": 0.03, "plastic": 0.08}),
    # both with the report's penalty contact (the steady solver's default, exact contact, is
    # another model: torque -11 % against this transient); measured (steady against
    # transient, 9369641): force +8.3 %, torque +1.6 %, slip +0.08 points, angle -0.008 rad,
    # plastic power +5.4 %; the transient's flat tops end at the discrete first contact
    # node, 1 h = 0.02 m wide here
    # (the report's scheme to steady state with constrained tops: 25 s, in -m slow)
    pytest.param(("steady_constrained_penalty", "settled_constrained"),
                 {"force": 0.12, "torque": 0.05, "slip": 3e-3, "angle": 0.015, "plastic": 0.08},
                 marks=pytest.mark.slow),
])
def test_steady_agrees_with_transient(pair, bounds, request):
    """The direct steady solve against the report's scheme run to its steady state, same
    model (free-surface model, friction, penalties) and mesh size."""
    s, _, _ = request.getfixturevalue(pair[0])
    t, _, _ = request.getfixturevalue(pair[1])
    assert s["method"] == "steady" and t["method"] == "transient"
    assert s["free_surface"] == t["free_surface"]
    # the steady penalty run ends with exit code 7 (its leak is 17 % of the forward slip on
    # this coarse mesh, issue 30): settled, its figures still compared
    assert s["steady_state"] and s["fixed_point_settled"] and t["status"] == "steady"
    assert s["converged"] or s["not_conserved"]
    assert s["roll_force"] == pytest.approx(t["roll_force"], rel=bounds["force"])
    assert s["roll_torque"] == pytest.approx(t["roll_torque"], rel=bounds["torque"])
    assert abs(s["forward_slip"] - t["forward_slip"]) < bounds["slip"]
    assert abs(s["neutral_angle"] - t["neutral_angle"]) < bounds["angle"]
    assert s["plastic_power"] == pytest.approx(t["plastic_power"], rel=bounds["plastic"])


def test_a_given_a_f_is_kept_and_an_estimated_one_follows_the_flow(slipping, estimated):
    """The report's scheme: friction.a_f = 3 is the a_f of every step; left out, (3.15) is
    evaluated again before every step's solve (history.csv's a_f column changes from step to
    step, as the flow does)."""
    for fixture, given in ((slipping, True), (estimated, False)):
        _, _, out = fixture
        a_f = np.genfromtxt(out / "history.csv", delimiter=",", names=True)["a_f"]
        if given:
            assert np.all(a_f == 3.0)
        else:
            assert len(np.unique(a_f[1:])) > len(a_f[1:]) // 2


@pytest.mark.parametrize("fixture", ["steady_slipping", "steady_estimated", "steady_constrained",
                                     "settled", pytest.param("settled_constrained",
                                                             marks=pytest.mark.slow)])
def test_force_balance(fixture, request):
    """The plate's forces close: roll + free tops + faces + symmetry reaction = 0, the last
    from the residual of (3.6) in its Dirichlet rows. That closure is an identity of the
    discrete equations (e_x, e_y are test functions): it checks that the reported forces are
    the ones the equations apply, and Newton's convergence. The physics check is the symmetry
    line's force computed from the stress on it, which must carry the roll force (traced tops
    carry nothing, no tension; a roll force scaled by 1.1 fails); constrained tops carry part
    of the load (measured: 36 % of the roll force at a_f = 5)."""
    s, _, _ = request.getfixturevalue(fixture)
    fb = s["force_balance"]
    roll = fb["roll"]
    force = -roll[1]                       # the last step's (the summary's force is a mean)
    if s["method"] == "steady":
        assert force == pytest.approx(s["roll_force"], rel=1e-12)
    assert s["balance_error"] < 1e-4
    total = np.sum([fb[k] for k in ("roll", "free_top", "face", "symmetry")], axis=0)
    assert np.hypot(*total) < 1e-4 * force
    # the symmetry line's force from the stress on it (-int sigma_yy dx, not from the
    # residual): measured +0.5..0.8 % (steady), +0.9 % (transient) at h = 0.02
    assert s["symmetry_stress_force_y"] == pytest.approx(fb["symmetry"][1], rel=0.02)
    if s["free_surface"] == "traced":
        assert s["symmetry_stress_force_y"] == pytest.approx(force, rel=0.02)
        if s["method"] == "steady":
            assert fb["free_top"] == [0.0, 0.0]
            assert abs(roll[0]) < 1e-3 * abs(roll[1])
            assert fb["symmetry"][1] == pytest.approx(force, rel=1e-3)
        else:
            # the report's scheme: free top nodes arriving at the roll move faster than it,
            # and the one-sided inlet penalty (3.2a) on the free top holds them back (measured
            # 1.2 % of the roll force, horizontal)
            assert np.hypot(*fb["free_top"]) < 0.02 * force
    else:
        assert s["free_top_force_share"] == pytest.approx(np.hypot(*fb["free_top"]) / force,
                                                          rel=1e-9)
        assert 0.2 < s["free_top_force_share"] < 0.6


def test_steady_outputs_and_unit_independence(tmp_path_factory, steady_slipping):
    s1, c1, out = steady_slipping
    # held to the arc (bilateral), the raw multiplier turns tensile near the gap of this thick
    # strip: reported (issue 30), not hidden by an exit correction
    assert s1["steps"] == 0 and s1["newton_solves"] >= 1 and s1["contact_loss_detected"]
    assert s1["fixed_point_settled"] and s1["coupling_updates"] >= 2
    hist = np.genfromtxt(out / "history.csv", delimiter=",", names=True)
    # one row per coupling update and one per Newton solve, all at the target m (cold start
    # from the kinematic guess, no continuation)
    assert len(hist) == s1["newton_solves"] + s1["coupling_updates"]
    assert np.all(hist["m"] == 0.2)
    assert hist["iterations"].sum() == s1["nonlinear_iterations"]
    s2, c2, _ = _run(tmp_path_factory, "steady_si", **{"solver.method": "steady",
                                                         "friction.a_f": 3.0, "material.K": 1.5e8,
                                                         "contact.unilateral": False})
    for key in ("neutral_angle", "forward_slip", "exit_velocity"):
        assert s2[key] == pytest.approx(s1[key], rel=1e-6, abs=1e-12)
    assert s2["roll_force"] == pytest.approx(1.5e8 * s1["roll_force"], rel=1e-6)


def test_steady_domain_lengths_do_not_matter(tmp_path_factory, steady_slipping):
    """Doubling the flat entry and exit of the steady strip changes nothing that matters."""
    s1, _, _ = steady_slipping
    s2, _, _ = _run(tmp_path_factory, "steady_long", **{
        "solver.method": "steady", "friction.a_f": 3.0, "contact.unilateral": False,
        "solver.steady_entry_length": 2.0, "solver.steady_exit_length": 1.6})
    assert s2["dofs"] > s1["dofs"]
    # measured: torque +0.3 %, exit velocity -0.1 %; the roll force +1.5 % here but up to 8 %
    # with only one length doubled: it follows the discrete first contact node (one element)
    for key in ("roll_torque", "exit_velocity", "mass_flux_out"):
        assert s2[key] == pytest.approx(s1[key], rel=0.02)
    assert s2["roll_force"] == pytest.approx(s1["roll_force"], rel=0.1)


FRICTION_LAWS = {"viscoplastic": {}, "coulomb": {"friction.law": "coulomb", "friction.mu": 0.3},
                 "tresca": {"friction.law": "tresca", "friction.factor": 0.8}}


@pytest.mark.parametrize("hand,law", [(True, "viscoplastic"), (False, "viscoplastic"),
                                      (True, "coulomb"), (True, "tresca")])
def test_newton_jacobian_is_the_exact_linearisation(hand, law):
    """The assembled Jacobian (Norton-Hoff and friction tangents by hand + the other boundary
    terms by symbolic differentiation, or the whole residual differentiated) equals NGSolve's
    automatic linearisation of the residual, at a state with contact, friction and active
    penalties, for each friction law (the primal-dual tangent with nu = eps/E at the iterate,
    where it is Newton's: fem/primal_dual.py)."""
    import numpy as np

    import hotroll.fem.rolling_form as RF
    from hotroll.fem.forms import NonlinearProblem
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.runner import build_model, steady_settings

    case = _case(**{"solver.method": "steady", **FRICTION_LAWS[law]})
    model, _ = build_model(case)
    # the Jacobian without the matrix-only regularisation of the multiplier block (a term the
    # residual does not have, docs/theory.md 1e): then it is the exact linearisation
    saved, RF.MATRIX_REGULARISATION = RF.MATRIX_REGULARISATION, 0.0
    try:
        run = SteadyRun(model, steady_settings(case), case.plate.length)
    finally:
        RF.MATRIX_REGULARISATION = saved
    run._cold_start()
    form = run.form
    form.a_f.Set(37.0)
    prob = form.nonlinear if hand else NonlinearProblem(form.fes, form.integrand,
                                                      velocity_scale=model.rp.u_roll)
    rng = np.random.default_rng(1)
    vec = prob.gf.vec.FV().NumPy()
    vec[:] = form.nonlinear.gf.vec.FV().NumPy()
    vec[:] *= 1.0 + 0.3 * rng.standard_normal(vec.size)   # both signs of slip, inlet/outlet active
    assert np.sum(form.chi.vec.FV().NumPy()) > 5
    if hasattr(prob, "prepare"):     # the primal-dual tangent's nu = eps/E at the iterate
        prob.prepare(1)
    prob.a_newton.AssembleLinearization(prob.gf.vec)
    prob.a_jacobian.Assemble()
    x = prob.gf.vec.CreateVector()
    x.FV().NumPy()[:] = rng.standard_normal(x.size)
    a = (prob.a_newton.mat * x).Evaluate().FV().NumPy()
    b = (prob.a_jacobian.mat * x).Evaluate().FV().NumPy()
    assert np.linalg.norm(a - b) <= 1e-12 * np.linalg.norm(a)
