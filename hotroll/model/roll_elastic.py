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
series is summed in closed form (``_series``: the load's Fourier coefficients are exact sums
over its kinks, and a_n, b_n split into 1/(n - 1) and 1/(n + 1), whose sums are Li1 and Li2 on
the unit circle). An FFT on a uniform grid (16 points per smallest node spacing, until issue 34
session 7) converged to it at first order in the grid: 1e-5 of u_r, 3e-4 of the hoop strain at
the grid it took, 2^15-2^18 points, 2-70 ms a call on the ten stands.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

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

    def rim(self, theta: np.ndarray, pressure: np.ndarray, shear: np.ndarray | None = None,
            at: np.ndarray | None = None) -> dict[str, np.ndarray]:
        """The rim's displacement under the nodal tractions (Pa) at the angles ``theta`` (rad,
        increasing), piecewise linear between the nodes and zero outside them; at the angles
        ``at`` (default: the nodes). Returns u_r and u_t (m) and the hoop strain
        e_tt = (u_r + du_t/dtheta) / R of the rim (-). The series summed in closed form
        (``_series``): exact for the piecewise-linear load."""
        theta = np.asarray(theta, dtype=float)
        p = np.asarray(pressure, dtype=float)
        q = np.zeros_like(p) if shear is None else np.asarray(shear, dtype=float)
        if theta.ndim != 1 or p.shape != theta.shape or q.shape != theta.shape:
            raise ValueError("theta, pressure and shear must be 1-D arrays of one length")
        if np.any(np.diff(theta) <= 0.0) or theta[0] <= -math.pi or theta[-1] >= math.pi:
            raise ValueError("the load's angles must increase strictly within (-pi, pi)")
        at = theta if at is None else np.asarray(at, dtype=float)
        nu, c = self.elasticity.nu, self.radius / self.elasticity.shear_modulus
        # the hoop strain is log-singular at a jump of the load (its ends): within 1e-3 of the
        # smallest node spacing of one it is taken at that distance
        re_a0, im_b0, im_a1, re_b1, re_a2, im_b2 = _series(
            at[:, None] - theta[None, :], nu,
            floor=1e-3 * float(np.min(np.diff(theta), initial=1.0)))
        Jp, Dp = _kinks(theta, p)
        Jq, Dq = _kinks(theta, q)
        mean_p = float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(theta))) / (2.0 * math.pi)

        def dot(m, v):
            return np.einsum("ij,j->i", m, v)

        k = c / math.pi
        u_r = -0.5 * c * (1.0 - 2.0 * nu) * mean_p - k * (
            dot(im_a1, Jp) - dot(re_a2, Dp) + dot(re_b1, Jq) + dot(im_b2, Dq))
        u_t = k * (-dot(re_b1, Jp) - dot(im_b2, Dp) + dot(im_a1, Jq) - dot(re_a2, Dq))
        du_t = k * (dot(im_b0, Jp) - dot(re_b1, Dp) + dot(re_a0, Jq) + dot(im_a1, Dq))
        return {"u_r": u_r, "u_t": u_t, "hoop": (u_r + du_t) / self.radius}


