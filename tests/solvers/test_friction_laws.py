"""Coulomb and Tresca friction and the strip tensions through the rolling code (issue 15).

The report's geometry on a coarse mesh (h = 0.02 m), steady solver unless stated. Each law is
checked against numbers computed here from the case's own parameters (mu, factor, tensions)
and the fields the run writes, not against the law object the solver used:
- Tresca: the contact shear is factor x k with k = sigma_ef / sqrt3 taken from the written
  strain-rate field;
- Coulomb: where mu p < k the shear is mu p (friction power = mu int p |v_s| ds); with a large
  mu the contact sticks wherever mu p > k and gives Tresca's factor 1 answer;
- tensions: the force balance carries exactly sigma_b h0/2 and sigma_f h1/2, the power balance
  closes with the tensions' power, and they move the neutral point and the forward slip the
  way slab theory says (back tension towards the exit and less slip, front the opposite; both
  lower the force).
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from casebuild import build_case, shared_scope
from scipy.integrate import simpson

from hotroll.config.case import CaseError
from hotroll.model.friction import CoulombFriction, TrescaFriction, ViscoplasticFriction
from hotroll.workflows.runner import run_case

BASE = {
    "name": "friction",
    "pass": {"roll_radius": 0.6, "entry_thickness": 0.5, "exit_thickness": 0.4,
             "roll_angular_velocity": math.pi / 3},
    "plate": {"length": 1.0},
    "material": {"K": 1.0, "m": 0.2},
    "friction": {"law": "coulomb", "mu": 0.3},
    "mesh": {"h_contact": 0.02},
    "solver": {"method": "steady", "threads": 1},
    "output": {"figures": False, "vtk": False},
}
SQRT3 = math.sqrt(3.0)
THIN = {"pass.roll_radius": 0.3, "pass.entry_thickness": 0.1, "pass.exit_thickness": 0.08,
        "pass.roll_angular_velocity": 1.0, "plate.length": 0.5, "mesh.h_contact": "auto"}
THIN_MU02 = {"law": "coulomb", "mu": 0.2}


def _case(friction=None, **over):
    return build_case(BASE, "friction", friction, **over)


def _run(tmp_path_factory, name, friction=None, **over):
    out = tmp_path_factory.mktemp(name)
    summary = run_case(_case(friction, **over), out)
    contact = np.genfromtxt(out / "contact.csv", delimiter=",", names=True)
    fields = dict(np.load(out / "fields.npz"))
    return summary, contact, fields


def _k_from_fields(contact, fields):
    """k = sigma_ef / sqrt3 at the contact vertices, from the written vertex fields."""
    pts = fields["points"]
    xy = np.stack([contact["x"], contact["y"]], -1)
    nearest = np.argmin(np.linalg.norm(pts[None, :, :] - xy[:, None, :], axis=-1), axis=1)
    return fields["sigma_ef"][nearest] / SQRT3


@pytest.fixture(scope=shared_scope)
def coulomb(tmp_path_factory):
    return _run(tmp_path_factory, "coulomb")


@pytest.fixture(scope=shared_scope)
def tresca(tmp_path_factory):
    return _run(tmp_path_factory, "tresca", {"law": "tresca", "factor": 0.8})


# --- the law objects on numbers (hand-derived) -------------------------------------------------
def test_laws_on_numbers():
    v_reg = 1e-6
    slip = np.array([-0.3, -0.01, 0.02, 0.5])
    p, k = np.array([1.0, 4.0, 2.0, -1.0]), np.array([0.9, 0.9, 0.9, 0.9])
    # Coulomb: min(mu p, k) against the slip, no shear where the pressure is tensile (the kinks
    # rounded over 1 % of k: 1e-4 here)
    tau = CoulombFriction(v_reg, mu=0.3).shear(slip, pressure=p, k=k)
    assert tau == pytest.approx([0.3, 0.9, -0.6, 0.0], rel=2e-4, abs=1e-4)
    sharp = CoulombFriction(v_reg, mu=0.3, rounding=1e-9).shear(slip, pressure=p, k=k)
    assert sharp == pytest.approx([0.3, 0.9, -0.6, 0.0], rel=1e-6, abs=1e-9)
    tau = TrescaFriction(v_reg, factor=0.8).shear(slip, k=k)
    assert tau == pytest.approx(-0.72 * np.sign(slip), rel=1e-6)
    # viscoplastic (2.29a): a_f K |v_s|^m against the slip
    tau = ViscoplasticFriction(v_reg, K=2.0, m=0.2).shear(slip, a_f=3.0)
    assert tau == pytest.approx(-6.0 * np.abs(slip) ** 0.2 * np.sign(slip), rel=1e-6)
    # dissipation is never negative
    assert np.all(CoulombFriction(v_reg, mu=0.3).power_density(slip, pressure=p, k=k) >= 0)


@pytest.mark.mutation
@pytest.mark.parametrize("law", [CoulombFriction(1e-3, mu=0.3), TrescaFriction(1e-3, factor=0.8),
                                 ViscoplasticFriction(1e-3, K=2.0, m=0.2)])
def test_coefficient_partials_are_the_derivatives(law):
    """Newton's friction tangent uses ``coefficient_partials``: central differences of the
    coefficient in slip^2, pressure and k agree, across Coulomb's two rounded kinks (p near 0,
    mu p near k) and sliding/sticking points."""
    slip2 = np.array([1e-8, 4e-6, 1e-4, 0.09, 0.25, 1e-6, 2e-5])
    p = np.array([1.0, 4.0, 2.0, -1.0, 3.0, 0.001, 2.99])    # mu p = k at p = 3
    k = np.full_like(p, 0.9)
    kw = dict(a_f=3.0, m=0.2)
    d_s2, d_p, d_k = law.coefficient_partials(slip2, pressure=p, k=k, **kw)

    def diff(arg, value):
        h = 1e-6 * np.maximum(np.abs(value), 1e-6)
        args = dict(slip2=slip2, pressure=p, k=k)
        up = law.coefficient(**{**args, arg: value + h}, **kw)
        down = law.coefficient(**{**args, arg: value - h}, **kw)
        return (up - down) / (2 * h)

    for analytic, arg, value in ((d_s2, "slip2", slip2), (d_p, "pressure", p), (d_k, "k", k)):
        expected = diff(arg, value)
        assert np.broadcast_to(analytic, expected.shape) == pytest.approx(
            expected, rel=1e-5, abs=1e-7 * np.max(np.abs(expected)) + 1e-12), arg


# --- through the rolling code -------------------------------------------------------------------
@pytest.mark.mutation   # cheap enough for mutmut's selection (pyproject [tool.mutmut])
def test_tresca_shear_is_factor_times_k(tresca):
    summary, contact, fields = tresca
    assert summary["converged"] and summary["power_balance_error"] < 1e-2
    v = contact["vertex"] == 1
    # past the first h of the arc: the flow turns onto the roll at the contact's start (the
    # velocity's corner singularity, the mesh refined 16x there), the strain rate varies
    # steeply across its small surface elements, and the two k below differ there by up to
    # 12 % (0.2-0.7 h from the start; within 4 % beyond h)
    beyond = contact["x"] > contact["x"][0] + summary["h_contact"]
    sliding = v & beyond & (np.abs(contact["v_slip"]) > 10 * 1e-3 * summary["roll_surface_speed"])
    assert sliding.sum() >= 5
    k = _k_from_fields(contact[sliding], fields)
    ratio = np.abs(contact["shear_stress"][sliding]) / k
    # k here is sigma_ef of the written P1 strain rate, the law's the P1 field of sigma_ef:
    # the two interpolations differ by a few %
    assert np.median(ratio) == pytest.approx(0.8, rel=0.05)
    assert np.all(np.abs(ratio - 0.8) < 0.08)


@pytest.mark.mutation   # cheap enough for mutmut's selection (pyproject [tool.mutmut])
def test_coulomb_shear_is_mu_p_below_the_cap(coulomb):
    summary, contact, fields = coulomb
    assert summary["converged"] and summary["power_balance_error"] < 1e-2
    # the shear is the law of the multiplier's own nodal values (as the form evaluates it)
    p, slip = -contact["normal_stress_multiplier"], contact["v_slip"]
    k = _k_from_fields(contact, fields)
    reg = np.abs(slip) / np.hypot(slip, 1e-3 * summary["roll_surface_speed"])  # (2.29a)-like
    # away from the law's rounded kinks (p = 0 and mu p = k, rounded over 1 % of k)
    slide = (0.3 * p < 0.8 * k) & (p > 0.5 * k) & (reg > 0.98)
    assert slide.sum() >= 5
    assert np.abs(contact["shear_stress"][slide]) == pytest.approx(0.3 * p[slide] * reg[slide],
                                                                   rel=2e-3)
    # where mu p exceeds k the shear is capped at k (sticking friction); the form takes k at
    # its quadrature points from the element's strain rate, k here is sigma_ef of the written
    # P1 strain rate: they differ by up to 13 % node by node where the rate varies steeply
    # across the surface element, 4 % in the median; "exceeds" by 5 % (beyond the 1 % kink
    # rounding and the median difference: on the mesh refined at the contact's start mu p
    # sits at 1.05-1.09 k over the first 4 h, 3 of its vertices above 1.2 k before)
    stick = (contact["vertex"] == 1) & (0.3 * p > 1.05 * k)
    assert stick.sum() >= 3
    ratio = np.abs(contact["shear_stress"][stick]) / k[stick]
    assert np.median(ratio) == pytest.approx(1.0, abs=0.07)
    # at worst: one vertex mid-arc where the written strain rate dips (sigma_ef of the P1 rate
    # against the P1 field of sigma_ef: 0.31 against 0.53 with exact contact, 13 % with the
    # penalty, issue 30)
    assert np.all(np.abs(ratio - 1.0) < 0.75)


def test_coulomb_friction_power_is_mu_p_slip(tmp_path_factory):
    """Low friction, no sticking: the dissipated friction power is mu int p |v_s| ds, taken
    from the contact profile (trapezoid over the arc) and the case's mu. A thinner pass
    (bite angle 0.26 rad: at mu = 0.2 the strip is drawn in; Example 1's 0.41 rad is not)."""
    summary, contact, fields = _run(tmp_path_factory, "coulomb_low", THIN_MU02, **THIN)
    assert summary["converged"] and not summary["outlet_driven"]
    # the multiplier's own nodal values: the P1 function the form's friction term integrates
    p = np.maximum(-contact["normal_stress_multiplier"], 0.0)
    slip, v_reg = contact["v_slip"], 1e-3 * summary["roll_surface_speed"]
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(contact["x"]), np.diff(contact["y"])))])
    k = _k_from_fields(contact, fields)
    # it sticks only at the first touching node (the entry corner's pressure peak)
    assert np.mean(0.2 * p < k) > 0.9
    # regularised: |tau| |v_s| = min(mu p, k) v_s^2 / sqrt(v_s^2 + v_reg^2)
    # Simpson on each P2 edge (vertex, midpoint, vertex alternate along the arc)
    power = simpson(np.minimum(0.2 * p, k) * slip**2 / np.sqrt(slip**2 + v_reg**2), x=arc)
    assert summary["friction_power"] == pytest.approx(power, rel=0.03)


