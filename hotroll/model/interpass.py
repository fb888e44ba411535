"""Interpass cooling of a flat strip (issue 17): its temperature through the half thickness
during a transport between two stands.

Model: 1D conduction through the thickness, symmetric about the mid-plane, with convection
and radiation at the surface (both surfaces alike; no heat along the strip, whose length
scale is metres against millimetres):

    dH(T)/dt = d/dy (k(T) dT/dy),  0 < y < H (H the half thickness, y = 0 the mid-plane),
    -k dT/dy = h (T - T_amb) + eps sigma (T^4 - T_amb^4)  at y = H,  dT/dy = 0 at y = 0.

Why this one: a hot strip in air loses most of its heat by radiation (4 eps sigma T^3 ~ 370
W/(m^2 K) at 1000 degC and eps = 0.8, against h ~ 20), the Biot number h_eff H / k is ~0.05
for a 8 mm strip and ~1.3 for a 200 mm slab, so the profile matters for slabs and the mean
for strips; this model covers both with the same data as the pass's [thermal] section. Not
in it: water descaling sprays, roll-table contact, scale.

Discretisation: vertex-centred finite volumes on N equal intervals (nodes y_i = i H / N, the
end cells of half width; the last node is the surface, where the boundary flux acts),
implicit Euler in time, Newton on each step for H(T) and the radiation, the face
conductivities from the last iterate. The enthalpy change equals the heat lost through the
surface over the steps to rounding (``TransportResult.balance_error``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hotroll.model.heat_transfer import ConvectionRadiation, HeatTransferLaw
from hotroll.model.thermal_properties import ThermalInputError, ThermalProperties, finite_number


@dataclass(frozen=True)
class TransportResult:
    """The temperature through the half thickness after a transport (K at ``y``, m from the
    mid-plane to the surface), its enthalpy mean and surface value (K), the heat lost per
    unit area of one surface (J/m^2) and the balance error (relative)."""

    y: np.ndarray
    temperature: np.ndarray
    mean: float
    surface: float
    heat_lost: float
    balance_error: float
    times: np.ndarray | None = None      # s, with ``record``: 0 and the end of every step
    history: np.ndarray | None = None    # K, the profile at those times (steps + 1, nodes)


def _weights(n: int, dy: float) -> np.ndarray:
    """Each node's control-volume width: dy, and dy/2 at both ends."""
    w = np.full(n + 1, dy)
    w[0] = w[-1] = 0.5 * dy
    return w


