"""Where the temperature's strip mesh samples the mechanics (``solvers/thermal_coupling.py``):
the mechanics element each strip vertex belongs to (its weight in that element's mean
temperature) and the points where a field that jumps between elements is read.

A strip vertex on a mechanics element's edge or vertex is in two or more elements, and a
point search picks one of them by its own order, which is neither reproducible across meshes
nor the mirror image's choice on the full strip (equal rolls then differed between their
upper and lower halves by 3e-4 in the exit shear strain and 5e-7 in force, and curled by
1.6e-5 1/m: thermal_pass, issue 52). So:

- each vertex's element is the one holding a point a little inside its own strip cell
  (downstream by 1e-3 of its column spacing, upstream on the outlet's column; towards the
  mid-plane or symmetry line by 1e-3 of the thinnest row), whose mirror image is the mirror
  image's;
- the full strip's mid-plane row lies on elements' edges all along: each vertex there counts
  half in the element above and half in the one below;
- the heat sources are means over each vertex's dual cell (from the midpoints to its
  neighbours, ``CELL_POINTS`` Gauss points a direction, none on the mid-plane, each the
  mirror image of the mirror vertex's): the plastic power density over the cell, the
  friction flux over the surface's dual segment where it lies in its roll's contact
  (``ThermalCoupling._transfer``). A value read at one point (until 2026-11-29: 1e-3 of a
  cell inside it, beside a surface vertex) carried a peak narrower than a strip cell (the
  contact's start on a mesh refined there, ``mesh.corner_refinement``) over the whole cell:
  plastic heat +2.9 %, friction heat +23 % on thermal_pass at 16x; with the means -0.2 % and
  -2.1 % (and at 1x +0.02 % and -0.3 %, against +0.24 % and +2.2 % read at points).

With these the full strip of two equal rolls is its own mirror image to round-off (its exit
shear, forces and curvature 1e-14 apart: thermal_pass). ``k_means``: an element's temperature
from the vertices it owns.
"""
from __future__ import annotations

from typing import Callable, NamedTuple

import numpy as np

#: the nudge into a cell, in units of its size
NUDGE = 1e-3


#: Gauss points per direction over a vertex's dual cell (the heat sources' cell means)
CELL_POINTS = 4


class StripSamples(NamedTuple):
    owner: np.ndarray        # the mechanics element of each strip vertex (a point's inside
                             # its cell)
    empty: np.ndarray        # the mechanics elements no strip vertex counts in
    mid: tuple | None        # full strip: (mid-plane row's vertices, points above, below)
    cells: tuple             # (mesh points, weights): each vertex's dual cell's Gauss points
    surface: tuple           # (mesh points, weights): each surface vertex's dual segment's


