"""Where the temperature's strip mesh samples the mechanics (``solvers/thermal_coupling.py``):
the mechanics element each strip vertex belongs to (its weight in that element's mean
temperature) and the points where a field that jumps between elements is read.

A strip vertex on a mechanics element's edge or vertex is in two or more elements, and a
point search picks one of them by its own order, which is neither reproducible across meshes
nor the mirror image's choice on the full strip (equal rolls then differed by 3e-4 in the exit
shear strain, 5e-7 in force, and curled by 1.6e-5 1/m: thermal_pass, issue 52). So:

- each vertex's element is the one holding a point a little inside its own strip cell (1e-3
  of the cell, downstream and towards the mid-plane or symmetry line; upstream on the outlet's
  column), whose mirror image is the mirror image's; the plastic heat density is read there;
- the full strip's mid-plane row lies on elements' edges all along: each vertex there counts
  half in the element above and half in the one below, and its plastic heat density is the
  mean of the two;
- a surface vertex on a mechanics vertex (the contact's start, a break of both meshes) reads
  the friction flux's mean just before and just after it (the shear flow stress k jumps
  there): each surface vertex the mean of the points 1e-3 of a column spacing either side.

With these, equal rolls agree to 1.5e-6 in the exit shear, 8e-8 in force, a curvature of
8e-7 1/m.
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
        j0 = int(np.argmin(np.abs(eta)))
        rows = np.arange(j0 * strip.shape[1], (j0 + 1) * strip.shape[1])
        off = NUDGE * (eta[j0 + 1] - eta[j0])
        sides = [find(np.stack([X, s * off * strip.top_height(X)], -1)) for s in (1.0, -1.0)]
        mid = (rows, *sides)
        counted.append(np.asarray(sides[1]["nr"], dtype=int))
    gap = np.diff(X)
    dx = NUDGE * np.minimum(np.append(gap, gap[-1]), np.insert(gap, 0, gap[0]))
    surfaces = (-1.0, 1.0) if strip.full else (1.0,)
    surface = [find(np.concatenate([np.stack([x, e * strip.top_height(x)], -1)
                                    for e in surfaces]))
               for x in (np.clip(X + s * dx, X[0], X[-1]) for s in (-1.0, 1.0))]
    empty = np.setdiff1d(np.arange(n_elements), np.concatenate(counted))
    return StripSamples(inside, owner, empty, mid, surface)