def test_large_mu_sticks_like_a_factor_of_one(tmp_path_factory, coulomb):
    """mu -> infinity: min(mu p, k) = k wherever the roll presses, i.e. Tresca with factor 1;
    more friction, more force."""
    big, _, _ = _run(tmp_path_factory, "coulomb_big", {"law": "coulomb", "mu": 2.0})
    one, _, _ = _run(tmp_path_factory, "tresca_one", {"law": "tresca", "factor": 1.0})
    assert big["roll_force"] == pytest.approx(one["roll_force"], rel=0.01)
    assert big["roll_torque"] == pytest.approx(one["roll_torque"], rel=0.02)
    # not "more friction, more force": on this thick strip (h/l_c about 1.8) the force hardly
    # depends on friction (measured with exact contact: mu = 2 0.12 % below mu = 0.3; with the
    # penalty 0.6 % above); sticking slips less: the friction power falls (0.56 vs 1.16 mW/m)
    assert big["friction_power"] < coulomb[0]["friction_power"]


# --- tensions -----------------------------------------------------------------------------------
@pytest.fixture(scope=shared_scope)
def tensions(tmp_path_factory, coulomb):
    f = {"law": "coulomb", "mu": 0.5}
    base = _run(tmp_path_factory, "mu05", f)[0]
    back = _run(tmp_path_factory, "back", f, **{"pass.back_tension": 0.1})[0]
    front = _run(tmp_path_factory, "front", f, **{"pass.front_tension": 0.1})[0]
    return base, back, front


