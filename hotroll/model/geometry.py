"""Roll and plate geometry of one flat-rolling pass (report Section 4, Fig. 1).

Half model: y = 0 is the symmetry axis, the upper roll has its centre at
(axis_x, half_exit + R) and turns so that its lowest point moves in +x.

A flattened roll (``[roll] model``, docs/theory.md 1f) keeps its centre: its surface is
r(theta) = R + w(theta) about it (``RollShape``), w normalised so that the lowest point of the
surface stays at the gap (the roll's approach goes into the gap, not into w); its rim moves at
omega R (1 + e_tt(theta)), e_tt the rim's hoop strain. Without a shape the roll is the rigid
circle and every method below is the circle's formula.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np


class RollShape:
    """The flattened roll's surface r(theta) = R + w(theta) and its rim strain, tabled at
    increasing angles and interpolated by cubic splines (constant beyond the table). Mutable:
    the roll coupling updates it in place (``set``), and every ``RollPass`` holding it follows."""

    def __init__(self, theta, w, hoop=None, tie: float = 0.0):
        #: heights (m) within which two lowest points count as equal: the exit is then the one
        #: nearest the last exit (``lowest``); 0: always the lowest
        self.tie = tie
        self._previous_t: float | None = None
        self.set(theta, w, hoop)

    def set(self, theta, w, hoop=None) -> None:
        from scipy.interpolate import CubicSpline

        theta = np.asarray(theta, dtype=float)
        w = np.asarray(w, dtype=float)
        hoop = np.zeros_like(w) if hoop is None else np.asarray(hoop, dtype=float)
        if theta.ndim != 1 or len(theta) < 4 or w.shape != theta.shape or hoop.shape != theta.shape:
            raise ValueError("a roll shape needs at least 4 angles and one w and hoop strain each")
        if np.any(np.diff(theta) <= 0.0):
            raise ValueError("a roll shape's angles must increase")
        self.theta, self.w, self.hoop = theta.copy(), w.copy(), hoop.copy()
        last = getattr(self, "_lowest", None)
        if last is not None:
            self._previous_t = last[1]
        self._lowest: tuple | None = None
        self.cache: dict = {}      # what a RollPass derives from this shape (its bite angle)
        self._w = CubicSpline(theta, w, bc_type="clamped")
        self._dw = self._w.derivative()
        self._hoop = CubicSpline(theta, hoop, bc_type="clamped")

    def _clip(self, theta):
        return np.clip(theta, self.theta[0], self.theta[-1])

    def offset(self, theta):
        """w(theta), m."""
        return self._w(self._clip(theta))

    def slope(self, theta):
        """dw/dtheta, m/rad (0 beyond the table)."""
        t = np.asarray(theta, dtype=float)
        inside = (t >= self.theta[0]) & (t <= self.theta[-1])
        return np.where(inside, self._dw(self._clip(t)), 0.0)

    def strain(self, theta):
        """The rim's hoop strain e_tt(theta), -."""
        return self._hoop(self._clip(theta))

    def lowest(self, radius: float) -> tuple[float, float]:
        """(t_min, r(t_min)): the angle of the surface's lowest point, where (R + w) cos t is
        largest (cached until the shape changes). Where the surface is flat to within ``tie``
        (several local lowest points less than ``tie`` above the lowest), the one nearest the
        last shape's: the exit moves continuously instead of jumping between near-equal dips
        (a thin strip's flat zone, docs/theory.md 1f)."""
        if self._lowest is None or self._lowest[0] != radius:
            from scipy.optimize import minimize_scalar

            t = self.theta
            h = (radius + self.w) * np.cos(t)
            i = int(np.argmax(h))
            if self.tie > 0.0 and self._previous_t is not None:
                peak = np.r_[h[0] >= h[1], (h[1:-1] >= h[:-2]) & (h[1:-1] >= h[2:]),
                             h[-1] >= h[-2]]
                near = np.flatnonzero(peak & (h >= h[i] - self.tie))
                i = int(near[np.argmin(np.abs(t[near] - self._previous_t))])
            lo, hi = t[max(i - 1, 0)], t[min(i + 1, len(t) - 1)]
            res = minimize_scalar(lambda a: -(radius + float(self.offset(a))) * math.cos(a),
                                  bounds=(lo, hi), method="bounded",
                                  options={"xatol": 1e-13 * max(1.0, abs(hi - lo))})
            self._lowest = (radius, float(res.x), radius + float(self.offset(res.x)))
        return self._lowest[1], self._lowest[2]

    def copy(self) -> "RollShape":
        """The same surface, on its own (``set`` on either leaves the other): it shares the
        splines, which ``set`` replaces and nothing changes in place (a copy is taken at every
        roll update; building the splines again cost as much as the update's own)."""
        out = RollShape.__new__(RollShape)
        out.tie, out._previous_t = self.tie, self._previous_t
        out.theta, out.w, out.hoop = self.theta.copy(), self.w.copy(), self.hoop.copy()
        out._lowest, out.cache = None, {}
        out._w, out._dw, out._hoop = self._w, self._dw, self._hoop
        return out

    @property
    def max_offset(self) -> float:
        return float(np.max(np.abs(self.w)))

    @classmethod
    def circle(cls, radius: float, flattened: float, theta) -> "RollShape":
        """Hitchcock's flattened roll: the circle of radius R' >= R through the rigid roll's
        lowest point, seen from the rigid roll's centre: r = -D cos t + sqrt(R'^2 - D^2 sin^2 t),
        D = R' - R."""
        theta = np.asarray(theta, dtype=float)
        D = flattened - radius
        r = -D * np.cos(theta) + np.sqrt(flattened**2 - (D * np.sin(theta)) ** 2)
        return cls(theta, r - radius)


