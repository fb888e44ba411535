"""Shape of the steady strip and its free tops (steady counterpart of (3.7) + (3.9)).

Two free-surface models (``[plate] free_surface``):

- ``"constrained"``: the report's (3.2d) holds the free tops flat (entry thickness before the
  bite, the gap after it); the contact is the geometric arc from the touching point to the gap.
- ``"traced"``: the tops are traction-free and follow the flow. In a steady flow a free top is a
  streamline, u_x eta'(x) = u_y (the kinematic condition v.n = 0). The strip's shape is then
  three numbers and two curves: the contact start x_c where the entry top meets the roll, the
  entry top eta_in(x) on [x_in, x_c] (flat far upstream, where the strip is rigid) and the exit
  top eta_out(x) on [X_roll, x_out] (leaving the roll at the gap).

``StripMap`` maps the reference mesh (flat tops, contact from the geometric touching point
x_touch) onto such a shape: a piecewise-linear stretch in x moves the reference touching point to
x_c (the contact set is always the same chain of edges, so x_c is a continuous unknown), and
every P2 node is scaled vertically, y' = y H(x') / H_ref(x), with H the new top height.

``kinematic_update`` is the fixed-point map on the shape: trace the streamlines of the computed
flow along the free tops; on the exit side the traced curve is the new top; on the entry side
the traced curve misses the roll at x_c by a gap g, and the contact start moves by g / s_roll
(s_roll the roll's slope there) with the traced sag profile carried along. The gap contracts by
about 10x per update (measured, docs/theory.md 4b).
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from hotroll.fem.spaces import P2Nodes
from hotroll.model.geometry import RollPass


@dataclass
class StripShape:
    """The contact's two ends and the free tops as curves (x, y) in the current configuration."""

    x_c: float
    entry_x: np.ndarray      # entry top, increasing x, ending at x_c
    entry_y: np.ndarray
    exit_x: np.ndarray       # exit top, increasing x, starting at the contact's end x_e
    exit_y: np.ndarray
    x_e: float | None = None  # the contact's end (separation point); None: the gap X_roll

    @classmethod
    def flat(cls, rp: RollPass) -> "StripShape":
        """The reference shape: flat tops, contact from the geometric touching point."""
        return cls(rp.x_touch, np.array([rp.x_touch - 1e3, rp.x_touch]),
                   np.full(2, rp.half_entry), np.array([rp.axis_x, rp.axis_x + 1e3]),
                   np.full(2, rp.half_exit))

    def end(self, rp: RollPass) -> float:
        """x_e: where the contact ends (the gap X_roll unless the strip leaves before it)."""
        return rp.axis_x if self.x_e is None else self.x_e

    def copy(self) -> "StripShape":
        return StripShape(self.x_c, self.entry_x.copy(), self.entry_y.copy(),
                          self.exit_x.copy(), self.exit_y.copy(), self.x_e)


def roll_height(rp: RollPass, x):
    """Height of the roll surface above the axis at x (lower half of the roll)."""
    return rp.height(x)


def roll_slope(rp: RollPass, x: float) -> float:
    """d(roll height)/dx at x: the circle's; a flattened roll's by a central difference."""
    if rp.shape is None:
        cx, _ = rp.centre
        return float((x - cx) / np.sqrt(max(rp.radius**2 - (x - cx) ** 2, 1e-300)))
    dx = 1e-6 * rp.contact_length
    return float((rp.height(x + dx) - rp.height(x - dx)) / (2.0 * dx))


