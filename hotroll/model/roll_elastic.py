"""The work roll's elasticity: Hitchcock's flattened radius and the plane-strain elastic disc
under the contact tractions the strip solve gives (docs/theory.md 1f).

- ``RollElasticity.hitchcock_ratio``: R'/R = 1 + C F'/dh, C = 16 (1 - nu^2) / (pi E), F' the
  roll force per unit width, dh the full draught (Hitchcock 1935; an elliptical pressure on an
  elastic half-space, the flattened arc kept circular).
- ``ElasticDisc``: the surface displacement of a solid elastic disc (plane strain) of radius R
  under a normal pressure p(theta) and a shear q(theta) on its rim, by the disc's Fourier
  solution (Michell's stress functions r^n cos n theta, r^(n+2) cos n theta; derived and checked
  in docs/notes/elastic-roll-and-pyroll-research.md 2): for the mode n >= 2, with
  mu = E / (2 (1 + nu)), a_n = ((2n - 1) - 2 (n - 1) nu) / (2 (n^2 - 1)) and
  b_n = (2 (n - 1) nu - (n - 2)) / (2 (n^2 - 1)),

      p = P cos(n t + f), q = Q sin(n t + f)  ->
      u_r = -(R/mu) (a_n P + b_n Q) cos(n t + f),  u_t = (R/mu) (b_n P + a_n Q) sin(n t + f);

  n = 0: u_r = -(1 - 2 nu) R P / (2 mu) (the mean pressure). For large n, a_n -> (1 - nu)/n:
  Flamant's half-plane kernel; the disc's finite radius is in the rest. The mean shear (the
  drive torque) and the n = 1 modes (the net force) are carried by the roll's supports (the
  bearings, the backup roll): on the rim they move the arc as a rigid body plus an O(F'/E) cos
  theta term, which changes R' by less than 1e-4 R for F' < 20 MN/m; left out, the roll's
  approach goes into the gap (the profile's lowest point is put at the exit gauge).

Angles: theta from the roll's lowest point, positive towards the entry (``RollPass.angle``);
u_r outward, u_t along d/d theta; p > 0 presses the roll, q > 0 pushes the rim towards +theta.
The tractions are given at nodes and taken piecewise linear between them, zero outside; the
series is summed by an FFT on a uniform grid fine enough for the nodes (``grid_points``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: steel work rolls (forged or cast steel; docs/notes/elastic-roll-and-pyroll-research.md 1)
STEEL_E, STEEL_NU = 210e9, 0.3


@dataclass(frozen=True)
class RollElasticity:
    """Young's modulus (Pa) and Poisson's ratio of the roll."""

    E: float = STEEL_E
    nu: float = STEEL_NU

    def __post_init__(self):
        if not (math.isfinite(self.E) and self.E > 0.0):
            raise ValueError(f"the roll's Young's modulus must be a positive number of Pa, not {self.E}")
        if not 0.0 <= self.nu < 0.5:
            raise ValueError(f"the roll's Poisson's ratio must be in [0, 0.5), not {self.nu}")

    @property
    def shear_modulus(self) -> float:
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def hitchcock_constant(self) -> float:
        """C = 16 (1 - nu^2) / (pi E), 1/Pa."""
        return 16.0 * (1.0 - self.nu**2) / (math.pi * self.E)

    def hitchcock_ratio(self, force_per_width: float, draught: float) -> float:
        """R'/R = 1 + C F'/dh: F' the roll force per unit width (N/m), dh = h0 - h1 (m)."""
        if not draught > 0.0:
            raise ValueError(f"Hitchcock's radius needs a positive draught, not {draught} m")
        return 1.0 + self.hitchcock_constant * force_per_width / draught

    def hertz_half_width(self, force_per_width: float, radius: float) -> float:
        """b = sqrt(4 F' R / (pi E*)), E* = E / (1 - nu^2): the roll on a rigid flat (Johnson 4.2)."""
        e_star = self.E / (1.0 - self.nu**2)
        return math.sqrt(4.0 * force_per_width * radius / (math.pi * e_star))


