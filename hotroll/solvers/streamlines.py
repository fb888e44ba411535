"""Histories along the steady strip's streamlines (issue 33; docs/theory.md 1g).

The recrystallisation kinetics need, on each streamline, the strain it gains in the pass and
the strain-weighted means of ln(edot) and 1/T, from which ln Z = <ln edot> + Q_def/R <1/T>.
A streamline is a line of constant flux fraction phi (the flux below it over the section's):
on each column of the thermal strip mesh (``fem/strip_mesh.py``: fine over the contact) its
height follows from the column's flux profile (``ThermalCoupling.fine_column_flux``, the
stream function's own data), and at the outlet, where the strip moves rigidly, phi = eta.
Along it, with the points' current positions x_i and speeds |v_i|, dt_i = |x_{i+1} - x_i| /
mean |v| and every integral is a trapezoid sum. The temperature is the strip mesh's own, not
the coarser mechanics mesh's. The full strip between two rolls (issue 52): eta from -1 (the
lower surface) to 1, phi the flux fraction from the lower surface, and at the outlet (whose
rigid motion may rotate with the curl) the outlet column's own phi(eta). Streamline means
from a transported field (SUPG) were tried
first and not kept: the Galerkin solution is not monotone, and on finishing_mill's first
pass the centre's mean temperature came out 4 K below the entry temperature (the centre only
heats).
"""
from __future__ import annotations

import numpy as np

from hotroll.fem.forms import strain_rate
from hotroll.model.material import edot_squared

#: Sample points per column interval of the thermal strip along a streamline.
SUB = 8


def streamline_means(thermal, eta: np.ndarray) -> dict[str, np.ndarray]:
    """At the outlet heights ``eta`` (flux fractions): the pass strain int edot dt, the
    strain-weighted means of ln(edot) (edot in 1/s) and of 1/T (1/K), along the streamline
    through each."""
    from ngsolve import CF, sqrt, x, y

    strip = thermal.strip
    eta = np.asarray(eta, dtype=float)
    flux = thermal.fine_column_flux()
    frac = flux / flux[-1]
    fine = thermal._fine
    ncol = len(strip.X)
    phi = np.interp(eta, fine, frac[:, -1]) if strip.full else eta
    path = np.empty((len(eta), ncol))
    for i in range(ncol):
        path[:, i] = np.interp(phi, frac[:, i], fine)
    # SUB points per column interval, straight between the columns in (X, eta): the rate is
    # a P2 velocity's gradient, discontinuous between elements; sampling it only on the
    # columns made the means depend on which side of an element edge a column fell (2 % in
    # strain between two runs that the exact scaling says are the same)
    w = np.arange(SUB) / SUB
    Xs = np.append(((1 - w)[None, :] * strip.X[:-1, None] +
                    w[None, :] * strip.X[1:, None]).ravel(), strip.X[-1])
    path = np.concatenate([((1 - w)[None, None, :] * path[:, :-1, None] +
                            w[None, None, :] * path[:, 1:, None]).reshape(len(eta), -1),
                           path[:, -1:]], axis=1)
    X = np.broadcast_to(Xs, path.shape)
    # inside the strip: a surface streamline's points 1e-3 of the thinnest row in from the
    # surface (on it, a point on a mechanics vertex is in two elements, where the rate jumps,
    # and the search's pick is not the mirror image's: the full strip's two surface
    # streamlines differed by 0.7 % in pass strain)
    inward = 1e-3 * float(np.min(np.diff(strip.eta)))
    path = np.clip(path, strip.eta[0] + inward, 1.0 - inward)
    ref = np.stack([X.ravel(), path.ravel() * strip.top_height(X.ravel())], -1)
    u = thermal.form.nonlinear.velocity
    rate = sqrt(edot_squared(strain_rate(u)) + 1e-300)
    vals = thermal._at(CF((x, y, u[0], u[1], rate)), thermal._find(ref))
    vals = vals.reshape(path.shape + (5,))
    # T on the strip's structured logical grid, linear in each cell (its P1 triangles up to
    # the cell's diagonal: O(h^2)); a point search on the strip mesh cost 4x this whole call
    T = bilinear(strip.eta, strip.X, thermal.field.values.reshape(strip.shape),
                 np.clip(path.ravel(), strip.eta[0], 1.0), X.ravel()).reshape(path.shape)
    pos, speed = vals[..., :2], np.hypot(vals[..., 2], vals[..., 3])
    edot = np.maximum(vals[..., 4], 1e-300)
    dt = np.hypot(*np.moveaxis(np.diff(pos, axis=1), -1, 0)) / (0.5 * (speed[:, 1:] +
                                                                       speed[:, :-1]))

    def integral(f):
        return np.sum(0.5 * (f[:, 1:] + f[:, :-1]) * dt, axis=1)

    strain = integral(edot)
    safe = np.maximum(strain, 1e-300)
    return {"pass_strain": strain, "log_rate_mean": integral(edot * np.log(edot)) / safe,
            "inverse_temperature_mean": integral(edot / T) / safe}


def bilinear(a: np.ndarray, b: np.ndarray, values: np.ndarray, pa: np.ndarray,
             pb: np.ndarray) -> np.ndarray:
    """Bilinear interpolation of ``values`` (len(a), len(b)) on the rectilinear grid of the
    increasing axes a, b at the points (pa, pb), inside the grid: what scipy's
    RegularGridInterpolator does (tested against it), without importing scipy.interpolate
    (and scipy.optimize with it: 0.4 s of every run whose roll is rigid, for one call)."""
    i = np.clip(np.searchsorted(a, pa, side="right") - 1, 0, len(a) - 2)
    j = np.clip(np.searchsorted(b, pb, side="right") - 1, 0, len(b) - 2)
    ta = (pa - a[i]) / (a[i + 1] - a[i])
    tb = (pb - b[j]) / (b[j + 1] - b[j])
    return ((1.0 - ta) * ((1.0 - tb) * values[i, j] + tb * values[i, j + 1])
            + ta * ((1.0 - tb) * values[i + 1, j] + tb * values[i + 1, j + 1]))

