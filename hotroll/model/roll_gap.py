"""The roll gap of a flat-rolling stand: two work rolls, each with its own radius, speed,
friction and roll model (issue 52). Symmetry is derived, not assumed: a gap is ``symmetric``
when both rolls are equal in every per-roll value, and only then is the half model with its
symmetry plane (today's ``RollPass``) the whole pass.

**Frame** (the full-thickness frame): x as in ``RollPass`` (the roll axes at x = ``axis_x``,
rolling towards +x); y = 0 is the exit mid-plane, halfway between the two rolls' nearest
points. The upper roll's centre is at (axis_x, h1/2 + R1), the lower's at (axis_x, -h1/2 - R2).

**Pass line.** The entry strip's centreline height ``pass_line`` is the one at which both rolls
first touch it at the same x (docs: ../shared/notes/asymmetric-rolling.md 1.1). Exactly, for
circles: 2 R1 dh1 - dh1^2 = 2 R2 dh2 - dh2^2 with dh1 + dh2 = dh, whence
pass_line = (dh1 - dh2)/2 = dh (R2 - R1) / (2 (R1 + R2 - dh)); for dh << R it is the note's
small-angle split dh1 = dh R2/(R1 + R2), and it is exactly 0 for equal radii.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

from hotroll.model.geometry import RollPass

#: The roll models a roll may have (``[roll] model``).
ROLL_MODELS = ("rigid", "hitchcock", "elastic")
UPPER, LOWER = +1, -1


def pass_line(R1: float, R2: float, dh: float) -> float:
    """The entry centreline height (m) of ``RollGap.pass_line`` for radii R1 (upper), R2 and
    draft dh (m): dh (R2 - R1) / (2 (R1 + R2 - dh))."""
    return dh * (R2 - R1) / (2.0 * (R1 + R2 - dh))


def draft_split(R1: float, R2: float, dh: float) -> tuple[float, float]:
    """(dh1, dh2) (m) of ``RollGap.draft_split``: dh/2 +- the pass line."""
    half, c = 0.5 * dh, pass_line(R1, R2, dh)
    return half + c, half - c


def fit_problems(R1: float, R2: float, dh: float,
                 names: tuple[str, str] = ("upper.radius", "lower.radius")) -> list[str]:
    """Radii R1 (upper), R2 (m) that do not fit a draft dh (m): each roll's share of the draft
    must be smaller than its radius (a bite angle below 90 degrees); ``names``: what the lines
    call the two radii."""
    if R1 + R2 <= dh:
        return [f"{names[1]}: the two radii ({R1:g} m + {R2:g} m) must exceed the draft "
                f"({dh:g} m)"]
    return [f"{name}: must exceed this roll's share of the draft, {share:g} m (the split at "
            f"which both rolls bite at the same x); allowed: > {share:g} m, got {R:g} m"
            for name, R, share in zip(names, (R1, R2), draft_split(R1, R2, dh))
            if not share < R]


@dataclass(frozen=True)
class RollFriction:
    """A roll's own friction: a registered law's name and its data as the case gives them
    ((key, value) pairs, sorted; values in SI)."""

    law: str
    parameters: tuple[tuple[str, float | str], ...] = ()


@dataclass(frozen=True)
class Roll:
    """One work roll. ``friction`` None: the case's ``[friction]``."""

    radius: float                          # R, m
    omega: float                           # angular velocity, rad/s (> 0: drives the strip on)
    friction: RollFriction | None = None
    model: str = "rigid"                   # rigid | hitchcock | elastic
    side: int = UPPER                      # +1 upper (centre above the strip), -1 lower

    @property
    def surface_speed(self) -> float:
        """omega R, m/s."""
        return self.omega * self.radius

    def problems(self, name: str) -> list[str]:
        """What is wrong with this roll as ``name`` (``upper``/``lower``), each with the
        allowed range."""
        out = []
        if not (math.isfinite(self.radius) and self.radius > 0.0):
            out.append(f"{name}.radius: must be > 0 [m], got {self.radius!r}")
        if not (math.isfinite(self.omega) and self.omega > 0.0):
            out.append(f"{name}.omega: must be > 0 [rad/s] (a roll at <= 0 stands or drives "
                       f"the strip backwards), got {self.omega!r}")
        if self.model not in ROLL_MODELS:
            out.append(f"{name}.model: must be one of {', '.join(ROLL_MODELS)}, "
                       f"got {self.model!r}")
        if self.friction is not None:
            from hotroll.model.friction import FRICTION_LAWS

            if self.friction.law not in FRICTION_LAWS:
                out.append(f"{name}.friction: law {self.friction.law!r} is not registered "
                           f"(registered: {', '.join(FRICTION_LAWS)})")
        return out


