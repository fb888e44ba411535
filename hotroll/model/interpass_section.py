"""Interpass cooling across the width (issue 53): the temperature over the strip's quarter
cross-section during a transport between two stands, its edges cooling from the side as well
as from the top (``model/interpass.py`` is its 1D form through the thickness).

Model: 2D conduction over 0 < y < H (half thickness), 0 < z < B (half width), symmetric about
mid-thickness and mid-width, convection and radiation on the top (y = H) and the edge (z = B)
by the free surfaces' law (the corner loses through both):

    dH(T)/dt = d/dy (k dT/dy) + d/dz (k dT/dz),
    -k dT/dn = q(T) on y = H and z = B,  dT/dn = 0 on y = 0 and z = 0.

No heat along the strip (its length scale is metres). Discretisation: vertex-centred finite
volumes on a tensor grid, ``ny`` equal intervals through the thickness (the 1D model's) and
intervals across the width graded from the edge (the edge's layer as thin as a thickness
interval and at most a fifth of the heat's reach sqrt(alpha t), growing x1.2 towards
mid-width up to B / 40), implicit Euler, Newton on each step (sparse LU) for H(T) and the
radiation. The enthalpy change equals the heat lost through the top and the edge to rounding
(``SectionCooling.balance_error``). Where the edge's heat does not reach mid-width the
mid-width column is the 1D model's (same grid and steps through the thickness)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hotroll.model.heat_transfer import HeatTransferLaw
from hotroll.model.interpass import _weights, enthalpy_mean
from hotroll.model.section import SectionProfile
from hotroll.model.thermal_properties import ThermalInputError, ThermalProperties, finite_number

#: the width grid: its edge layer at most this share of the heat's reach sqrt(alpha t), its
#: layers growing this much towards mid-width, up to the half width over WIDTH_INTERVALS
REACH_SHARE, GROWTH, WIDTH_INTERVALS = 0.2, 1.2, 40


@dataclass(frozen=True)
class SectionCooling:
    """The cross-section's temperature after a transport (``section``, K over eta and zeta),
    its enthalpy mean (K), the heat lost per metre of strip by the quarter section (J/m) and
    the balance error (relative)."""

    section: SectionProfile
    mean: float
    heat_lost: float
    balance_error: float
    y: np.ndarray | None = None          # m, the nodes through the thickness
    times: np.ndarray | None = None      # s, with ``record``: 0 and the end of every step
    history: np.ndarray | None = None    # K, mid-width's column at those times


def width_nodes(half_width: float, first: float) -> np.ndarray:
    """Nodes from 0 (mid-width) to ``half_width`` (m): ``first`` wide at the edge, each
    interval x GROWTH towards mid-width up to half_width / WIDTH_INTERVALS."""
    cap = half_width / WIDTH_INTERVALS
    steps, d, total = [], min(first, cap), 0.0
    while total + d < half_width - 1e-12 * half_width:
        steps.append(d)
        total += d
        d = min(d * GROWTH, cap)
    if steps and half_width - total < 0.5 * steps[-1]:   # no sliver at mid-width
        steps[-1] += half_width - total
    else:
        steps.append(half_width - total)
    z = half_width - np.concatenate([[0.0], np.cumsum(steps)])[::-1]
    z[0], z[-1] = 0.0, half_width
    return z


def _volumes(nodes: np.ndarray) -> np.ndarray:
    """Each node's control-volume width on an unequal grid (half its two intervals)."""
    d = np.diff(nodes)
    w = np.zeros(nodes.size)
    w[:-1] += 0.5 * d
    w[1:] += 0.5 * d
    return w