def enthalpy_mean(props: ThermalProperties, T: np.ndarray, weights: np.ndarray) -> float:
    """The temperature whose enthalpy per volume is the weighted mean of H(T) (K): the strip's
    mean temperature as its heat content sees it (bisection; H is increasing)."""
    target = float(weights @ props.enthalpy_values(T)) / float(weights.sum())
    lo, hi = float(np.min(T)), float(np.max(T))
    for _ in range(200):
        if hi - lo <= 1e-12 * hi:
            break
        mid = 0.5 * (lo + hi)
        if float(props.enthalpy_values(mid)) < target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def cool(y: np.ndarray, T: np.ndarray, half_thickness: float, duration: float,
         props: ThermalProperties, htc: float | None, emissivity: float | None, ambient: float,
         intervals: int = 40, steps: int | None = None,
         surface: HeatTransferLaw | None = None, record: bool = False) -> TransportResult:
    """The temperature profile ``T`` (K) at ``y`` (from the mid-plane, 0, to the surface, the
    last value; rescaled onto ``half_thickness``, so a logical coordinate in [0, 1] serves too)
    after ``duration`` seconds in air (module docstring); one value is a uniform profile.
    ``steps`` implicit steps (default: at least 100, and dt at most a tenth of H^2 / alpha).
    The surface loses q(T) of the free surfaces' law ``surface`` (``model/heat_transfer``;
    default: convection ``htc`` and radiation ``emissivity``). ``record``: keep the profile
    after every step (``times``, ``history``: what the recrystallisation kinetics integrate)."""
    H = finite_number("half_thickness", half_thickness, 0.0, True, None, "m")
    t_end = finite_number("duration", duration, 0.0, False, None, "s")
    if surface is None:            # htc and emissivity ignored when a law is given
        surface = ConvectionRadiation(finite_number("htc_air", htc, 0.0, False, None, "W/(m^2 K)"),
                                      finite_number("emissivity", emissivity, 0.0, False, 1.0, ""))
    T_amb = finite_number("ambient_temperature", ambient, 0.0, True, None, "K")
    y, T = np.asarray(y, dtype=float), np.asarray(T, dtype=float)
    if y.ndim != 1 or y.shape != T.shape or y.size < 1 or not np.all(np.isfinite(T)) \
            or np.any(T <= 0.0) or (y.size > 1 and np.any(np.diff(y) <= 0.0)):
        raise ThermalInputError("transport profile: y (m) and T (K) must be equal-length "
                                "arrays, y increasing, T finite and > 0")
    n = int(intervals)
    if n < 2:
        raise ThermalInputError(f"transport intervals = {intervals!r}: must be >= 2")
    dy = H / n
    nodes = np.linspace(0.0, H, n + 1)
    temp = np.interp(nodes, y * (H / y[-1]) if y[-1] > 0 else y, T)   # onto the nodes
    w = _weights(n, dy)
    H0 = float(w @ props.enthalpy_values(temp))
    if t_end == 0.0:
        return TransportResult(nodes, temp, enthalpy_mean(props, temp, w), float(temp[-1]),
                               0.0, 0.0, np.zeros(1) if record else None,
                               temp[None, :].copy() if record else None)
    if steps is None:
        alpha = float(np.max(props.k_values(temp) / props.rho_c_values(temp)))
        steps = max(100, math.ceil(t_end / (0.1 * H * H / alpha)))
    dt = t_end / int(steps)
    lost = 0.0
    history = [temp.copy()] if record else None
    # the tridiagonal solve: LAPACK's gtsv, which scipy.linalg.solve_banded((1, 1), ...)
    # calls, without its per-call checks (2900 small solves in a ten-stand schedule);
    # imported here: scipy.linalg only where a strip cools
    from scipy.linalg.lapack import dgtsv

    for _ in range(int(steps)):
        old_H = props.enthalpy_values(temp)
        new = temp.copy()
        H_new = old_H                        # H(new) = H(temp) in the first iteration
        for it in range(50):                 # Newton on the step's residual
            if it:
                H_new = props.enthalpy_values(new)
            k = props.k_values(new)
            kf = 0.5 * (k[1:] + k[:-1]) / dy          # face conductances, W/(m^2 K)
            q_s = surface.flux(new[-1], T_amb)
            flux = kf * (new[1:] - new[:-1])          # into node i from node i+1
            res = w * (H_new - old_H) / dt
            res[:-1] -= flux
            res[1:] += flux
            res[-1] += q_s
            # tridiagonal Jacobian (face conductances frozen): diagonal and off-diagonals
            diag = w * props.rho_c_values(new) / dt
            diag[:-1] += kf
            diag[1:] += kf
            diag[-1] += surface.dflux(new[-1], T_amb)
            off = -kf
            _, _, _, d, info = dgtsv(off, diag, off, -res)
            if info:
                raise np.linalg.LinAlgError(f"interpass cooling: singular Jacobian "
                                            f"(gtsv info {info})")
            new += d
            if np.max(np.abs(d)) <= 1e-11 * np.max(new):
                break
        temp = new
        if record:
            history.append(temp.copy())
        lost += dt * surface.flux(temp[-1], T_amb)
    change = H0 - float(w @ props.enthalpy_values(temp))
    err = abs(change - lost) / max(abs(lost), 1e-300)
    return TransportResult(nodes, temp, enthalpy_mean(props, temp, w), float(temp[-1]), lost,
                           err, np.linspace(0.0, t_end, int(steps) + 1) if record else None,
                           np.array(history) if record else None)