@dataclass(frozen=True)
class RollGap:
    """Two rolls over a strip from ``entry_thickness`` to ``exit_thickness`` (m), their axes at
    x = ``axis_x`` (m). Checked on construction (ValueError naming the field)."""

    upper: Roll
    lower: Roll
    entry_thickness: float
    exit_thickness: float
    axis_x: float = 1.0

    def __post_init__(self):
        problems = self.upper.problems("upper") + self.lower.problems("lower")
        if self.upper.side != UPPER:
            problems.append(f"upper.side: must be +1, got {self.upper.side!r}")
        if self.lower.side != LOWER:
            problems.append(f"lower.side: must be -1, got {self.lower.side!r}")
        h0, h1 = self.entry_thickness, self.exit_thickness
        if not (math.isfinite(h1) and 0.0 < h1 < h0 and math.isfinite(h0)):
            problems.append(f"exit_thickness: must be > 0 and < entry_thickness ({h0!r} m), "
                            f"got {h1!r} m")
        if not problems:
            problems += fit_problems(self.upper.radius, self.lower.radius, self.draft)
        if problems:
            raise ValueError("; ".join(problems))

    # --- what the two rolls make of the strip ----------------------------------------------
    @property
    def symmetric(self) -> bool:
        """Both rolls equal in radius, speed, friction and roll model (exact ==): the half
        model with its symmetry plane is then the whole pass."""
        return not self.differences()

    def differences(self) -> list[str]:
        """The per-roll values in which the two rolls differ (exact ==), in the order radius,
        omega, friction, model."""
        return [name for name in ("radius", "omega", "friction", "model")
                if getattr(self.upper, name) != getattr(self.lower, name)]

    @property
    def draft(self) -> float:
        """dh = h0 - h1, m."""
        return self.entry_thickness - self.exit_thickness

    @property
    def equivalent_radius(self) -> float:
        """R_e = 2 R1 R2 / (R1 + R2) (m): h(x) ~ h1 + x^2/R_e, one roll's radius when equal."""
        R1, R2 = self.upper.radius, self.lower.radius
        return 2.0 * R1 * R2 / (R1 + R2)

    @property
    def pass_line(self) -> float:
        """The entry strip's centreline height (m, the full-thickness frame: y = 0 the exit
        mid-plane) at which both rolls touch it at the same x: dh (R2 - R1) / (2 (R1 + R2 -
        dh)); below the mid-plane (< 0) when the upper roll is the larger, 0 for equal radii."""
        return pass_line(self.upper.radius, self.lower.radius, self.draft)

    def draft_split(self) -> tuple[float, float]:
        """(dh1, dh2) (m): the upper and the lower roll's shares of the draft at the pass line,
        dh/2 +- pass_line; to first order in dh/R the note's dh R2/(R1+R2), dh R1/(R1+R2): the
        smaller roll takes the larger share."""
        return draft_split(self.upper.radius, self.lower.radius, self.draft)

    @property
    def speed_ratio(self) -> float:
        """Upper over lower surface speed, -."""
        return self.upper.surface_speed / self.lower.surface_speed

    def roll(self, side: int) -> Roll:
        """The roll on ``side`` (+1 upper, -1 lower)."""
        if side == UPPER:
            return self.upper
        if side == LOWER:
            return self.lower
        raise ValueError(f"side: must be +1 (upper) or -1 (lower), got {side!r}")

    def centre(self, side: int) -> tuple[float, float]:
        """The roll's axis in the full-thickness frame (m): (axis_x, +-(h1/2 + R))."""
        R = self.roll(side).radius
        return (self.axis_x, side * (0.5 * self.exit_thickness + R))

    def arc(self, side: int) -> RollPass:
        """The roll's ``RollPass`` in its own frame: the full-thickness frame for the upper
        roll, mirrored (y -> -y) for the lower, so that y = 0 is the exit mid-plane and the
        roll is above it; ``half_entry`` is the entry strip's surface height there, h0/2 +-
        pass_line. The upper roll of a symmetric gap: today's RollPass(R, h0/2, h1/2, omega,
        axis_x)."""
        roll = self.roll(side)
        return RollPass(roll.radius, 0.5 * self.entry_thickness + side * self.pass_line,
                        0.5 * self.exit_thickness, roll.omega, self.axis_x)

    def mirror(self) -> RollGap:
        """The stand turned upside down: the rolls swapped (each keeps its own values)."""
        return replace(self, upper=replace(self.lower, side=UPPER),
                       lower=replace(self.upper, side=LOWER))