def cool_section(T0: SectionProfile, half_thickness: float, half_width: float,
                 duration: float, props: ThermalProperties, surface: HeatTransferLaw,
                 ambient: float, intervals: int = 40, steps: int | None = None,
                 record: bool = False) -> SectionCooling:
    """The cross-section ``T0`` (K) after ``duration`` seconds in air (module docstring).
    ``steps`` implicit steps (default: the 1D model's, at least 100 and dt at most a tenth of
    H^2 / alpha). ``record``: keep mid-width's column after every step (what the
    recrystallisation kinetics integrate)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import spsolve

    H = finite_number("half_thickness", half_thickness, 0.0, True, None, "m")
    B = finite_number("half_width", half_width, 0.0, True, None, "m")
    t_end = finite_number("duration", duration, 0.0, False, None, "s")
    T_amb = finite_number("ambient_temperature", ambient, 0.0, True, None, "K")
    if np.any(T0.array <= 0.0):
        raise ThermalInputError("cross-section temperature: every value must be > 0 K")
    n = int(intervals)
    if n < 2:
        raise ThermalInputError(f"transport intervals = {intervals!r}: must be >= 2")
    if t_end == 0.0:
        return SectionCooling(T0, enthalpy_mean_of(T0, props), 0.0, 0.0,
                              np.asarray(T0.eta) * H, np.zeros(1) if record else None,
                              T0.array[:, :1].T.copy() if record else None)
    y = np.linspace(0.0, H, n + 1)
    alpha = float(np.max(props.k_values(T0.array) / props.rho_c_values(T0.array)))
    z = width_nodes(B, min(H / n, REACH_SHARE * math.sqrt(alpha * t_end)))
    ny, nz = y.size, z.size
    wy, wz = _weights(n, H / n), _volumes(z)
    vol = np.outer(wy, wz).ravel()                              # m^2 per node
    E, Z = np.meshgrid(y / H, z / B, indexing="ij")
    temp = T0(E, Z).ravel()
    idx = np.arange(ny * nz).reshape(ny, nz)
    # the faces between neighbours: (node a, node b, area over distance), m/m
    pairs = [(idx[:-1, :].ravel(), idx[1:, :].ravel(),
              (wz[None, :] / np.diff(y)[:, None]).ravel()),
             (idx[:, :-1].ravel(), idx[:, 1:].ravel(),
              (wy[:, None] / np.diff(z)[None, :]).ravel())]
    a = np.concatenate([p[0] for p in pairs])
    b = np.concatenate([p[1] for p in pairs])
    g = np.concatenate([p[2] for p in pairs])
    # the cooled faces' areas per node (m per metre of strip): the top row and the edge column
    area = np.zeros((ny, nz))
    area[-1, :] += wz
    area[:, -1] += wy
    area = area.ravel()
    H0 = float(vol @ props.enthalpy_values(temp))
    if steps is None:
        steps = max(100, math.ceil(t_end / (0.1 * H * H / alpha)))
    dt = t_end / steps
    lost = 0.0
    n_all = ny * nz
    history = [temp.reshape(ny, nz)[:, 0].copy()] if record else None
    for _ in range(int(steps)):
        old_H = props.enthalpy_values(temp)
        new = temp.copy()
        for it in range(50):
            H_new = old_H if it == 0 else props.enthalpy_values(new)
            k = props.k_values(new)
            kf = 0.5 * (k[a] + k[b]) * g                       # W/(m K) per face
            flux = kf * (new[b] - new[a])                       # into a from b
            res = vol * (H_new - old_H) / dt + area * surface.flux(new, T_amb)
            np.subtract.at(res, a, flux)
            np.add.at(res, b, flux)
            diag = vol * props.rho_c_values(new) / dt + area * surface.dflux(new, T_amb)
            np.add.at(diag, a, kf)
            np.add.at(diag, b, kf)
            J = coo_matrix((np.concatenate([diag, -kf, -kf]),
                            (np.concatenate([np.arange(n_all), a, b]),
                             np.concatenate([np.arange(n_all), b, a]))),
                           shape=(n_all, n_all)).tocsc()
            d = spsolve(J, -res)
            new += d
            if np.max(np.abs(d)) <= 1e-11 * np.max(new):
                break
        else:
            raise ThermalInputError(f"interpass cooling across the width: Newton did not "
                                    f"converge in a step of {dt:.3g} s (last change "
                                    f"{np.max(np.abs(d)):.3g} K)")
        temp = new
        if record:
            history.append(temp.reshape(ny, nz)[:, 0].copy())
        lost += dt * float(area @ surface.flux(temp, T_amb))
    change = H0 - float(vol @ props.enthalpy_values(temp))
    err = abs(change - lost) / max(abs(lost), 1e-300)
    grid = temp.reshape(ny, nz)
    section = SectionProfile(tuple(y / H), tuple(z / B), tuple(tuple(r) for r in grid))
    return SectionCooling(section, enthalpy_mean(props, temp, vol), lost, err, y,
                          np.linspace(0.0, t_end, int(steps) + 1) if record else None,
                          np.array(history) if record else None)


def enthalpy_mean_of(section: SectionProfile, props: ThermalProperties) -> float:
    """The section's mean temperature by its heat content (K): bilinear cells' corners by
    their control areas."""
    w = np.outer(_volumes(np.asarray(section.eta)), _volumes(np.asarray(section.zeta)))
    return enthalpy_mean(props, section.array.ravel(), w.ravel())