class StripMap:
    """All P2 nodes of the reference strip mesh and their map onto a ``StripShape``."""

    def __init__(self, rp: RollPass, mesh, n_scalar: int, d_ref: np.ndarray, x_in: float):
        # the reference mesh's roll (a flattened roll's surface moves; the reference does not)
        self.rp = rp if rp.shape is None else replace(rp, shape=rp.shape.copy())
        self.nodes = P2Nodes(mesh, n_scalar)
        self.P = self.nodes.X0 + self.nodes.values(d_ref).T     # reference positions
        X = self.P[:, 0]
        on_arc = (X > rp.x_touch) & (X < rp.axis_x)
        self.H_ref = np.where(X >= rp.axis_x, rp.half_exit, rp.half_entry)
        self.H_ref[on_arc] = roll_height(rp, X[on_arc])
        self.roll = rp           # the roll now (its surface, if flattened, moves)
        self.set_anchors(x_in, float(X.max()))

    def set_anchors(self, x_in: float, x_out: float) -> None:
        """The stretch's fixed points (the mesh's inlet and outlet at x_in, x_out): it acts
        between x_a (half a contact length before the bite) and X_roll, and on the exit side
        from X_roll to x_b (where the contact's end moves the exit top), which moves on with
        a contact end past the gap (``exit_anchor``) up to x_b_max, midway to the outlet."""
        rp = self.rp
        self.x_a = max(rp.x_touch - 0.5 * rp.contact_length, 0.5 * (x_in + rp.x_touch))
        self.x_b_max = 0.5 * (rp.axis_x + x_out)
        self.x_b = min(rp.axis_x + 0.5 * rp.contact_length, self.x_b_max)

    def x_bounds(self) -> tuple[float, float]:
        """Allowed range of the contact start (keeps the stretch within a factor ~2)."""
        rp = self.rp
        return (0.5 * (self.x_a + rp.x_touch), rp.axis_x - 0.5 * rp.contact_length)

    def end_bounds(self, past_gap: float = 0.0) -> tuple[float, float]:
        """Allowed range of the contact's end x_e: from half a contact length before the gap
        to the gap, or ``past_gap`` contact lengths after it (an elastic strip follows the
        rising roll while it recovers), at most a quarter of the way to the outlet (half of
        x_b_max's distance: the exit side's elements squeezed by at most 2)."""
        rp = self.rp
        past = min(past_gap * rp.contact_length, 0.5 * (self.x_b_max - rp.axis_x))
        return (rp.axis_x - 0.5 * rp.contact_length, rp.axis_x + past)

    def exit_anchor(self, x_e: float) -> float:
        """Where the exit side's stretch ends for a contact end at x_e: x_b, or twice the end's
        distance past the gap where that is further (at most x_b_max), so that the elements
        between the gap and it are squeezed by at most a factor 2 (with x_b fixed, a wrap held
        at half a contact length past the gap squeezed them to nothing)."""
        a = self.rp.axis_x
        return min(max(self.x_b, a + 2.0 * (x_e - a)), self.x_b_max)

    def stretch(self, X: np.ndarray, x_c: float, x_e: float | None = None) -> np.ndarray:
        """Piecewise-linear in x: x_a and the exit anchor (``exit_anchor(x_e)``) stay, the
        reference touching point goes to x_c, the reference gap X_roll to the contact's end x_e
        (default X_roll)."""
        rp, xa = self.rp, self.x_a
        x_e = rp.axis_x if x_e is None else x_e
        xb = self.exit_anchor(x_e)
        x = X.copy()
        a = (X > xa) & (X <= rp.x_touch)
        x[a] = xa + (X[a] - xa) * (x_c - xa) / (rp.x_touch - xa)
        b = (X > rp.x_touch) & (X < rp.axis_x)
        x[b] = x_c + (X[b] - rp.x_touch) * (x_e - x_c) / (rp.axis_x - rp.x_touch)
        c = (X >= rp.axis_x) & (X < xb)
        x[c] = x_e + (X[c] - rp.axis_x) * (xb - x_e) / (xb - rp.axis_x)
        return x

    def displacement(self, shape: StripShape) -> np.ndarray:
        """Coefficient vector of the P2 displacement that maps the reference mesh onto ``shape``:
        the arc's chain of edges on the roll from x_c to x_e, the free tops on their curves."""
        return self.nodes.coefficients((self.positions(shape) - self.nodes.X0).T)

    def positions(self, shape: StripShape) -> np.ndarray:
        """The P2 nodes' positions (N, 2) on ``shape`` (``displacement``)."""
        rp, X = self.rp, self.P[:, 0]
        x = self.stretch(X, shape.x_c, shape.x_e)
        H = roll_height(self.roll, x)
        ent, ex = X < rp.x_touch, X >= rp.axis_x
        H[ent] = np.interp(x[ent], shape.entry_x, shape.entry_y)
        # the exit top starts at the contact's end, on the roll
        H[ex] = np.where(x[ex] <= shape.exit_x[0], H[ex],
                         np.interp(x[ex], shape.exit_x, shape.exit_y))
        return np.stack([x, self.P[:, 1] * H / self.H_ref], axis=1)


#: ``_trace``: the cubic's stencil where its node spacings are within this ratio of each other
SPACING = 0.1