def _kinks(theta: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(J, D): the jumps of a piecewise-linear v (zero outside the nodes) and of its slope at
    the nodes. Its Fourier coefficients are then exact sums over the nodes:
    int v e^(-i n t) dt = sum_j (J_j / (i n) + D_j / (i n)^2) e^(-i n theta_j)."""
    J = np.zeros_like(v)
    if len(v) < 2:              # one node: a load of zero width, no kinks (zero displacement)
        return J, np.zeros_like(v)
    slope = np.diff(v) / np.diff(theta)
    J[0], J[-1] = v[0], -v[-1]
    return J, np.diff(np.concatenate([[0.0], slope, [0.0]]))


def _bernoulli(m: int) -> list[Fraction]:
    """B_0 .. B_m, exact (sum_{k<=n} C(n+1, k) B_k = 0)."""
    B = [Fraction(1)]
    for n in range(1, m + 1):
        B.append(-sum(math.comb(n + 1, k) * B[k] for k in range(n)) / (n + 1))
    return B


#: |B_2k| / (2k (2k + 1)!), k = 1..24: the series of Clausen's Cl2 (``_clausen2``)
_CL2 = np.array([float(abs(b)) / (2.0 * k * math.factorial(2 * k + 1))
                 for k, b in zip(range(1, 25), _bernoulli(48)[2::2])])


def _clausen2(x: np.ndarray) -> np.ndarray:
    """Cl2(x) = Im Li2(e^(i x)) for |x| <= pi: x - x ln|x| + sum_k |B_2k| x^(2k+1) /
    (2k (2k+1)!) (Abramowitz and Stegun 27.8). The terms fall by (x / 2 pi)^2: as many are
    summed as take them below 1e-17 of the first (24 at |x| = pi, 6 at 0.3)."""
    ax = np.abs(x)
    top = float(np.max(ax, initial=0.0))
    ratio = (top / (2.0 * math.pi)) ** 2
    terms = len(_CL2) if ratio >= 0.25 else max(1, min(len(_CL2), math.ceil(
        17.0 / -math.log10(ratio)) if ratio > 0.0 else 1))
    x2 = x * x
    acc = np.zeros_like(x)
    for coeff in _CL2[:terms][::-1]:
        acc = acc * x2 + coeff
    return x - x * np.log(np.where(ax > 0.0, ax, 1.0)) + acc * x2 * x


def _series(psi: np.ndarray, nu: float, floor: float = 1e-300) -> tuple[np.ndarray, ...]:
    """The disc's sums over n >= 2 at the angles psi (elementwise): with
    A_k = sum a_n e^(i n psi) / n^k and B_k = sum b_n e^(i n psi) / n^k, the parts the rim
    needs, (Re A0, Im B0, Im A1, Re B1, Re A2, Im B2). By partial fractions a_n =
    al/(n-1) + be/(n+1) and b_n = al/(n-1) - be/(n+1) (al = 1/4, be = (3 - 4 nu)/4), so every
    sum is a combination of Li1(E) = -log(1 - E) and Li2(E) at E = e^(i psi), in closed form
    on the unit circle: Li1 = -ln|2 sin(t/2)| + i (pi - t)/2, Li2 = pi^2/6 - t (2 pi - t)/4
    + i Cl2(t), t = psi mod 2 pi. Li1's log is the hoop strain's at a jump of the load (A0,
    B0; the others multiply it by 1 - E): there ``floor`` bounds |1 - E| from below."""
    al, be = 0.25, 0.25 * (3.0 - 4.0 * nu)
    t = np.mod(psi, 2.0 * math.pi)
    c, s = np.cos(psi), np.sin(psi)
    chord = np.abs(2.0 * np.sin(0.5 * t))
    m = 0.5 * math.pi - 0.5 * t                       # Im Li1
    re2 = math.pi**2 / 6.0 - 0.25 * t * (2.0 * math.pi - t)
    im2 = _clausen2(np.where(t > math.pi, t - 2.0 * math.pi, t))

    def sums(lg):
        """(Re, Im) of sum E^n/(n-1), E^n/n, E^n/(n+1) for Re Li1 = lg."""
        m1 = (c * lg - s * m, c * m + s * lg)
        n0 = (lg - c, m - s)
        p1 = (lg * c + m * s - 1.0 - 0.5 * c, m * c - lg * s - 0.5 * s)
        return m1, n0, p1

    (m1r, m1i), (n0r, n0i), (p1r, p1i) = sums(-np.log(np.maximum(chord, 1e-300)))
    n00r, n00i = re2 - c, im2 - s                     # sum E^n / n^2
    (f1r, f1i), _, (fp1r, fp1i) = sums(-np.log(np.maximum(chord, floor)))
    re_a0 = al * f1r + be * fp1r
    im_b0 = al * f1i - be * fp1i
    im_a1 = al * (m1i - n0i) + be * (n0i - p1i)                  # 1/(n(n-1)), 1/(n(n+1))
    re_b1 = al * (m1r - n0r) - be * (n0r - p1r)
    re_a2 = al * (m1r - n0r - n00r) + be * (n00r - n0r + p1r)     # 1/(n^2(n-1)), 1/(n^2(n+1))
    im_b2 = al * (m1i - n0i - n00i) - be * (n00i - n0i + p1i)
    return re_a0, im_b0, im_a1, re_b1, re_a2, im_b2


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
        """One relaxed update of the shape; the residual: the largest distance between the
        surface and the one its tractions give (m), before the step (with ``relaxation`` < 1
        the step is that share of it: the residual, not the step, says whether it settled)."""
        grid, w, hoop = self.target(np.asarray(theta, float), np.asarray(pressure, float),
                                    np.asarray(shear, float), force)
        old = self.shape.offset(grid)
        r = w - old
        old_hoop = self.shape.strain(grid)
        self.shape.set(grid, old + self.relaxation * r,
                       old_hoop + self.relaxation * (hoop - old_hoop))
        self.updates += 1
        return float(np.max(np.abs(r)))