def test_tension_forces_and_power_balance(tensions):
    _, back, front = tensions
    # the tension force is sigma times the face's half-thickness (the exit one is the traced
    # strip's, flux / mean velocity, 0.2 % below the gap)
    assert back["force_balance"]["tension"][0] == pytest.approx(-0.1 * 0.25, rel=1e-6)
    exit_half = front["mass_flux_out"] / front["exit_velocity"]
    assert exit_half == pytest.approx(0.2, rel=5e-3)
    assert front["force_balance"]["tension"][0] == pytest.approx(0.1 * exit_half, rel=1e-4)
    for s in (back, front):
        assert s["converged"]
        assert s["balance_error"] < 1e-4
        # roll power + tension power = dissipation
        assert s["power_balance_error"] < 1e-2
        # the tension's power is sigma x flux (back: taken out, front: put in)
    assert back["tension_power"] == pytest.approx(-0.1 * back["mass_flux_in"], rel=1e-2)
    assert front["tension_power"] == pytest.approx(0.1 * front["mass_flux_out"], rel=1e-2)


def test_tensions_move_the_neutral_point(tensions):
    base, back, front = tensions
    assert back["neutral_angle"] < base["neutral_angle"] < front["neutral_angle"]
    assert back["forward_slip"] < base["forward_slip"] < front["forward_slip"]
    assert back["roll_force"] < base["roll_force"] and front["roll_force"] < base["roll_force"]


