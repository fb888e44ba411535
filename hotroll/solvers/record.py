"""A solved run as a ``Solution`` record (``model/solution.py``; issue 52, stage 1): everything
the results layer reads, taken off the live FE and solver objects here, so that ``results/``
needs neither. ``SteadyRun`` and ``TransientRun`` call ``solution_record`` from their own
``solution_record``. The vertex fields, the ParaView writer, the gap means and the outlet's
profiles are measured in ``solvers/record_fields.py``."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from hotroll.fem import quantities as Q
from hotroll.model.solution import PassData, RollContact, Solution
from hotroll.solvers.contact_end import surface_overlap
from hotroll.solvers.record_fields import exit_profiles, gap_means, vertex_fields, write_vtk


def solution_record(run, frame_shift: float = 0.0) -> Solution:
    """The ``Solution`` of a solved ``SteadyRun`` or ``TransientRun`` (``run.state`` with its
    fields and figures); ``frame_shift`` (m): the solver's frame to the case's."""
    pb, thermal = run.problem, getattr(run, "thermal", None)
    K = pb.material.K
    columns = thermal.contact_columns() if thermal is not None else None
    prof = Q.contact_profile(run.form, run.top, run.d, K, columns)
    top_columns = {"temperature": columns["temperature"]} if columns else None
    x_start = float(prof["x"][0]) if len(prof["x"]) else pb.rp.x_touch
    return replace(
        run.state, time_stepping=run.time_stepping, window=run.window, frame_shift=frame_shift,
        pass_data=PassData(h=pb.h, K=K, m=pb.material.m, entry_strain=pb.entry_strain,
                           temperature=pb.temperature),
        contacts=(roll_contact(run, prof),),
        tops=(Q.top_profile(run.form, run.top, run.d, top_columns),),
        fields=vertex_fields(run),
        thermal_strip=thermal.strip_fields() if thermal is not None else None,
        quantities=gap_means(run.form, pb.rp, x_start, K),
        exit_profile=exit_profiles(run), exit_strain=exit_strain(run),
        solve_stats=solve_stats(run), dofs=run.form.fes.ndof,
        nonlinear=run.s.nonlinear if run.time_stepping else "newton",
        write_vtk=lambda path, shift=0.0: write_vtk(run, path, shift=shift))


def roll_contact(run, prof: dict) -> RollContact:
    """The roll's contact: its profile ``prof`` (``Q.contact_profile``, SI) and how it is
    held (method, unilateral end, the pressure's last Newton change, a flattening roll's
    figures)."""
    pb, form = run.problem, run.form
    steady_exact = not run.time_stepping and form.exact
    unilateral = bool(getattr(run, "unilateral", False))
    roll = pb.roll
    return RollContact(
        rp=pb.rp, profile=prof, method=form.contact, exact=bool(form.exact),
        unilateral=unilateral,
        end_x=float(run.shape.end(pb.rp)) if unilateral else None,
        end_bounds=tuple(float(b) for b in run.end_bounds()) if unilateral else None,
        # exact contact: what the pressure still moved in the last Newton step (Pa; sticking
        # zones, fem/nonlinear.py)
        pressure_last_update=(run.result.stats[-1].multiplier_update * pb.rp.u_roll
                              * form.lam_scale * pb.material.K) if steady_exact else None,
        flattening=roll is not None,
        roll_updates=roll.updates if roll is not None else None,
        roll_last_move=roll.last_move if roll is not None else None,
        roll_shape_error=shape_error(roll, prof) if roll is not None else None,
        overlap=(None if run.time_stepping else
                 surface_overlap(run.top, run.d, pb.rp, float(run.shape.end(pb.rp)), 0.0)[0]))


def shape_error(roll, prof: dict) -> float:
    """How far the roll's surface lies from the one its final tractions give (the elastic
    disc's rim, or Hitchcock's circle): max |w - w(p, q)| over the contact's angles, over
    max |w(p, q)| there (-). Checks the fixed point at the end, not only its last move."""
    ang = np.asarray(prof["angle"], dtype=float)
    if len(ang) < 2:
        return math.nan
    order = np.argsort(ang)
    grid, w, _ = roll.target(ang[order], -np.asarray(prof["normal_stress"])[order],
                             np.asarray(prof["shear_stress"])[order])
    inside = (grid >= ang.min()) & (grid <= ang.max())
    scale = float(np.max(np.abs(w[inside]), initial=0.0))
    if not scale > 0.0:
        return math.nan
    return float(np.max(np.abs(roll.shape.offset(grid[inside]) - w[inside]))) / scale


def exit_strain(run) -> float | None:
    """Mean strain of the exit strip (None without a strain field): steady strip, x in
    X_roll + [0.25, 0.75] D with D = max(l_c, 2 h1) (the downstream length, where it is
    rigid); report's scheme, the material past X_roll + 2h that was ahead of the bite at the
    start (it has crossed the whole arc; the head was in the gap from t = 0)."""
    field = getattr(run, "strain", None)
    if field is None:
        return None
    rp = run.problem.rp       # the run's frame (steady: the roll's, axis at 0)
    D = max(rp.contact_length, 4.0 * rp.half_exit)
    if run.time_stepping:
        nv = run.mesh.nv
        x_now = run.top.X0[:, 0] + run.d[:nv]
        mask = (x_now > rp.axis_x + 2.0 * run.problem.h) & (run.top.X0[:, 0] < rp.x_touch)
        return field.mean_where(mask) if mask.any() else float("nan")
    return field.mean_between(rp.axis_x + 0.25 * D, rp.axis_x + 0.75 * D)


def solve_stats(run) -> dict:
    """The solve's counts (``Solution.solve_stats``): the steady solver's Newton solves,
    coupling updates, whether the fixed point settled and the free top's last residual in
    contact mesh sizes (None without traced tops); the report's scheme's time step (s)."""
    if run.time_stepping:
        return {"dt": run.s.dt}
    r = run.result
    return {"newton_solves": len(r.stats),
            "coupling_updates": len(r.surface_moves or r.a_f_history),
            "fixed_point_settled": bool(r.settled),
            "surface_residual_h": float(r.surface_moves[-1] / run.problem.h)
            if r.surface_moves else None}
