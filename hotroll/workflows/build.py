"""From a validated case to the solver's input: the problem (mesh spec, laws, couplings'
data) and the settings of either solver (the case -> problem stage of the pipeline)."""
from __future__ import annotations

from dataclasses import replace

from hotroll.config.case import Case, CaseError
from hotroll.config.full_strip import asymmetric_refusal, friction_sections
from hotroll.config.roll_sides import SIDES
from hotroll.config.spread import entry_section
from hotroll.fem.mesh import MeshSpec, plate_fine_length
from hotroll.model.material import NortonHoff
from hotroll.model.roll_elastic import FlatteningRoll, RollElasticity
from hotroll.solvers.problem import GapRolls, Problem
from hotroll.solvers.settling import default_end_time
from hotroll.solvers.steady_settings import SteadySettings, stage_iterations
from hotroll.solvers.transient import TransientSettings

#: Two dips of a flattened roll's surface less than this share of the exit half-thickness
#: apart in height are the same exit: the nearest to the last one is kept (``RollShape.lowest``;
#: thin strip's flat zone, docs/theory.md 1f). The exit thickness moves by at most 1e-3.
EXIT_TIE = 1e-3


def reference_material(case: Case):
    """(NortonHoff(K_ref, m, eps0), flow-stress law): the Norton-Hoff law that coincides with
    the case's flow-stress law at the plate temperature and entry strain (exactly the law for
    Norton-Hoff; for Hensel-Spittel m = m3 + m8 T and K_ref = K(entry strain, T), the strain
    dependence carried by the field K(strain)/K_ref, ``fem/rolling_form.py``)."""
    flow, T = case.material.flow_stress(), case.plate.temperature
    m = float(flow.rate_exponent(T))
    if not 0.0 < m <= 1.0:
        raise CaseError(f"plate.temperature: the flow-stress law's rate exponent is {m:.4g} at "
                        f"{T:g} K; it must be in (0, 1] (allowed temperatures for this law: "
                        f"{getattr(flow, 'admissible_temperature_range', lambda: '?')()} K)")
    K_ref = float(flow.consistency(case.plate.mean_entry_strain, T))
    return NortonHoff(K_ref, m, case.material.eps0), flow


def gap_rolls(case: Case, m: float) -> GapRolls:
    """The two rolls of an asymmetric pass for the full strip (``Problem.gap``): each roll's
    arc (``RollGap.arc``), its friction law (its section's, v_reg from its own surface speed;
    reduced units, rate exponent ``m``), a_f (given; None for a law without it) and, for a
    flattening roll, its model ([roll] or its side's table; [roll]'s elasticity and
    relaxation)."""
    gap = case.roll_gap()
    rolls, frictions, a_f, models = {}, {}, {}, {}
    elasticity = RollElasticity(case.roll.youngs_modulus, case.roll.poissons_ratio)
    for side, (_, section) in zip(SIDES, friction_sections(case)):
        rp = gap.arc(side)
        rolls[side] = rp
        frictions[side] = section.law_object(rp.u_roll, m)
        a_f[side] = section.a_f_rule if section.uses_a_f else None
        kind = (gap.upper if side > 0 else gap.lower).model
        if kind not in (None, "rigid"):
            models[side] = (kind, elasticity, case.roll.relaxation, EXIT_TIE * rp.half_exit)
    return GapRolls(rolls, frictions, a_f, gap.speed_ratio, models)


def build_model(case: Case):
    """Translate the case description into the solver's model and settings. A pass whose two
    rolls differ also carries them (``Problem.gap``: the full-thickness strip), after the
    refusal of what that strip does not carry yet (``asymmetric_refusal``)."""
    refusal = asymmetric_refusal(case)
    if refusal is not None:
        raise refusal
    sv = case.solver
    rp = case.pass_.roll_pass()
    h = case.mesh.h
    end_time = sv.end_time or default_end_time(rp)
    spec = MeshSpec(h=h, fine_length=plate_fine_length(rp, h, end_time),
                    h_far=case.mesh.h_far, grading=case.mesh.grading,
                    corner=case.mesh.corner_refinement)
    material, flow = reference_material(case)
    t_profile, e_profile = case.plate.entry_profiles()
    model = Problem(rp, case.plate.length, material,
                         case.friction.law_object(rp.u_roll, material.m), spec,
                         back_tension=case.pass_.back_tension,
                         front_tension=case.pass_.front_tension,
                         # (a 3D pass's entry temperature across the width takes the law too)
                         flow_stress=flow if (flow.depends_on_strain or case.thermal or (
                             entry_section(case) is not None)) else None,
                         temperature=case.plate.temperature,
                         entry_strain=case.plate.mean_entry_strain,
                         carries_strain=flow.depends_on_strain,
                         thermal=(case.material.thermal_properties(),
                                  case.thermal.boundary(case.plate.temperature, t_profile),
                                  case.thermal.mesh_refinement)
                         if case.thermal else None,
                         strain_profile=e_profile,
                         v_reg_per_speed=None if case.friction.v_reg is not None
                         else case.friction.regularisation_velocity(1.0),
                         strip_elasticity=case.strip_elasticity)
    if not case.roll_gap().symmetric:
        model = replace(model, gap=gap_rolls(case, material.m))
    elif case.roll.model != "rigid":
        shaped, roll = FlatteningRoll.start(
            rp, case.roll.model, RollElasticity(case.roll.youngs_modulus, case.roll.poissons_ratio),
            case.roll.relaxation, tie=EXIT_TIE * rp.half_exit)
        model = replace(model, rp=shaped, roll=roll)
    settings = TransientSettings(
        dt=case.dt, end_time=end_time, nonlinear=sv.nonlinear, tol=sv.tolerance,
        max_it=sv.max_iterations or 20, steady_tol=sv.steady_tolerance, max_steps=sv.max_steps,
        wall_time_limit=sv.wall_time_limit, checkpoint_every=sv.checkpoint_every,
        contact_tol=contact_tolerance(rp, case.dt),
        a_f=case.friction.a_f_rule,
        a_f_max=case.friction.a_f_max, free_surface=case.plate.free_surface)
    return model, settings


def steady_settings(case: Case):
    """Settings of the direct steady solver (same a_f rule, tolerance and free-surface model)."""
    sv = case.solver
    return SteadySettings(
        tol=sv.tolerance, max_it=stage_iterations(sv.max_iterations),
        a_f=case.friction.a_f_rule,
        a_f_max=case.friction.a_f_max, upstream=sv.steady_entry_length,
        downstream=sv.steady_exit_length, free_surface=case.plate.free_surface,
        contact=case.contact.resolved(sv.method), unilateral=case.contact.resolved_unilateral(sv.method),
        roll_tol=case.roll.tolerance)


def contact_tolerance(rp, dt: float) -> float:
    """Distance below which a node is in contact (3.9): the report's 1e-5 m (for R = 0.6 m),
    scaled with R, and at least 6 times the drift (U dt)^2 / 2R that explicit steps along the
    arc accumulate between two projections (10 steps); the drift bound is what matters on
    meshes coarser than Table 2's (for C1..F2 at the report's speeds the 1e-5 m governs).
    """
    drift = 10 * (rp.u_roll * dt) ** 2 / (2 * rp.radius)
    return max(1e-5 * rp.radius / 0.6, 6 * drift)
