"""Figures read off a contact profile (numpy only, no FE): the neutral point, the sticking zone,
the flux's neutral angle, the P1 smoothing, contact loss and the exit-pressure correction.
docs/theory.md 1e, 4.3, 4.5. ``fem/quantities.py`` re-exports them; ``results/`` reads them from
here (it imports no FE: issue 52, the ``results-no-fe`` contract)."""
from __future__ import annotations

import math

import numpy as np


def neutral_index(v_slip: np.ndarray, weights: np.ndarray | None = None) -> int:
    """Split index k that best separates backward (v_s < 0) from forward (v_s > 0) slip.

    Minimises the weighted count of misclassified nodes, sum_{i<k} w [v_s > 0] +
    sum_{i>=k} w [v_s < 0]. It is the sign change for a clean profile and stays robust where
    v_s is tiny (a sticking zone) or spikes at the first touching element; only signs count.
    """
    w = np.ones_like(v_slip) if weights is None else weights
    pos = np.concatenate([[0.0], np.cumsum((v_slip > 0) * w)])
    neg = np.concatenate([[0.0], np.cumsum((v_slip < 0) * w)])
    cost = pos + (neg[-1] - neg)
    return int(np.argmin(cost))


def neutral_point(profile: dict, rp) -> tuple[list[float], float]:
    """Neutral point [x, y] and neutral angle, interpolated at the split of ``neutral_index``."""
    vs = profile["v_slip"]
    if len(vs) == 0:
        return [math.nan, math.nan], math.nan
    ang = profile["angle"]
    w = np.gradient(ang) if len(ang) > 1 else np.ones(1)   # node spacing along the arc
    k = neutral_index(vs, np.abs(w))
    if k == 0:
        i, j = 0, 0
    elif k == len(vs):
        i, j = len(vs) - 1, len(vs) - 1
    else:
        i, j = k - 1, k
    a, b = vs[i], vs[j]
    s = 0.5 if (i == j or a == b or a * b > 0) else a / (a - b)
    a_n = ang[i] + s * (ang[j] - ang[i])
    cx, cy = rp.centre
    return [cx - rp.radius * math.sin(a_n), cy - rp.radius * math.cos(a_n)], float(a_n)


#: Slip below this fraction of the roll speed is sticking: the regularisation speed of Coulomb's
#: and Tresca's laws (below it they cannot tell slip from stick), and 100 times the Newton
#: tolerance on the velocity (1e-5 U).
STICKING_FLOOR = 1e-3


def sticking_zone(profile: dict, u_roll: float, min_length: float,
                  floor: float = STICKING_FLOOR) -> list[float] | None:
    """[start angle, end angle] (rad, start > end: from the entry) of the longest stretch of the
    contact, longer than ``min_length`` along the arc, where |v_s| < floor U; None without."""
    vs = np.abs(np.asarray(profile["v_slip"], dtype=float))
    if len(vs) < 2:
        return None
    xy = np.stack([profile["x"], profile["y"]], -1)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))])
    stuck = vs < floor * u_roll
    best, i = None, 0
    while i < len(vs):
        if stuck[i]:
            j = i
            while j + 1 < len(vs) and stuck[j + 1]:
                j += 1
            if s[j] - s[i] > min_length and (best is None or s[j] - s[i] > best[2]):
                best = (i, j, s[j] - s[i])
            i = j + 1
        else:
            i += 1
    if best is None:
        return None
    ang = profile["angle"]
    return [float(ang[best[0]]), float(ang[best[1]])]


def slip_sign_changes(profile: dict, zone: list[float]) -> int:
    """How often the slip changes sign between the nodes of ``zone`` ([start, end] angles,
    rad); exact zeros are skipped. More than one: the neutral point is not unique there."""
    ang = np.asarray(profile["angle"], dtype=float)
    vs = np.asarray(profile["v_slip"], dtype=float)
    sign = np.sign(vs[(ang <= zone[0]) & (ang >= zone[1])])
    sign = sign[sign != 0]
    return int(np.count_nonzero(np.diff(sign)))


def flux_neutral_angle(rp, flux: float) -> float:
    """The neutral angle of the flux (the slab theory's): where the roll's horizontal speed
    U cos(phi) carries the strip's flux over its half-height, y(phi) U cos(phi) = q, with
    y(phi) = h1/2 + R (1 - cos phi) (half model, q the half flux). It needs no slip sign, so it
    stays defined where the contact sticks; it converges with the flux. NaN if the flux is
    not between U h1/2 and the largest y U cos.

    A quadratic in c = cos(phi): R c^2 - (h + R) c + q/U = 0 (h = h1/2), its root nearest 1,
    written without cancellation: 1 - c = 2 (q/U - h) / ((R - h) + sqrt(D)),
    D = (h + R)^2 - 4 R q/U, and phi = 2 asin(sqrt((1 - c)/2)) (scipy's brentq here imported
    scipy.optimize, 0.4 s, into every rigid-roll run for this one root)."""
    import math

    U, R, h = rp.u_roll, rp.radius, rp.half_exit

    def f(phi):
        return (h + R * (1.0 - math.cos(phi))) * U * math.cos(phi) - flux

    # a root on the arc: the sign changes between the gap and the bite
    if not (math.isfinite(flux) and f(0.0) * f(rp.bite_angle) < 0):
        return math.nan
    qU = flux / U
    disc = max((h + R) ** 2 - 4.0 * R * qU, 0.0)
    one_minus_c = 2.0 * (qU - h) / ((R - h) + math.sqrt(disc))
    return 2.0 * math.asin(math.sqrt(0.5 * one_minus_c))