def _trace(xs: np.ndarray, slope: np.ndarray, y0: float) -> np.ndarray:
    """Streamline heights on dy/dx = slope from y0 at xs[0] (increasing): each step the
    integral of the slope's cubic through the four nearest nodes (two each side; the
    quadratic through three at the ends, the trapezoid with two or where the stencil's
    spacings differ more than ``SPACING``), by two-point Gauss (exact for a cubic). Measured
    against the trapezoidal rule before it (session of 2026-11-29 20:46): the roughing slab's
    top leaked 1.3e-4 of the inflow, now 2e-5."""
    xs, slope = np.asarray(xs, dtype=float), np.asarray(slope, dtype=float)
    n = len(xs)
    y = np.full(n, float(y0))
    if n < 2:
        return y
    H = np.diff(xs)
    inc = 0.5 * (slope[:-1] + slope[1:]) * H          # the trapezoid
    if n > 2:
        width = min(n, 4)
        lo = np.clip(np.arange(n - 1) - 1, 0, n - width)       # each stencil's first node
        stencil = lo[:, None] + np.arange(width)
        xk, sk = xs[stencil], slope[stencil]
        # a stencil with a spacing below SPACING of its largest (the contact's end a hair
        # before a node) keeps the trapezoid: its Lagrange weights grow as 1 / that spacing
        gaps = np.diff(xk, axis=1)
        ok = gaps.min(axis=1) >= SPACING * gaps.max(axis=1)
        xk, sk, x0, h = xk[ok], sk[ok], xs[:-1][ok], H[ok]
        g = 0.5 / np.sqrt(3.0)
        cubic = np.zeros(len(h))
        for a in (0.5 - g, 0.5 + g):                  # the Gauss points on [x_i, x_i+1]
            t = x0 + a * h
            for k in range(width):                    # Lagrange's basis at t
                basis = np.ones(len(h))
                for j in range(width):
                    if j != k:
                        basis *= (t - xk[:, j]) / (xk[:, k] - xk[:, j])
                cubic += 0.5 * h * basis * sk[:, k]
        inc[ok] = cubic
    y[1:] = y0 + np.cumsum(inc)
    return y


def kinematic_update(rp: RollPass, shape: StripShape, x: np.ndarray, v: np.ndarray,
                     part: np.ndarray, x_up: float, bounds: tuple[float, float]):
    """One fixed-point update of the free tops from the flow at the top nodes.

    ``x``, ``v``: positions and velocities of the top P2 nodes, sorted by x; ``part``: 0 entry
    free top, 1 contact, 2 exit free top. The entry top is traced from the entry thickness at
    ``x_up`` (upstream the strip is rigid and flat) to the first contact node; the exit top from
    the contact's end x_e on the roll (``StripShape.end``; it moves by ``ContactEndSearch``).
    Returns (new shape, residual in m): the residual is the largest distance between a traced
    top and the current one (the gap at the contact start included).
    """
    vx = np.where(np.abs(v[:, 0]) > 1e-300, v[:, 0], 1e-300)
    slope = v[:, 1] / vx
    # entry: free nodes from x_up, then the contact start node
    ent = np.nonzero((part == 0) & (x[:, 0] >= x_up))[0]
    first = np.nonzero(part == 1)[0][0]
    idx = np.append(ent, first)
    xs = x[idx, 0]
    eta = _trace(xs, slope[idx], rp.half_entry)
    x_c = shape.x_c
    gap = eta[-1] - float(roll_height(rp, x_c))
    lo, hi = bounds
    x_new = float(np.clip(x_c + gap / roll_slope(rp, x_c), lo, hi))
    # the traced sag, as a function of the distance to the contact start, moves with it; a
    # linear blend from x_up closes the remaining gap at the new contact start
    dist, sag = x_c - xs, rp.half_entry - eta
    ent_x = np.concatenate([[x_up - 1e3], x_new - dist])
    ent_y = np.concatenate([[rp.half_entry], rp.half_entry - sag])
    w = np.clip((ent_x - x_up) / max(x_new - x_up, 1e-300), 0.0, 1.0)
    ent_y += w * (float(roll_height(rp, x_new)) - ent_y[-1])
    residual = float(np.max(np.abs(eta - x[idx, 1])))
    # exit: from the contact's end on the roll along the nodes after it (the exit top's, and
    # the contact's beyond a new end: their flow is the free top's there)
    end = shape.end(rp)
    ex = np.nonzero((part != 0) & (x[:, 0] > end))[0]
    xs2 = np.concatenate([[end], x[ex, 0]])
    s_end = np.interp(end, x[part != 0, 0], slope[part != 0])
    eta2 = _trace(xs2, np.concatenate([[s_end], slope[ex]]), float(roll_height(rp, end)))
    free = part[ex] == 2
    if free.any():
        residual = max(residual, float(np.max(np.abs(eta2[1:][free] - x[ex][free, 1]))))
    ex_x = np.concatenate([xs2, [xs2[-1] + 1e3]])
    ex_y = np.concatenate([eta2, [eta2[-1]]])
    return StripShape(x_new, ent_x, ent_y, ex_x, ex_y, shape.x_e), residual


