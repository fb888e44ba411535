"""A solved full-thickness strip (``solvers/full_steady.FullSteadyRun``: an asymmetric pass
between two rolls, issue 52) as a ``Solution`` record (``model/solution.py``), what the
results layer reads; the half model's is ``solvers/record.py``.

What it holds, against the half model's record:
- ``contacts``: two ``RollContact``, the upper roll's then the lower's, each with its roll's
  arc (``RollGap.arc``) and its contact profile (``FullSteadyRun.side_profile``) in that
  roll's own frame: the upper's is the full strip's frame, the lower's has y mirrored (y up
  from the exit mid-plane towards the lower roll, its normal and shear stresses and slips as
  the upper's would be), so that one reading serves both rolls;
- ``tops``: the two free surfaces (upper, lower), each in its roll's own frame as above;
- ``fields``: the vertex fields over the whole (full-thickness) mesh, in the full frame (y > 0
  towards the upper roll), ``contact_edges`` the upper's then the lower's;
- ``quantities``: the means over the deformation zone, from the earlier of the two contact
  starts to the roll gap, over the whole thickness;
- ``exit_profile``: None (the outlet's profile through the half thickness is the half
  model's; the full strip's through its whole thickness is not written yet);
  ``exit_strain``: the exit strip's mean strain over its whole thickness, as the half model's.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from hotroll.fem import quantities as Q
from hotroll.model.solution import PassData, RollContact, Solution
from hotroll.solvers.record import exit_strain, solve_stats
from hotroll.solvers.record_fields import gap_means, vertex_fields, write_vtk

SIDES = (1, -1)


def solution_record(run, frame_shift: float = 0.0) -> Solution:
    """The ``Solution`` of a solved ``FullSteadyRun`` (``run.state`` with its fields and
    figures); ``frame_shift`` (m): the solver's frame (the roll axes at x = 0) to the case's."""
    pb, thermal = run.problem, run.thermal
    K = pb.material.K
    # with a temperature: each contact's and free surface's temperature (K) and the contact's
    # heat flux to its roll (W/m^2), from the vertex fields (``contact_columns``)
    columns = thermal.contact_columns() if thermal is not None else None
    top_columns = {"temperature": columns["temperature"]} if columns else None
    profiles = {s: run.side_profile(s, K, columns) for s in SIDES}
    starts = [float(p["x"][0]) for p in profiles.values() if len(p["x"])]
    x_start = min(starts) if starts else min(rp.x_touch for rp in run.rolls.values())
    fields = vertex_fields(run)
    edges = tuple(np.stack([top.ea[rows], top.eb[rows]], -1)
                  for top in (run.tops[s] for s in SIDES)
                  for rows in (np.nonzero(top.edge_contact)[0],))
    return replace(
        run.state, time_stepping=False, window=run.window, frame_shift=frame_shift,
        pass_data=PassData(h=pb.h, K=K, m=pb.material.m, entry_strain=pb.entry_strain,
                           temperature=pb.temperature),
        contacts=tuple(side_contact(run, s, profiles[s]) for s in SIDES),
        tops=tuple(Q.top_profile(run.form, run.tops[s], run.d, top_columns) for s in SIDES),
        fields=replace(fields, contact_edges=edges),
        thermal_strip=thermal.strip_fields() if thermal is not None else None,
        quantities=gap_means(run.form, pb.rp, x_start, K),
        exit_profile=None, exit_strain=exit_strain(run),
        solve_stats=solve_stats(run), dofs=run.form.fes.ndof, nonlinear="newton",
        write_vtk=lambda path, shift=0.0: write_vtk(run, path, shift=shift))


def side_contact(run, side: int, prof: dict) -> RollContact:
    """The contact of the roll on ``side`` (+1 upper, -1 lower): its arc, its profile ``prof``
    (own frame, SI), the exact contact's multiplier, its unilateral end and that end's range
    (m, own frame), the pressure's last Newton change (Pa; the update is over the slower
    roll's speed, the one the form's bounds take)."""
    rp, form = run.rolls[side], run.form
    unilateral = bool(run.unilateral)
    u_ref = min(r.u_roll for r in run.rolls.values())
    return RollContact(
        rp=rp, profile=prof, method=form.contact, exact=bool(form.exact),
        unilateral=unilateral,
        end_x=float(run.shapes[side].end(rp)) if unilateral else None,
        end_bounds=tuple(float(b) for b in run.map.end_bounds(side)) if unilateral else None,
        pressure_last_update=(run.result.stats[-1].multiplier_update * u_ref * form.lam_scale
                              * run.problem.material.K) if form.exact else None)
