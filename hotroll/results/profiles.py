"""The exit strip's state through its half thickness (issue 17): what a pass hands on.

Measured where the steady model ends, on its outlet section, where the strip moves rigidly:
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

import numpy as np

from hotroll.fem.reproducible import find_points
from hotroll.solvers.streamlines import streamline_means

#: eta grid of the strain profile in an isothermal run (no thermal strip mesh).
ISOTHERMAL_ROWS = 21


def exit_profiles(run) -> dict | None:
    """{"eta": [...], "temperature": [...] or None, "strain": [...] or None} at the outlet of a
    steady run (``algorithms.steady.SteadyRun``); None if it carries neither field."""
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
        out["strain"] = _outlet(run, (strain.gf,), eta)[0].tolist()
    if thermal is not None:
        means = streamline_means(thermal, eta)
        out.update({k: means[k].tolist() for k in ("pass_strain", "log_rate_mean",
                                                   "inverse_temperature_mean")})
    return out


def _outlet(run, fields, eta: np.ndarray) -> list[np.ndarray]:
    """The fields at eta on the outlet section (searched in the undeformed mesh, as
    NGSolve's point search ignores the deformation, and evaluated on the deformed one)."""
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