class ContactEndSearch:
    """The contact's end x_e as a root of p_end(x_e), the contact pressure at the arc's last
    vertex (which the map puts at x_e), one step per coupling update (``step``).

    Unilateral contact ends where the pressure falls to zero (a smooth separation: the
    multiplier at the end vertex vanishes) or at the gap (the upper bound) with p >= 0 there:
    p_end >= 0, X_roll - x_e >= 0, p_end (X_roll - x_e) = 0. A step goes to the zero of the
    pressure's line through the last two vertices (a tensile vertex before the end: to the
    first zero crossing after the peak, however far); once the last update lies within an
    element, along the secant through the two (x_e, p_end) instead (p_end(x_e) falls about
    twice as steeply as the pressure along the arc: the line alone overshot, p_end alternating
    in sign and shrinking by only 0.7 an update), unless that secant is less than a quarter
    as steep as the line (the flow's noise on two nearly equal p_end). A step is at most ``trust`` long: one
    element, halved whenever p_end changes sign (the root lies behind) and doubled back
    towards an element only while |p_end| falls on the same side (a trust that grew whenever
    the sign held let a search near the gap cycle with period four). p_end is read from a
    flow converged to the coupling threshold and, at the gap, from a P1 multiplier that averages the rigid-plastic
    strip's pressure jump there: near the gap it need not be monotone (a pass rolled by the
    PyRolL plugin cycled between the gap and 0.1 element before it), and the halving ends such
    a search at a sign change of p_end in a bounded number of updates."""

    #: an elastic strip's first steps (``winkler``) may reach this many elements
    WINKLER_ELEMENTS = 4.0

    def __init__(self):
        self.last: tuple[float, float] | None = None
        self.trust: float | None = None
        self.signs = 0           # sign changes of p_end so far

    def step(self, x: np.ndarray, pressure: np.ndarray, bounds: tuple[float, float],
             winkler: Callable[[float, float], float] | None = None) -> tuple[float, float]:
        """(new x_e clipped to ``bounds``, the residual: its distance from the current end, m)
        from the pressure at the arc's vertices (``x`` increasing, the last at the end).
        ``winkler(x, p)``: an elastic strip's end predicted from a vertex in its elastic exit
        zone (where the rising roll has taken up the strip's elastic recovery c_e p), taken
        until p_end first changes sign, up to ``WINKLER_ELEMENTS`` elements a step; None where
        it predicts nothing (an end before the gap: the steps of a rigid-plastic strip)."""
        lo_b, hi_b = bounds
        p = np.asarray(pressure, dtype=float)
        x = np.asarray(x, dtype=float)
        x_e, p_e = float(x[-1]), float(p[-1])
        h = x_e - float(x[-2])                         # the last element's length
        if self.last is not None and (self.last[1] < 0.0) != (p_e < 0.0):
            self.signs += 1
        predicted = (winkler(x_e, p_e) if winkler is not None and self.signs == 0 and p_e > 0.0
                     else None)
        if predicted is not None:
            new = float(np.clip(predicted, x_e, x_e + self.WINKLER_ELEMENTS * h))
            self.last, self.trust = (x_e, p_e), h
            new = float(np.clip(new, lo_b, hi_b))
            return new, abs(new - x_e)
        peak = int(np.argmax(p))
        neg = np.flatnonzero(p[:-1] < 0.0)
        neg = neg[neg > peak]
        last, self.last = self.last, (x_e, p_e)
        if len(neg):             # tensile before the end: the first crossing after the peak
            i = int(neg[0])
            self.trust = h
            new = float(np.clip(x[i - 1] + p[i - 1] * (x[i] - x[i - 1]) / (p[i - 1] - p[i]),
                                lo_b, hi_b))
            return new, abs(new - x_e)
        if p[-2] > p_e:          # falling towards the end: where its line reaches zero
            new = x_e + p_e * h / (p[-2] - p_e)
        else:                    # not falling: the contact goes on
            new = x_e + (h if p_e >= 0.0 else -h)
        trust = h if self.trust is None else self.trust
        if last is not None:
            xo, po = last
            slope = (p_e - po) / (x_e - xo) if x_e != xo else 0.0
            # the secant only where it falls at least a quarter as steeply as the pressure's
            # line: flatter, it is the flow's noise on two nearly equal p_end (two ends 2 um
            # apart with a wrapping strip's p_end 3.36e-3 and 3.35e-3 K sent the end a
            # trust's 0.6 mm on, and it never settled)
            if (0.0 < abs(x_e - xo) <= h and slope < 0.0
                    and -slope >= 0.25 * max(p[-2] - p_e, 0.0) / h):
                new = x_e - p_e * (x_e - xo) / (p_e - po)
            if (po < 0.0) != (p_e < 0.0):
                trust *= 0.5
            elif abs(p_e) < abs(po):       # same side and closer: the trust grows back
                trust = min(2.0 * trust, h)
        self.trust = trust
        new = float(np.clip(min(max(new, x_e - trust), x_e + trust), lo_b, hi_b))
        return new, abs(new - x_e)