def _dual_gauss(axis: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(points (len, n), weights (n,), summing to 1): Gauss-Legendre over each node's dual
    interval of the sorted ``axis`` (from the midpoint before to the midpoint after, the ends
    at the axis's ends)."""
    mid = 0.5 * (axis[1:] + axis[:-1])
    lo, hi = np.concatenate([axis[:1], mid]), np.concatenate([mid, axis[-1:]])
    g, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * g[None, :], 0.5 * w


def cell_means(values: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Each vertex's mean from its cell's points' ``values`` (vertex-major, ``weights`` per
    point of a cell)."""
    return values.reshape(-1, len(weights)) @ weights


def contact_means(values: np.ndarray, x: np.ndarray, ranges: list[tuple[float, float]],
                  weights: np.ndarray) -> np.ndarray:
    """Each surface vertex's mean of ``values`` over the points of its dual segment (at x,
    vertex-major, ``weights`` per point) that lie in its surface's contact range (``ranges``
    (lo, hi) per surface, in the points' order); 0 where none does."""
    n = len(values) // len(ranges)
    lo, hi = (np.repeat([r[i] for r in ranges], n) for i in (0, 1))
    w = ((x >= lo) & (x <= hi)).reshape(-1, len(weights)) * weights
    return (values.reshape(-1, len(weights)) * w).sum(1) / np.maximum(w.sum(1), 1e-300)


def strip_samples(strip, find: Callable, n_elements: int) -> StripSamples:
    """The samples of ``strip`` (``fem/strip_mesh.ThermalStrip``) in the mechanics mesh
    (``find``: reference points (N, 2) -> mesh points; ``n_elements`` its elements)."""
    X, eta = strip.X, strip.eta
    Xg, Eg = np.meshgrid(X, eta)
    dX = NUDGE * np.append(np.diff(X), np.diff(X)[-1])
    dX[-1] *= -1.0                                   # the outlet's column: upstream
    dE = NUDGE * np.abs(np.diff(eta)).min()
    Xn = np.broadcast_to(X + dX, Xg.shape).ravel()
    towards_middle = -np.sign(Eg) if strip.full else np.where(Eg > 0.0, -1.0, 1.0)
    En = (Eg + towards_middle * dE).ravel()
    inside = find(np.stack([Xn, En * strip.top_height(Xn)], -1))
    owner = np.array(inside["nr"], dtype=int)
    counted = [owner]
    mid = None
    if strip.full:
        # the mid-plane row (at the same nudged x as the other rows): the element above owns
        # half of each vertex, the one below the other half
        j0 = int(np.argmin(np.abs(eta)))
        rows = np.arange(j0 * strip.shape[1], (j0 + 1) * strip.shape[1])
        off = NUDGE * (eta[j0 + 1] - eta[j0])
        Xm = X + dX
        sides = [find(np.stack([Xm, s * off * strip.top_height(Xm)], -1)) for s in (1.0, -1.0)]
        mid = (rows, *sides)
        owner[rows] = np.asarray(sides[0]["nr"], dtype=int)
        counted.append(np.asarray(sides[1]["nr"], dtype=int))
    surfaces = (-1.0, 1.0) if strip.full else (1.0,)
    empty = np.setdiff1d(np.arange(n_elements), np.concatenate(counted))
    # the heat sources at each vertex: their means over its dual cell (plastic density) and
    # dual segment of the surface (friction flux), Gauss points inside, none on the mid-plane
    # (CELL_POINTS even) and each the mirror image of the mirror vertex's
    gx, wx = _dual_gauss(X, CELL_POINTS)
    ge, we = _dual_gauss(eta, CELL_POINTS)
    if not strip.full:
        # the symmetry line's row: the upper half of the full strip's mid-plane cell, its
        # points those of the symmetric cell folded onto y >= 0 (the same weights), so that
        # the full strip of two equal rolls integrates the sources as the half model twice
        # (with the half cell's own Gauss points the plastic heat differed by 4-9e-6 at
        # the fixed point's limit: thermal_pass, 1x and 16x)
        ge[0] = np.abs(0.5 * eta[1] * np.polynomial.legendre.leggauss(CELL_POINTS)[0])
    PX = np.broadcast_to(gx[None, :, :, None], (len(eta), len(X), CELL_POINTS, CELL_POINTS))
    PE = np.broadcast_to(ge[:, None, None, :], PX.shape)
    cells = (find(np.stack([PX.ravel(), PE.ravel() * strip.top_height(PX.ravel())], -1)),
             np.outer(wx, we).ravel())
    sx = gx.ravel()
    surface = (find(np.concatenate([np.stack([sx, e * strip.top_height(sx)], -1)
                                    for e in surfaces])), wx)
    return StripSamples(owner, empty, mid, cells, surface)


def k_means(owner: np.ndarray, ne: int, vals: np.ndarray, w: np.ndarray,
            consistency=None) -> np.ndarray:
    """Each of the ``ne`` mechanics elements' temperature from the strip vertices it owns
    (``owner``, their temperatures ``vals`` and weights ``w``): the one whose consistency
    K(T) (``consistency``) is their weighted mean of K, so that the element is as hard as the
    material in it on average (the plain mean of T would make a chilled element softer: K is
    convex in T); bisection between the smallest and the largest T inside. The plain mean for
    a law without T (``consistency`` None), or one not monotone there."""
    wsum = np.maximum(np.bincount(owner, w, minlength=ne), 1e-300)
    plain = np.bincount(owner, w * vals, minlength=ne) / wsum
    if consistency is None:
        return plain

    def K(T):
        return np.asarray(consistency(T), dtype=float)

    target = np.bincount(owner, w * K(vals), minlength=ne) / wsum
    lo = np.full(ne, np.inf)
    hi = np.full(ne, -np.inf)
    np.minimum.at(lo, owner, vals)
    np.maximum.at(hi, owner, vals)
    lo, hi = np.where(np.isfinite(lo), lo, plain), np.where(np.isfinite(hi), hi, plain)
    k_lo, k_hi = K(lo), K(hi)
    # K the same at both ends (a law without T, or one element's uniform temperature):
    # any T between would do, and the bisection would follow the rounding: the plain mean
    flat = np.abs(k_lo - k_hi) <= 1e-12 * np.abs(k_hi)
    if np.all(flat):
        return plain
    falling = k_lo >= k_hi
    if not np.all(falling | flat):
        return plain
    for _ in range(60):                   # to 1e-9 of the temperature (~30 halvings)
        if np.max(hi - lo) <= 1e-9 * np.max(np.abs(hi)):
            break
        mid = 0.5 * (lo + hi)
        above = K(mid) > target           # still too hard: go hotter
        lo, hi = np.where(above, mid, lo), np.where(above, hi, mid)
    return np.where(flat, plain, 0.5 * (lo + hi))