# --- input ---------------------------------------------------------------------------------------
@pytest.mark.parametrize("friction, key", [
    ({"law": "coulomb"}, "friction.mu"),
    ({"law": "tresca"}, "friction.factor"),
    ({"law": "tresca", "factor": 1.5}, "friction.factor"),
    ({"law": "coulomb", "mu": -0.1}, "friction.mu"),
    ({"law": "coulomb", "mu": 0.3, "a_f": 5.0}, "friction.a_f"),
    ({"law": "viscoplastic", "mu": 0.3}, "friction.mu"),
    ({"law": "amontons"}, "friction.law"),
])
def test_bad_friction_input_names_the_field(friction, key):
    with pytest.raises(CaseError) as e:
        _case(friction)
    assert key in str(e.value)


def test_negative_tension_is_refused():
    with pytest.raises(CaseError) as e:
        _case(**{"pass.back_tension": -1.0})
    assert "pass.back_tension" in str(e.value) and ">= 0" in str(e.value)


def test_coulomb_in_the_reports_scheme_obeys_the_law(tmp_path_factory):
    """The report's scheme with Coulomb friction, a few steps (not steady): on the sliding
    contact nodes the written shear is mu p times the regularisation, computed here from the
    written pressure and slip; the power balance closes with the law's friction power."""
    s, contact, fields = _run(tmp_path_factory, "coulomb_steps", {"law": "coulomb", "mu": 0.2},
                              **{"solver.method": "transient", "solver.end_time": 0.015})
    assert s["method"] == "transient" and s["steps"] >= 3
    assert s["power_balance_error"] < 1e-2
    p, slip = -contact["normal_stress"], contact["v_slip"]
    k = _k_from_fields(contact, fields)
    reg = np.abs(slip) / np.hypot(slip, 1e-3 * s["roll_surface_speed"])
    slide = (0.2 * p < 0.8 * k) & (p > 0.5 * k) & (reg > 0.98)
    assert slide.sum() >= 5
    assert np.abs(contact["shear_stress"][slide]) == pytest.approx(0.2 * p[slide] * reg[slide],
                                                                   rel=2e-3)
    # friction opposes the slip
    assert np.all(contact["shear_stress"][slide] * slip[slide] < 0)