def smoothed(profile: dict, values: np.ndarray) -> np.ndarray:
    """L2 projection of a P2 contact profile onto continuous P1 along the arc (the plotted
    profile; the raw nodal values stay in ``contact.csv``).

    The contact nodes alternate vertex, edge midpoint, vertex, ... from entry to exit
    (``profile["vertex"]``); on each edge the raw values are the quadratic through its three
    nodes. The projection removes the vertex/midpoint zigzag of the penalty reaction and keeps
    every integral against a function linear in the arc length: the resultant along the arc
    and the torque of the shear exactly, the roll force up to the turn of the roll normal
    within an edge. Returns the values at the same nodes (midpoints: the mean of their
    vertices); the raw values where the nodes do not alternate (a contact vertex without a
    contact edge, in the report's scheme).
    """
    y = np.asarray(values, dtype=float)
    n = len(y)
    pattern = np.arange(n) % 2 == 0
    if n < 3 or n % 2 == 0 or ("vertex" in profile
                               and not np.array_equal(np.asarray(profile["vertex"]) > 0, pattern)):
        return y.copy()
    xy = np.stack([profile["x"], profile["y"]], -1)
    seg = np.linalg.norm(np.diff(xy, axis=0), axis=1)
    L = seg[0::2] + seg[1::2]                       # edge lengths (vertex to vertex)
    ya, ym, yb = y[0:-1:2], y[1::2], y[2::2]
    nv = len(L) + 1
    diag = np.zeros(nv)
    diag[:-1] += L / 3.0
    diag[1:] += L / 3.0
    off = L / 6.0
    rhs = np.zeros(nv)
    rhs[:-1] += L * (ya / 6.0 + ym / 3.0)
    rhs[1:] += L * (ym / 3.0 + yb / 6.0)
    M = np.diag(diag) + np.diag(off, 1) + np.diag(off, -1)
    c = np.linalg.solve(M, rhs)
    out = np.empty(n)
    out[0::2] = c
    out[1::2] = 0.5 * (c[:-1] + c[1:])
    return out


#: Tension below this share of the peak pressure is the unilateral contact's end tolerance
#: (its end is iterated to p = 0 within 1e-3 h: about 1e-4 of the peak), not contact loss.
LOSS_FLOOR = 1e-3


def contact_loss(profile: dict, normal_stress: np.ndarray, min_length: float) -> list:
    """Stretches [x_start, x_end] of the contact, at least ``min_length`` long along the arc,
    where the normal stress is tensile (beyond ``LOSS_FLOOR`` of the peak pressure): there the
    strip would leave the roll."""
    sn = np.asarray(normal_stress, dtype=float)
    if len(sn) < 2:
        return []
    sn = sn - LOSS_FLOOR * max(float(-sn.min()), 0.0)
    xy = np.stack([profile["x"], profile["y"]], -1)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))])
    out, i = [], 0
    while i < len(sn):
        if sn[i] > 0:
            j = i
            while j + 1 < len(sn) and sn[j + 1] > 0:
                j += 1
            if s[j] - s[i] >= min_length:
                out.append([float(xy[i, 0]), float(xy[j, 0])])
            i = j + 1
        else:
            i += 1
    return out


def exit_corrected(profile: dict, h: float, zone: float = 2.0, fit: float = 6.0) -> np.ndarray:
    """Exit-pressure correction (Section 3.4; the report does not say which): the normal stress at
    the contact nodes within ``zone * h`` of the last contact point is replaced by the
    least-squares line through the nodes between ``zone * h`` and ``fit * h`` from it,
    extrapolated; the oscillation at the change of boundary condition is removed, the rest kept.
    """
    sn = np.array(profile["normal_stress"], dtype=float)
    if len(sn) < 4:
        return sn
    xy = np.stack([profile["x"], profile["y"]], -1)
    seg = np.linalg.norm(np.diff(xy, axis=0), axis=1)
    dist_to_end = np.concatenate([np.cumsum(seg[::-1])[::-1], [0.0]])
    near = dist_to_end < zone * h
    ref = (dist_to_end >= zone * h) & (dist_to_end < fit * h)
    if ref.sum() < 2 or not near.any():
        return sn
    coef = np.polyfit(dist_to_end[ref], sn[ref], 1)
    sn[near] = np.polyval(coef, dist_to_end[near])
    return sn
