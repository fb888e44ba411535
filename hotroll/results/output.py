"""Writing results: atomic JSON/CSV/NPZ files and ParaView (VTK) output of the fields."""
from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from hotroll.fem.forms import strain_rate
from hotroll.fem.mesh import mesh_triangles
from hotroll.fem.quantities import p1_space
from hotroll.files import DiskFullError, atomic, disk_full  # noqa: F401  (the app's writers use them)
from hotroll.model.material import edot_squared


def _atomic_write_text(path: Path, text: str) -> None:
    with atomic(path) as tmp:
        with open(tmp, "w") as f:
            f.write(text)


def _clean(v):
    if isinstance(v, (np.floating, float)):
        return float(v) if math.isfinite(v) else None
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.bool_,)):
        return bool(v)
    if isinstance(v, (list, tuple, np.ndarray)):
        return [_clean(x) for x in v]
    if isinstance(v, Mapping):       # a dict or a typed Summary
        return {k: _clean(x) for k, x in v.items()}
    return v


def write_json(path: Path, data: dict) -> None:
    """JSON with NaN/inf written as null."""
    _atomic_write_text(Path(path), json.dumps(_clean(data), indent=2) + "\n")


def write_csv(path: Path, columns: dict[str, np.ndarray] | list[dict]) -> None:
    """A CSV with a header line, from column arrays or from a list of row dicts."""
    if isinstance(columns, list):
        keys = list(columns[0].keys()) if columns else []
        rows = [[r.get(k) for k in keys] for r in columns]
    else:
        keys = list(columns.keys())
        rows = list(zip(*[np.asarray(columns[k]).tolist() for k in keys]))
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(keys)
    for r in rows:
        w.writerow(["" if x is None else (repr(float(x)) if isinstance(x, float) else x)
                    for x in r])
    _atomic_write_text(Path(path), buf.getvalue())


def write_npz(path: Path, **arrays) -> None:
    with atomic(Path(path)) as tmp:
        np.savez_compressed(tmp, **arrays)


def write_text(path: Path, text: str) -> None:
    """A text file, atomically (``atomic``)."""
    _atomic_write_text(Path(path), text)


def vertex_fields(run) -> dict:
    """Deformed vertices, triangles and vertex values of v, p, edot, strain, temperature (the
    coupled field at the vertex, or the plate's uniform one), flow_temperature (the one the
    flow stress takes: the mechanics elements' means, solvers/thermal_coupling.py) and sigma_ef (the
    flow stress at that strain, rate and flow temperature); SI units."""
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
    return {
        "points": pts, "triangles": tris, "v": vel, "pressure": pressure, "edot": edot,
        "strain": strain, "sigma_ef": np.asarray(sigma), "temperature": temperature,
        "flow_temperature": flow_T,
        "contact_edges": np.stack([run.top.ea[rows], run.top.eb[rows]], -1),
        "roll_centre": np.array(run.problem.rp.centre), "roll_radius": run.problem.rp.radius,
    }


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
