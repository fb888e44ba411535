"""The fields of a solved run for its ``Solution`` record (``solvers/record.py``): the vertex
fields (``VertexFields``), the ParaView writer, the means over the roll gap and the outlet's
profiles through the half thickness. These read the FE objects (NGSolve), which is why they sit
in solvers/ and not in results/ (issue 52, stage 1).

The outlet's profiles (issue 17: what a pass hands on) are measured where the steady model
ends, on its outlet section, where the strip moves rigidly:
- temperature: the thermal strip mesh's last column (its rows, dense at the surface, are the
  eta grid), K;
- strain: the strain field at the same eta (the mechanics' P1 field), -;
- eta = y / half thickness, 0 centre line, 1 surface;
- along the streamline ending there (issue 33; thermal runs): the pass strain, and the
  strain-weighted means of ln(edot) (edot in 1/s) and of 1/T (1/K) that the recrystallisation
  kinetics' Zener-Hollomon parameter takes (``solvers/streamlines.py``).
A steady run without a strain field (a law independent of the strain) and without [thermal]
has no profile (None).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from hotroll.fem.forms import strain_rate
from hotroll.fem.mesh import mesh_triangles
from hotroll.fem.quantities import p1_space
from hotroll.fem.reproducible import find_points, integrate
from hotroll.files import atomic
from hotroll.model.material import edot_squared
from hotroll.model.solution import VertexFields
from hotroll.solvers.streamlines import streamline_means

#: eta grid of the strain profile in an isothermal run (no thermal strip mesh).
ISOTHERMAL_ROWS = 21


def vertex_fields(run) -> VertexFields:
    """Deformed vertices, triangles and vertex values of v, p, edot, strain, temperature (the
    coupled field at the vertex, or the plate's uniform one), flow_temperature (the one the
    flow stress takes: the mechanics elements' means, solvers/thermal_coupling.py) and sigma_ef (the
    flow stress at that strain, rate and flow temperature); the roll's contact edges; SI
    units."""
    import ngsolve

    mesh, form, K = run.mesh, run.form, run.problem.material.K
    nv = mesh.nv
    ns = form.fes.components[0].ndof // 2
    sol = form.nonlinear.gf.vec.FV().NumPy()
    pts = run.top.X0 + np.stack([run.d[:nv], run.d[ns:ns + nv]], -1)
    tris = mesh_triangles(mesh)
    vel = np.stack([sol[:nv], sol[ns:ns + nv]], -1)
    pressure = K * form.nonlinear.pressure.vec.FV().NumPy()[:nv]
    g = ngsolve.GridFunction(p1_space(mesh))
    g.Set(ngsolve.sqrt(edot_squared(strain_rate(form.nonlinear.velocity)) + 1e-300))
    edot = np.maximum(g.vec.FV().NumPy()[:nv].copy(), 0.0)
    rows = np.nonzero(run.top.edge_contact)[0]
    model, field = run.problem, getattr(run, "strain", None)
    strain = (field.values[:nv].copy() if field is not None
              else np.full(nv, model.entry_strain))
    thermal = getattr(run, "thermal", None)
    temperature, flow_T = ((thermal.vertex_temperature(), thermal.flow_temperature())
                           if thermal is not None else (np.full(nv, model.temperature),) * 2)
    sigma = (model.flow_stress.sigma(strain, edot, flow_T)
             if model.flow_stress is not None else model.material.sigma_ef(edot))
    return VertexFields(
        points=pts, triangles=tris, v=vel, pressure=pressure, edot=edot, strain=strain,
        sigma_ef=np.asarray(sigma), temperature=temperature, flow_temperature=flow_T,
        contact_edges=(np.stack([run.top.ea[rows], run.top.eb[rows]], -1),))


def write_vtk(run, path: Path, shift: float = 0.0) -> Path:
    """ParaView file (.vtu) of velocity, pressure, strain rate, sigma_ef (and the strain, the
    temperature) on the deformed plate; with a temperature, also thermal.vtu, the field on its
    own strip mesh; both moved by ``shift`` in x (the roll's frame to the case's)."""
    if shift:
        thermal = getattr(run, "thermal", None)
        strip = getattr(thermal, "strip", None)
        nv = run.mesh.nv
        run.d[:nv] += shift            # vertex DOFs of the x displacement (bubbles unmoved)
        if strip is not None:
            strip.disp.vec.FV().NumPy()[: strip.nv] += shift
        try:
            run.mesh.SetDeformation(run.disp)
            if strip is not None:
                strip.mesh.SetDeformation(strip.disp)
            return write_vtk(run, path)
        finally:
            run.d[:nv] -= shift
            run.mesh.SetDeformation(run.disp)
            if strip is not None:
                strip.disp.vec.FV().NumPy()[: strip.nv] -= shift
                strip.mesh.SetDeformation(strip.disp)
    import ngsolve

    form, K = run.form, run.problem.material.K
    edot = ngsolve.sqrt(edot_squared(strain_rate(form.nonlinear.velocity)) + 1e-300)
    m = run.problem.material.m
    coefs = [form.nonlinear.velocity, K * form.nonlinear.pressure, edot,
             K * form.consistency * 3.0 ** ((m + 1) / 2) * edot**m]
    names = ["velocity", "pressure", "edot", "sigma_ef"]
    if getattr(run, "strain", None) is not None:
        coefs.append(run.strain.gf)
        names.append("strain")
    thermal = getattr(run, "thermal", None)
    if thermal is not None:
        coefs.append(thermal.T)
        names.append("temperature")
    with atomic(Path(path).with_suffix(".vtu")) as tmp:      # NGSolve appends .vtu
        ngsolve.VTKOutput(run.mesh, coefs=coefs, names=names,
                          filename=str(tmp.with_suffix("")), subdivision=1).Do()
    if getattr(thermal, "strip", None) is not None:    # the temperature's own strip mesh
        with atomic(Path(path).with_name("thermal.vtu")) as tmp:
            ngsolve.VTKOutput(thermal.strip.mesh, coefs=[thermal.field.gf],
                              names=["temperature"], filename=str(tmp.with_suffix("")),
                              subdivision=0).Do()
    return Path(path).with_suffix(".vtu")


def gap_means(form, rp, x_start: float, K: float) -> dict:
    """Volume means over the deformation zone (the strip between the contact start x_start and
    the roll gap X_roll): the flow stress sigma_ef (Pa) and the equivalent strain rate (1/s)."""
    from ngsolve import IfPos, sqrt, x

    band = IfPos(x - x_start, IfPos(rp.axis_x - x, 1.0, 0.0), 0.0)
    area = integrate(band, form.mesh)
    if not area > 0:
        return {"mean_flow_stress": math.nan, "mean_strain_rate": math.nan}
    e2 = edot_squared(strain_rate(form.nonlinear.velocity))
    sigma = form.material.sigma_ef_reg(e2, m=form.m_material, K=form.consistency)
    return {"mean_flow_stress": K * integrate(band * sigma, form.mesh) / area,
            "mean_strain_rate": integrate(band * sqrt(e2 + 1e-300), form.mesh) / area}


def exit_profiles(run) -> dict | None:
    """{"eta": [...], "temperature": [...] or None, "strain": [...] or None, and the
    streamlines' "pass_strain", "log_rate_mean", "inverse_temperature_mean" or None} at the
    outlet of a steady run (``solvers.steady.SteadyRun``); None if it carries neither field,
    and for the report's scheme."""
    thermal, strain = getattr(run, "thermal", None), getattr(run, "strain", None)
    if (thermal is None and strain is None) or run.time_stepping:
        return None
    if thermal is not None:
        strip = thermal.strip
        eta = np.asarray(strip.eta, dtype=float)
        temperature = thermal.field.values.reshape(strip.shape)[:, -1].copy()
    else:
        eta, temperature = np.linspace(0.0, 1.0, ISOTHERMAL_ROWS), None
    out = {"eta": eta.tolist(),
           "temperature": None if temperature is None else temperature.tolist(),
           "strain": None, "pass_strain": None, "log_rate_mean": None,
           "inverse_temperature_mean": None}
    if strain is not None:
        out["strain"] = outlet_values(run, (strain.gf,), eta)[0].tolist()
    if thermal is not None:
        means = streamline_means(thermal, eta)
        out.update({k: means[k].tolist() for k in ("pass_strain", "log_rate_mean",
                                                   "inverse_temperature_mean")})
    return out


def outlet_values(run, fields, eta: np.ndarray) -> list[np.ndarray]:
    """The fields at eta on the outlet section, eta = y over the reference top's height
    there (0 to 1 the half strip, -1 to 1 the full strip's whole thickness), searched in the
    undeformed mesh (NGSolve's point search ignores the deformation) and evaluated on the
    deformed one."""
    top = run.top
    ref = top.X0[top.verts]
    order = np.argsort(ref[:, 0])
    xs, ys = ref[order, 0], ref[order, 1]
    x = xs[-1] - 1e-6 * (xs[-1] - xs[0])            # just inside the outlet face
    y = eta * np.interp(x, xs, ys) * (1.0 - 1e-9)
    mesh = run.mesh
    mesh.UnsetDeformation()
    try:
        pts = find_points(mesh, np.full_like(y, x), y)
    finally:
        mesh.SetDeformation(run.disp)
    return [np.asarray(f(pts), dtype=float).reshape(-1) for f in fields]