@dataclass(frozen=True)
class RollPass:
    """Geometry and kinematics of the roll gap (all SI)."""

    radius: float          # R, m
    half_entry: float      # plate half-thickness before the bite, m
    half_exit: float       # roll-gap half-height, m
    omega: float           # roll angular velocity, rad/s
    axis_x: float = 1.0    # x of the roll axis (the report's frame: 1.0)
    shape: RollShape | None = field(default=None, compare=False)   # a flattened roll

    @property
    def centre(self) -> tuple[float, float]:
        """The roll's axis: at X_roll, the gap plus R above the axis; a flattened roll's is
        shifted in x so that its surface's lowest point (the gap) is at X_roll."""
        if self.shape is None:
            return (self.axis_x, self.half_exit + self.radius)
        t, r = self.shape.lowest(self.radius)
        return (self.axis_x + r * math.sin(t), self.half_exit + self.radius)

    @property
    def u_roll(self) -> float:
        """|U_roll,tau| = omega R, the roll surface speed."""
        return self.omega * self.radius

    @property
    def draft(self) -> float:
        return self.half_entry - self.half_exit

    @property
    def x_touch(self) -> float:
        """First touching point of the initial (maximum-contact) configuration."""
        cy = self.centre[1]
        if self.shape is None:
            return self.axis_x - math.sqrt(self.radius**2 - (cy - self.half_entry) ** 2)
        # cached with the shape, as the bite angle (asked for thousands of times a pass: the
        # soft zone, the contact length)
        key = ("touch", self.radius, self.half_entry, self.half_exit, self.axis_x)
        cached = self.shape.cache.get(key)
        if cached is None:
            t = self.bite_angle
            cached = self.shape.cache[key] = self.centre[0] - float(self.surface_radius(t)) \
                * math.sin(t)
        return cached

    @property
    def contact_length(self) -> float:
        """Projected contact length l_c = axis_x - x_touch; a rigid roll's computed without
        axis_x (the same bits wherever the frame puts the roll: the steady mesh's lengths
        follow from it, and netgen's mesh around a refined contact start changed with their
        last bit: Case R's force 1.1e-4 apart with the axis at 1 m and at -7.5 m, now 2e-10).
        A flattened roll's keeps the difference (its lowest point's choice between near-equal
        dips remembers the last call: asked for here, the swapped stand's mirror moved 3e-9)."""
        if self.shape is None:
            return math.sqrt(self.radius**2 - (self.centre[1] - self.half_entry) ** 2)
        return self.axis_x - self.x_touch

    @property
    def rigid_bite_angle(self) -> float:
        """acos(1 - dh / 2R): the bite angle of the rigid roll (the pass's geometry alone)."""
        return math.acos(1.0 - self.draft / self.radius)

    @property
    def bite_angle(self) -> float:
        """The angle of the first touching point: the surface's height there is the entry's."""
        if self.shape is None:
            return self.rigid_bite_angle
        key = ("bite", self.radius, self.half_entry, self.half_exit)
        cached = self.shape.cache.get(key)
        if cached is None:
            cached = self.shape.cache[key] = self._flattened_bite_angle()
        return cached

    def _flattened_bite_angle(self) -> float:
        from scipy.optimize import brentq

        cy = self.centre[1]
        rigid = self.rigid_bite_angle

        def above_entry(t):
            return cy - float(self.surface_radius(t)) * math.cos(t) - self.half_entry

        hi = rigid
        while above_entry(hi) < 0.0:
            hi = min(2.0 * hi, 0.5 * math.pi)
            if hi == 0.5 * math.pi:
                break
        return brentq(above_entry, 0.0, hi, xtol=1e-15 * max(1.0, hi))

    @property
    def soft_zone(self) -> tuple[float, float]:
        """Interval I of Table 1 around the first touching point, where the penalties are softer.

        The report's I = [0.75, 0.775] is [x_touch - 0.0425 l_c, x_touch + 0.0617 l_c] for its
        geometry; we keep those fractions of the contact length for other geometries.
        """
        lc = self.contact_length
        return (self.x_touch - 0.0425 * lc, self.x_touch + 0.0617 * lc)

    # --- point-wise helpers (numpy, vectorised over rows of xy) ---------------------------
    def surface_radius(self, theta):
        """r(theta) = R + w(theta): the surface's distance from the centre (R when rigid)."""
        if self.shape is None:
            return self.radius + 0.0 * np.asarray(theta, dtype=float)
        return self.radius + self.shape.offset(theta)

    def surface_speed(self, xy: np.ndarray) -> np.ndarray:
        """The rim's speed omega R (1 + e_tt) at the points' angles (omega R when rigid)."""
        if self.shape is None:
            return self.u_roll + 0.0 * np.asarray(xy, dtype=float)[..., 0]
        return self.u_roll * (1.0 + self.shape.strain(self.angle(xy)))

    @property
    def gap_radius(self) -> float:
        """The radius of curvature (m) of the roll's surface at its lowest point: R for the
        rigid roll; a flattened roll's r(t) = R + w(t) there, (r^2 + r'^2)^1.5 / (r^2 + 2 r'^2
        - r r'')."""
        if self.shape is None:
            return self.radius
        t, r = self.shape.lowest(self.radius)
        d1 = float(self.shape.slope(t))
        d2 = float(self.shape._dw.derivative()(t))
        den = r * r + 2.0 * d1 * d1 - r * d2
        return (r * r + d1 * d1) ** 1.5 / den if den > 0.0 else math.inf

    def height(self, x) -> np.ndarray:
        """The height of the roll's lower surface at x (its lowest point: the gap)."""
        cx, cy = self.centre
        x = np.asarray(x, dtype=float)
        if self.shape is None:
            return cy - np.sqrt(np.maximum(self.radius**2 - (x - cx) ** 2, 0.0))
        t = np.arcsin(np.clip((cx - x) / self.radius, -1.0, 1.0))
        for _ in range(30):        # Newton on x = cx - r(t) sin t
            r = self.surface_radius(t)
            f = cx - r * np.sin(t) - x
            step = f / (self.shape.slope(t) * np.sin(t) + r * np.cos(t))
            t = t + step
            if np.max(np.abs(step), initial=0.0) < 1e-15:
                break
        return cy - self.surface_radius(t) * np.cos(t)

    def signed_distance(self, xy: np.ndarray) -> np.ndarray:
        """Distance to the roll surface, negative inside the roll (penetration); for a
        flattened roll the radial distance |x - c| - r(theta)."""
        c = np.asarray(self.centre)
        if self.shape is None:
            return np.linalg.norm(np.asarray(xy) - c, axis=-1) - self.radius
        return np.linalg.norm(np.asarray(xy) - c, axis=-1) - self.surface_radius(self.angle(xy))

    def project(self, xy: np.ndarray) -> np.ndarray:
        """Projection Pi onto the roll surface, (3.9): orthogonal onto the circle; radial onto
        a flattened roll's surface."""
        c = np.asarray(self.centre)
        d = np.asarray(xy, dtype=float) - c
        r = np.linalg.norm(d, axis=-1, keepdims=True)
        if self.shape is None:
            return c + self.radius * d / r
        return c + self.surface_radius(self.angle(xy))[..., None] * d / r

    def tilt(self, xy: np.ndarray) -> np.ndarray:
        """beta = atan(r'/r): the angle between a flattened roll's normal and the radius
        (0 when rigid); normal = n0 cos beta - t0 sin beta, tangent = n0 sin beta + t0 cos beta
        with n0, t0 the circle's."""
        if self.shape is None:
            return 0.0 * np.asarray(xy, dtype=float)[..., 0]
        t = self.angle(xy)
        return np.arctan2(self.shape.slope(t), self.surface_radius(t))

    def angle(self, xy: np.ndarray) -> np.ndarray:
        """Angle from the roll's vertical centre line, positive towards the entry."""
        xy = np.asarray(xy, dtype=float)
        cx, cy = self.centre
        return np.arctan2(cx - xy[..., 0], cy - xy[..., 1])

    def tangent(self, xy: np.ndarray) -> np.ndarray:
        """Unit tangent of the roll surface in the direction of U_roll."""
        xy = np.asarray(xy, dtype=float)
        cx, cy = self.centre
        t = np.stack([-(xy[..., 1] - cy), xy[..., 0] - cx], axis=-1)
        t = t / np.linalg.norm(t, axis=-1, keepdims=True)
        if self.shape is None:
            return t
        d = np.asarray(self.centre) - xy
        n = d / np.linalg.norm(d, axis=-1, keepdims=True)
        b = self.tilt(xy)[..., None]
        return n * np.sin(b) + t * np.cos(b)

    def normal(self, xy: np.ndarray) -> np.ndarray:
        """Unit normal pointing from the plate into the roll (outward for the plate)."""
        xy = np.asarray(xy, dtype=float)
        d = np.asarray(self.centre) - xy
        n = d / np.linalg.norm(d, axis=-1, keepdims=True)
        if self.shape is None:
            return n
        cx, cy = self.centre
        t = np.stack([-(xy[..., 1] - cy), xy[..., 0] - cx], axis=-1)
        t = t / np.linalg.norm(t, axis=-1, keepdims=True)
        b = self.tilt(xy)[..., None]
        return n * np.cos(b) - t * np.sin(b)


def auto_contact_size(rp: RollPass) -> float:
    """``h_contact = "auto"``: l_c/12 and at most a sixth of the exit half-thickness, the
    coarsest size whose steady roll force is within 1 % of the mesh-converged value in the
    refinement studies of docs/theory.md 4e (Example 1: within 0.2 %)."""
    return min(rp.contact_length / 12.0, rp.half_exit / 6.0)