@pytest.mark.slow
def test_coulomb_in_the_reports_scheme_agrees_with_steady(tmp_path_factory):
    """The report's scheme with Coulomb friction run to its steady state against the steady
    solver with the same model, the report's penalty contact, on the same mesh (h = 0.02,
    Example 1's geometry; measured at 9369641: force +1.2 %, torque -1.7 %, slip +0.31 points).
    Both end not conserved (exit code 7: the penalty lets the strip through the roll, most at
    this slow roll), their figures still compared, as in test_rolling.py. Slow (about 6 min on
    one core: 171 steps of 8-15 Newton iterations), outside the default suite:
    ``pytest -m slow``. (The default steady run, exact contact, is another model: force
    -0.4 %, torque +4.7 %, slip +1.7 points against this transient.)"""
    tr, _, _ = _run(tmp_path_factory, "coulomb_transient",
                    **{"solver.method": "transient", "solver.end_time": 3.0})
    st, _, _ = _run(tmp_path_factory, "coulomb_penalty", **{"contact.method": "penalty"})
    assert tr["status"] == "steady" and (tr["converged"] or tr["not_conserved"])
    assert st["steady_state"] and st["fixed_point_settled"]
    assert tr["roll_force"] == pytest.approx(st["roll_force"], rel=0.02)
    assert tr["roll_torque"] == pytest.approx(st["roll_torque"], rel=0.03)
    assert abs(tr["forward_slip"] - st["forward_slip"]) < 0.005
    assert tr["power_balance_error"] < 1e-2


@pytest.mark.parametrize("fixture", ["coulomb", "tresca"])
def test_written_shear_flow_stress_is_the_fields_k(fixture, request):
    """contact.csv's shear_flow_stress (k = sigma_ef/sqrt3 at the contact nodes, projected
    onto P1 from the volume) against k from the written vertex field sigma_ef at the same
    vertices: two projections of the same stress, measured 3.5 % (Coulomb) and 1.9 % (Tresca)
    apart in the median, 13 % and 7 % at worst (next to the contact ends)."""
    _, contact, fields = request.getfixturevalue(fixture)
    vertex = contact["vertex"] > 0
    ratio = contact["shear_flow_stress"][vertex] / _k_from_fields(contact[vertex], fields)
    assert np.median(np.abs(ratio - 1.0)) < 0.08
    # measured with exact contact (issue 30): 0.70 at one vertex mid-arc where the written
    # strain rate dips (Coulomb; 13 % with the penalty)
    assert np.max(np.abs(ratio - 1.0)) < 0.75


def test_the_registry_builds_the_friction_section():
    """[friction] is built from model/friction's registry: every law's parameters are fields
    with their unit in the description, each law takes only its own (by hand: Coulomb's mu,
    Tresca's factor, the viscoplastic a_f defaulting to "estimate"), the default v_reg is the
    law's fraction of the roll speed, and each law names a slab form the comparison knows."""
    from hotroll.config.friction import FrictionConfig
    from hotroll.model.friction import FRICTION_LAWS

    assert list(FRICTION_LAWS) == ["viscoplastic", "coulomb", "tresca"]
    fields = FrictionConfig.model_fields
    for spec in FRICTION_LAWS.values():
        for p in spec.parameters:
            assert p.name in fields and f"[{p.unit or '-'}]" in fields[p.name].description
        assert spec.slab[0] in ("coulomb", "tresca", "sticking")
    fr = FrictionConfig(law="viscoplastic")
    assert fr.given() == {"a_f": "estimate"} and fr.a_f_rule is None
    assert fr.regularisation_velocity(2.0) == pytest.approx(2e-4)
    tr = FrictionConfig(law="tresca", factor=0.4)
    assert tr.given() == {"factor": 0.4} and tr.a_f_rule == 0.0 and not tr.uses_a_f
    assert tr.regularisation_velocity(2.0) == pytest.approx(2e-3)
    assert tr.law_object(2.0, 0.2) == TrescaFriction(2e-3, factor=0.4)
    with pytest.raises(ValueError, match="friction.mu: only for law"):
        FrictionConfig(law="tresca", factor=0.4, mu=0.3)
