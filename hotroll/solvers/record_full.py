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
- ``exit_profile``: the outlet's state through the whole thickness, eta = y / half exit
  thickness from -1 (the lower surface) to 1 (the upper), ``exit_profile``: the temperature
  (K, or None isothermal), the strain (-, or None without a strain field) and the shear strain
  gamma_xy (-, ``fem/strain.py: ShearStrainField``) and, with a temperature, the
  streamlines' histories (``solvers/streamlines.py``: pass strain, means of ln edot and 1/T,
  the microstructure's kinetics); ``exit_strain``: the exit strip's mean strain over its whole
  thickness.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from hotroll.fem import quantities as Q
from hotroll.model.solution import PassData, RollContact, Solution
from hotroll.solvers.record import exit_strain, shape_error, solve_stats
from hotroll.solvers.record_fields import ISOTHERMAL_ROWS, gap_means, outlet_values, vertex_fields, write_vtk
from hotroll.solvers.streamlines import streamline_means

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
        exit_profile=exit_profile(run), exit_strain=exit_strain(run),
        solve_stats=solve_stats(run), dofs=run.form.fes.ndof, nonlinear="newton",
        write_vtk=lambda path, shift=0.0: write_vtk(run, path, shift=shift))


def exit_profile(run) -> dict:
    """The outlet's temperature, strain and shear strain at eta in [-1, 1] (module docstring):
    eta the thermal strip's rows (thin at both surfaces) or, isothermal, evenly spaced; the
    fields sampled just inside the outlet face (``record_fields.outlet_values``)."""
    from hotroll.solvers.gap_measure import exit_shear

    thermal, strain = run.thermal, run.strain
    if thermal is not None:
        strip = thermal.strip
        eta = np.asarray(strip.eta, dtype=float)
        temperature = thermal.field.values.reshape(strip.shape)[:, -1].tolist()
    else:
        eta, temperature = np.linspace(-1.0, 1.0, 2 * ISOTHERMAL_ROWS - 1), None
    if getattr(run, "_shear_field", None) is None:
        exit_shear(run)                 # the shear field transported along the last flow
    fields = (run._shear_field.gf,) + ((strain.gf,) if strain is not None else ())
    values = outlet_values(run, fields, eta)
    out = {"eta": eta.tolist(), "temperature": temperature,
           "strain": values[1].tolist() if strain is not None else None,
           "shear_strain": values[0].tolist(),
           "pass_strain": None, "log_rate_mean": None, "inverse_temperature_mean": None}
    if thermal is not None:     # the streamlines' histories (the microstructure's kinetics)
        means = streamline_means(thermal, eta)
        out.update({k: means[k].tolist() for k in ("pass_strain", "log_rate_mean",
                                                   "inverse_temperature_mean")})
    return out


def side_contact(run, side: int, prof: dict) -> RollContact:
    """The contact of the roll on ``side`` (+1 upper, -1 lower): its arc, its profile ``prof``
    (own frame, SI), the exact contact's multiplier, its unilateral end and that end's range
    (m, own frame), the pressure's last Newton change (Pa; the update is over the slower
    roll's speed, the one the form's bounds take)."""
    rp, form = run.rolls[side], run.form
    unilateral = bool(run.unilateral)
    u_ref = min(r.u_roll for r in run.rolls.values())
    roll = run.flattening.get(side)          # a flattening roll (its own frame, as prof)
    return RollContact(
        rp=rp, profile=prof, method=form.contact, exact=bool(form.exact),
        unilateral=unilateral,
        end_x=float(run.shapes[side].end(rp)) if unilateral else None,
        end_bounds=tuple(float(b) for b in run.side_end_bounds(side)) if unilateral else None,
        pressure_last_update=(run.result.stats[-1].multiplier_update * u_ref * form.lam_scale
                              * run.problem.material.K) if form.exact else None,
        flattening=roll is not None,
        roll_updates=roll.updates if roll is not None else None,
        roll_last_move=roll.last_move if roll is not None else None,
        roll_shape_error=shape_error(roll, prof) if roll is not None else None,
        overlap=run.side_overlap(side)[0], wraps=side in run.wraps)
