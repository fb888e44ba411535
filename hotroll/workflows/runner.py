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

from hotroll.config.case import Case, flat
from hotroll.results.outcome import CONSERVATION_TOL, conservation_problem, exit_code, leak_to_slip  # noqa: F401 (API)
from hotroll.results.output import (
    write_text,
)
from hotroll.results.run_dir import RunDir
from hotroll.results.run_summary import write_results
from hotroll.solvers.full_steady import FullSteadyRun
from hotroll.solvers.record_full import solution_record as full_record
from hotroll.solvers.settling import default_end_time  # noqa: F401  (runner's API)
from hotroll.solvers.steady import SteadyRun
from hotroll.solvers.threads import parallel, solver_threads, threads_used
from hotroll.solvers.transient import TransientRun
from hotroll.workflows.build import (  # noqa: F401  (runner's API)
    build_model,
    contact_tolerance,
    reference_material,
    steady_settings,
)
from hotroll.workflows.estimate import check
from hotroll.workflows.gauge import run_gap_case
from hotroll.workflows.spread import solve_spread

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
             progress: Callable[[dict], None] | None = None, sweep=None,
             mass_flux: tuple[float, float] | None = None) -> dict:
    """Run one case and write summary.json, contact.csv, top.csv, history.csv, fields, figures.

    ``sweep`` (an ``app.sweep.Sweep``): a steady case starts from the nearest case the sweep
    has solved on the same mesh (``warm_start_from`` in the summary). ``mass_flux`` (steady
    only): (inlet flux m^2/s of the half strip, relative tolerance) of a tandem stand whose
    roll speed the solve finds (``solvers/couplings.TandemSpeed``); the case's speed is the
    start, the speed found is written (case.toml, summary.json). An asymmetric pass (two
    rolls that differ, ``Problem.gap``) runs the full-thickness strip
    (``solvers/full_steady.FullSteadyRun``, its record ``solvers/record_full.py``)."""
    if case.pass_.roll_gap is not None:      # the exit thickness follows from the gap
        return run_gap_case(case, Path(out), run_case, progress=progress, sweep=sweep)
    est = check(case)                     # ResourceError before anything is written or meshed
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    write_text(out / "case.toml", case.to_toml())
    ckpt = out / "checkpoint"
    if not resume and (ckpt / "state.npz").exists():
        (ckpt / "state.npz").unlink()
    # the run's thread count ([solver] threads, set here; the solves' own calls are nested
    # no-ops): the meshing and set-up, each Newton step and the measures are parallel regions
    # with up to that many threads where no other process wants the cores
    # (fem/reproducible.parallel); the code between them is serial
    with solver_threads(case.solver.threads):
        t0 = time.perf_counter()
        with parallel():              # meshing and the forms' set-up: one parallel region
            model, settings = build_model(case)
        extra = {"estimated_dofs": est.dofs, "estimated_memory": est.memory_bytes,
                 "estimated_seconds": est.seconds, "warnings": case.warnings()}
        shift, spread = 0.0, None
        if case.solver.method == "steady":
            # solved in the roll's frame (axis at x = 0), written where the case puts the axis:
            # the numbers do not depend on roll_axis_x (issue 30)
            shift = model.rp.axis_x
            model = replace(model, rp=replace(model.rp, axis_x=0.0))
            near = warm = None
            if model.gap is not None:
                # an asymmetric pass: the full-thickness strip between its two rolls (each
                # in its own frame, their axes at x = 0); a sweep's neighbour on the same mesh
                # (a study over the speed ratio, say) starts it warm
                gap = model.gap.at_axis(0.0)
                run = FullSteadyRun(model, steady_settings(case), case.plate.length,
                                    gap.rolls, gap.frictions, gap.a_f, gap.roll_models)
                if sweep is not None:
                    run.record = sweep.history
                    near, warm = sweep.nearest(case, run)
            elif sweep is None:
                run = SteadyRun(model, steady_settings(case), case.plate.length)
            else:
                run = sweep.steady_run(case, model)
                near, warm = sweep.nearest(case, run)
            run.mass_flux = mass_flux
            run.run(progress, warm=warm)
            if case.spread is not None and run.state.status == "steady":
                spread = solve_spread(case, run, progress)   # the 3D pass across the width
            omega = run.problem.rp.omega
            if model.gap is None and omega != case.pass_.roll_angular_velocity:      # a tandem speed found in the solve
                case = case.with_overrides(**{"pass.roll_angular_velocity": omega})
                write_text(out / "case.toml", case.to_toml())
            if sweep is not None:
                sweep.add(case, run)
            extra["warm_start_from"] = near
            extra["warm_start_failed"] = bool(run.result.warm_failed)
        else:
            run = TransientRun(model, settings, checkpoint_dir=ckpt, fingerprint=fingerprint(case))
            run.run(progress)
        extra["solver_threads"] = threads_used()
        wall = time.perf_counter() - t0
        with parallel():              # the measures: one parallel region (fem/reproducible)
            # the solved pass as data (solvers/record.py): all the results read
            record = (full_record(run, frame_shift=shift) if model.gap is not None
                      else run.solution_record(frame_shift=shift))
            record.spread = spread
            summary = write_results(case, record, out, wall, extra)
    if case.output.figures:
        from hotroll.results.figures import plot_all  # matplotlib only when drawing

        plot_all(out)
    return summary


