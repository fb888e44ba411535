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
  image's; the plastic heat density is read there;
- the full strip's mid-plane row lies on elements' edges all along: each vertex there counts
  half in the element above and half in the one below, and its plastic heat density is the
  mean of the two;
- a surface vertex on a mechanics vertex (the contact's start, a break of both meshes) reads
  the friction flux's mean just before and just after it (the shear flow stress k jumps
  there): each surface vertex the mean of the points 1e-3 of a column spacing either side.

With these the full strip of two equal rolls is its own mirror image to round-off (its exit
shear, forces and curvature 1e-14 apart: thermal_pass). ``k_means``: an element's temperature
from the vertices it owns.
"""
from __future__ import annotations

from typing import Callable, NamedTuple

import numpy as np

#: the nudge into a cell, in units of its size (and of a column spacing on the surface)
NUDGE = 1e-3


class StripSamples(NamedTuple):
    inside: np.ndarray       # each strip vertex's point inside its cell (mesh points)
    owner: np.ndarray        # the mechanics element of each strip vertex (that point's)
    empty: np.ndarray        # the mechanics elements no strip vertex counts in
    mid: tuple | None        # full strip: (mid-plane row's vertices, points above, below)
    surface: list            # the surface rows' points just before and just after


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
    gap = np.diff(X)
    dx = NUDGE * np.minimum(np.append(gap, gap[-1]), np.insert(gap, 0, gap[0]))
    surfaces = (-1.0, 1.0) if strip.full else (1.0,)
    surface = [find(np.concatenate([np.stack([x, e * strip.top_height(x)], -1)
                                    for e in surfaces]))
               for x in (np.clip(X + s * dx, X[0], X[-1]) for s in (-1.0, 1.0))]
    empty = np.setdiff1d(np.arange(n_elements), np.concatenate(counted))
    return StripSamples(inside, owner, empty, mid, surface)


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