class ElasticDisc:
    """The rim displacement of the plane-strain elastic disc (the roll) under rim tractions."""

    def __init__(self, radius: float, elasticity: RollElasticity = RollElasticity()):
        if not radius > 0.0:
            raise ValueError(f"the roll radius must be positive, not {radius} m")
        self.radius, self.elasticity = radius, elasticity

    def grid_points(self, theta: np.ndarray) -> int:
        """A power of two with at least 16 grid points per smallest node spacing (and 2^14)."""
        spacing = np.diff(np.sort(theta))
        spacing = spacing[spacing > 0.0]
        smallest = spacing.min() if len(spacing) else 2.0 * math.pi / 2**14
        need = 16.0 * 2.0 * math.pi / smallest
        return int(2 ** max(14, math.ceil(math.log2(need))))

    def responses(self, n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(a_n, b_n) of the module docstring, zero for n < 2 (the supports' modes)."""
        nu = self.elasticity.nu
        n = np.asarray(n, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            den = 2.0 * (n**2 - 1.0)
            a = np.where(n >= 2, ((2 * n - 1) - 2 * (n - 1) * nu) / den, 0.0)
            b = np.where(n >= 2, (2 * (n - 1) * nu - (n - 2)) / den, 0.0)
        return a, b

    def rim(self, theta: np.ndarray, pressure: np.ndarray, shear: np.ndarray | None = None,
            at: np.ndarray | None = None) -> dict[str, np.ndarray]:
        """The rim's displacement under the nodal tractions (Pa) at the angles ``theta`` (rad,
        increasing), piecewise linear between the nodes and zero outside them; at the angles
        ``at`` (default: the nodes). Returns u_r and u_t (m) and the hoop strain
        e_tt = (u_r + du_t/dtheta) / R of the rim (-)."""
        theta = np.asarray(theta, dtype=float)
        p = np.asarray(pressure, dtype=float)
        q = np.zeros_like(p) if shear is None else np.asarray(shear, dtype=float)
        if theta.ndim != 1 or p.shape != theta.shape or q.shape != theta.shape:
            raise ValueError("theta, pressure and shear must be 1-D arrays of one length")
        if np.any(np.diff(theta) <= 0.0) or theta[0] <= -math.pi or theta[-1] >= math.pi:
            raise ValueError("the load's angles must increase strictly within (-pi, pi)")
        at = theta if at is None else np.asarray(at, dtype=float)
        N = self.grid_points(theta)
        grid = -math.pi + 2.0 * math.pi * np.arange(N) / N
        P = np.fft.rfft(np.interp(grid, theta, p, left=0.0, right=0.0))
        Q = np.fft.rfft(np.interp(grid, theta, q, left=0.0, right=0.0))
        n = np.arange(len(P))
        a, b = self.responses(n)
        c = self.radius / self.elasticity.shear_modulus
        Ur = -c * (a * P + 1j * b * Q)
        Ut = c * (-1j * b * P + a * Q)
        Ur[0] = -c * 0.5 * (1.0 - 2.0 * self.elasticity.nu) * P[0]     # the mean pressure
        hoop = (Ur + 1j * n * Ut) / self.radius
        out = {}
        for key, spec in (("u_r", Ur), ("u_t", Ut), ("hoop", hoop)):
            values = np.fft.irfft(spec, N)
            out[key] = np.interp(at, np.append(grid, math.pi), np.append(values, values[0]))
        return out


ROLL_MODELS = ("rigid", "hitchcock", "elastic")


class FlatteningRoll:
    """The flattening work roll of one pass: its surface (``RollShape``, shared with the
    ``RollPass`` the solver uses) updated in place from the contact tractions of the current
    strip solution, with under-relaxation.

    - ``"hitchcock"``: the circle of radius R' = R (1 + C F'/dh) through the gap (F' the roll
      force per unit width from the pressure and shear, dh = h0 - h1);
    - ``"elastic"``: the rim of the elastic disc (``ElasticDisc``) under the nodal pressure and
      shear, its constant part (the approach) dropped so that the surface's lowest point stays
      at the gap.
    """

    def __init__(self, rp, kind: str, elasticity: RollElasticity = RollElasticity(),
                 relaxation: float = 1.0, points: int = 240):
        from hotroll.model.geometry import RollShape

        if kind not in ("hitchcock", "elastic"):
            raise ValueError(f"roll.model must be 'hitchcock' or 'elastic' here, not {kind!r}")
        if not 0.0 < relaxation <= 1.0:
            raise ValueError(f"roll.relaxation must be in (0, 1], not {relaxation}")
        if rp.shape is None:
            raise ValueError("the pass's RollPass needs a RollShape to flatten")
        self.rp, self.kind, self.elasticity, self.relaxation = rp, kind, elasticity, relaxation
        self.disc = ElasticDisc(rp.radius, elasticity)
        self.points = points
        self.shape: RollShape = rp.shape
        self.updates = 0
        #: the last update's largest move of the arc the strip lies on (m), set by the roll's
        #: coupling (``solvers/couplings.py: RollFlattening``, which measures it)
        self.last_move = 0.0

    @classmethod
    def start(cls, rp, kind: str, elasticity: RollElasticity = RollElasticity(),
              relaxation: float = 1.0, force_per_width: float | None = None,
              tie: float = 0.0):
        """A RollPass with a shape (Hitchcock's circle for ``force_per_width``, else the rigid
        circle) and the FlatteningRoll that updates it; ``tie`` (m): heights within which two
        lowest points of the surface count as equal (``RollShape.lowest``)."""
        from dataclasses import replace

        from hotroll.model.geometry import RollShape

        ratio = 1.0
        if force_per_width is not None:
            ratio = elasticity.hitchcock_ratio(force_per_width, 2.0 * rp.draft)
        theta = cls.table(rp, math.sqrt(ratio) * rp.bite_angle)
        shape = RollShape.circle(rp.radius, ratio * rp.radius, theta)
        shape.tie = tie
        shaped = replace(rp, shape=shape)
        return shaped, cls(shaped, kind, elasticity, relaxation)

    @staticmethod
    def table(rp, bite: float, points: int = 240) -> np.ndarray:
        """The shape's angles: from half a bite angle past the gap to 2.5 bite angles."""
        return np.linspace(-0.5 * bite, 2.5 * bite, points)

    def target(self, theta, pressure, shear, force=None) -> tuple[np.ndarray, np.ndarray,
                                                                    np.ndarray]:
        """(angles, w, hoop strain) of the roll under the nodal tractions (Pa) at the contact
        angles ``theta`` (increasing); Hitchcock's takes the roll force per unit width ``force``
        (N/m; default: the tractions' resultant)."""
        from hotroll.model.geometry import RollShape

        rp = self.rp
        grid = self.table(rp, max(rp.bite_angle, float(np.max(theta))), self.points)
        if self.kind == "hitchcock":
            if force is None:
                force = self.force_per_width(theta, pressure, shear)
            ratio = max(1.0, self.elasticity.hitchcock_ratio(force, 2.0 * rp.draft))
            circle = RollShape.circle(rp.radius, ratio * rp.radius, grid)
            return grid, circle.w, np.zeros_like(grid)
        out = self.disc.rim(theta, pressure, shear, at=grid)
        return grid, self._at_gap(grid, out["u_r"]), out["hoop"]

    def _at_gap(self, grid, w) -> np.ndarray:
        """w minus the constant c that puts the lowest point at the gap: max (R + w - c) cos t
        = R."""
        R, c = self.rp.radius, 0.0
        for _ in range(20):
            step = float(np.max((R + w - c) * np.cos(grid))) - R
            c += step
            if abs(step) < 1e-15 * R:
                break
        return w - c

    def carry(self, other: "FlatteningRoll") -> None:
        """Start from ``other``'s settled surface (a similar pass's roll, schedules): its w and
        hoop strain at the same fraction of the bite angle, the lowest point put at this gap.
        Only a start: the updates carry the surface to this pass's own."""
        if other.kind != self.kind:
            return
        src, grid = other.shape, self.shape.theta
        ratio = other.rp.rigid_bite_angle / self.rp.rigid_bite_angle
        w = np.interp(grid * ratio, src.theta, src.w)
        hoop = np.interp(grid * ratio, src.theta, src.hoop)
        self.shape.set(grid, self._at_gap(grid, w) if self.kind == "elastic" else w, hoop)

    def force_per_width(self, theta, pressure, shear) -> float:
        """The roll force per unit width of the tractions: the vertical resultant of the
        pressure (along the radius, to first order in the tilt) and the shear (along e_t =
        (-cos t, sin t)) on the arc."""
        R = self.rp.radius
        fy = pressure * np.cos(theta) + shear * np.sin(theta)
        return float(np.sum(0.5 * (fy[1:] + fy[:-1]) * np.diff(theta))) * R

    def update(self, theta, pressure, shear, force=None) -> float:
        """One relaxed update of the shape; the largest change of the surface (m)."""
        grid, w, hoop = self.target(np.asarray(theta, float), np.asarray(pressure, float),
                                    np.asarray(shear, float), force)
        old = self.shape.offset(grid)
        new = old + self.relaxation * (w - old)
        old_hoop = self.shape.strain(grid)
        self.shape.set(grid, new, old_hoop + self.relaxation * (hoop - old_hoop))
        self.updates += 1
        return float(np.max(np.abs(new - old)))
