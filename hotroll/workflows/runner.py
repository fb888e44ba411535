"""From a validated case to results on disk: case -> model -> solver -> fields -> files.

Scalar results in ``summary.json`` are means over the last steady-state window (the report's
histories oscillate periodically with the discrete entry/exit of contact nodes), leaving out
steps whose nonlinear solve stopped unconverged; profiles and fields are those of the last step.
"""
from __future__ import annotations

import hashlib
import time
from dataclasses import replace
from pathlib import Path
from typing import Callable

from hotroll.config.case import Case, CaseError, flat
from hotroll.fem.mesh import MeshSpec, plate_fine_length
from hotroll.model.material import NortonHoff
from hotroll.model.roll_elastic import FlatteningRoll, RollElasticity
from hotroll.results.figures import plot_all
from hotroll.results.outcome import CONSERVATION_TOL, conservation_problem, exit_code, leak_to_slip  # noqa: F401 (API)
from hotroll.results.output import (
    write_text,
)
from hotroll.results.run_dir import RunDir
from hotroll.results.run_summary import write_results
from hotroll.solvers.problem import Problem
from hotroll.solvers.settling import default_end_time  # noqa: F401  (runner's API)
from hotroll.solvers.steady import SteadyRun
from hotroll.solvers.steady_settings import SteadySettings
from hotroll.solvers.transient import TransientRun, TransientSettings
from hotroll.workflows.estimate import check


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


def build_model(case: Case):
    """Translate the case description into the solver's model and settings."""
    sv = case.solver
    rp = case.pass_.roll_pass()
    h = case.mesh.h
    end_time = sv.end_time or default_end_time(rp)
    spec = MeshSpec(h=h, fine_length=plate_fine_length(rp, h, end_time),
                    h_far=case.mesh.h_far, grading=case.mesh.grading)
    material, flow = reference_material(case)
    t_profile, e_profile = case.plate.entry_profiles()
    model = Problem(rp, case.plate.length, material,
                         case.friction.law_object(rp.u_roll, material.m), spec,
                         back_tension=case.pass_.back_tension,
                         front_tension=case.pass_.front_tension,
                         flow_stress=flow if flow.depends_on_strain or case.thermal else None,
                         temperature=case.plate.temperature,
                         entry_strain=case.plate.mean_entry_strain,
                         carries_strain=flow.depends_on_strain,
                         thermal=(case.material.thermal_properties(),
                                  case.thermal.boundary(case.plate.temperature, t_profile),
                                  case.thermal.mesh_refinement)
                         if case.thermal else None,
                         strain_profile=e_profile)
    if case.roll.model != "rigid":
        shaped, roll = FlatteningRoll.start(
            rp, case.roll.model, RollElasticity(case.roll.youngs_modulus, case.roll.poissons_ratio),
            case.roll.relaxation)
        model = replace(model, rp=shaped, roll=roll)
    settings = TransientSettings(
        dt=case.dt, end_time=end_time, nonlinear=sv.nonlinear, tol=sv.tolerance,
        max_it=sv.max_iterations, steady_tol=sv.steady_tolerance, max_steps=sv.max_steps,
        wall_time_limit=sv.wall_time_limit, checkpoint_every=sv.checkpoint_every,
        contact_tol=contact_tolerance(rp, case.dt),
        a_f=case.friction.a_f_rule,
        a_f_max=case.friction.a_f_max, free_surface=case.plate.free_surface)
    return model, settings


def steady_settings(case: Case):
    """Settings of the direct steady solver (same a_f rule, tolerance and free-surface model)."""
    sv = case.solver
    return SteadySettings(
        tol=sv.tolerance, max_it=max(sv.max_iterations, 30),
        a_f=case.friction.a_f_rule,
        a_f_max=case.friction.a_f_max, upstream=sv.steady_entry_length,
        downstream=sv.steady_exit_length, free_surface=case.plate.free_surface,
        contact=case.contact.resolved(sv.method), unilateral=case.contact.unilateral,
        roll_tol=case.roll.tolerance)


def contact_tolerance(rp, dt: float) -> float:
    """Distance below which a node is in contact (3.9): the report's 1e-5 m (for R = 0.6 m),
    scaled with R, and at least 6 times the drift (U dt)^2 / 2R that explicit steps along the
    arc accumulate between two projections (10 steps); the drift bound is what matters on
    meshes coarser than Table 2's (for C1..F2 at the report's speeds the 1e-5 m governs).
    """
    drift = 10 * (rp.u_roll * dt) ** 2 / (2 * rp.radius)
    return max(1e-5 * rp.radius / 0.6, 6 * drift)


#: Solver keys that do not change the computed fields (a run may resume with other values).
_NOT_PHYSICS = ("wall_time_limit", "threads", "checkpoint_every", "memory_limit", "force")


def fingerprint(case: Case) -> str:
    """Hash of everything that determines the fields (not output, threads, limits)."""
    d = case.to_dict()
    d.pop("output", None)
    for key in _NOT_PHYSICS:
        d.get("solver", {}).pop(key, None)
    return hashlib.sha256(repr(sorted(flat(d).items())).encode()).hexdigest()[:16]


def finished_summary(case: Case, out: Path) -> dict | None:
    """The summary of a run of this very case (``out/case.toml`` the same text) that wrote
    ``out/summary.json``, else None: the finished run a schedule or a study reads back."""
    return RunDir(out).finished_summary(case.to_toml())


def run_case(case: Case, out: Path, *, resume: bool = True,
             progress: Callable[[dict], None] | None = None, sweep=None) -> dict:
    """Run one case and write summary.json, contact.csv, top.csv, history.csv, fields, figures.

    ``sweep`` (an ``app.sweep.Sweep``): a steady case starts from the nearest case the sweep
    has solved on the same mesh (``warm_start_from`` in the summary)."""
    import ngsolve

    est = check(case)                     # ResourceError before anything is written or meshed
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    ngsolve.SetNumThreads(case.solver.threads)
    write_text(out / "case.toml", case.to_toml())
    ckpt = out / "checkpoint"
    if not resume and (ckpt / "state.npz").exists():
        (ckpt / "state.npz").unlink()
    t0 = time.perf_counter()
    model, settings = build_model(case)
    extra = {"estimated_dofs": est.dofs, "estimated_memory": est.memory_bytes,
             "estimated_seconds": est.seconds}
    shift = 0.0
    if case.solver.method == "steady":
        # solved in the roll's frame (axis at x = 0), written where the case puts the axis:
        # the numbers do not depend on roll_axis_x (issue 30)
        shift = model.rp.axis_x
        model = replace(model, rp=replace(model.rp, axis_x=0.0))
        near = warm = None
        if sweep is None:
            run = SteadyRun(model, steady_settings(case), case.plate.length)
        else:
            run = sweep.steady_run(case, model)
            near, warm = sweep.nearest(case, run)
        run.run(progress, warm=warm)
        if sweep is not None:
            sweep.add(case, run)
        extra["warm_start_from"] = near
        extra["warm_start_failed"] = bool(run.result.warm_failed)
    else:
        run = TransientRun(model, settings, checkpoint_dir=ckpt, fingerprint=fingerprint(case))
        run.run(progress)
    run.frame_shift = shift
    wall = time.perf_counter() - t0
    summary = write_results(case, run, out, wall, extra)
    if case.output.figures:
        plot_all(out)
    return summary


