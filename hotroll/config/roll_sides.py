"""The per-roll tables of an asymmetric pass (issue 52): ``[pass.upper]``/``[pass.lower]`` (a
roll's own radius and speed) and ``[roll.upper]``/``[roll.lower]`` (its own roll model); the
friction's are in ``config/friction.py``. ``[pass]``, ``[roll]`` and ``[friction]`` describe both
rolls; a side's table gives only what differs for that roll. How a roll's radius and speed
follow from them (``roll_values``) and the checks of the pass's rolls (``side_problems``)."""
from __future__ import annotations

import math
from typing import Literal

from hotroll.config.base import MAX_LENGTH, PosFloat, Section, field
from hotroll.model.roll_gap import LOWER, UPPER, fit_problems

#: The side tables by side (+1 upper, -1 lower).
SIDES = {UPPER: "upper", LOWER: "lower"}


class RollSideConfig(Section):
    """One roll's own radius and speed (``[pass.upper]``, ``[pass.lower]``)."""

    roll_radius: float | None = field(
        None, "this roll's radius (omit: pass.roll_radius)", "m",
        f"> 0 and <= {MAX_LENGTH:g}", gt=0, le=MAX_LENGTH)
    roll_angular_velocity: PosFloat | None = field(
        None, "this roll's angular velocity (omit: pass.roll_angular_velocity; the lower roll's "
        "from pass.speed_ratio when that is given; at <= 0 it would stand or drive the strip "
        "backwards)", "rad/s", "> 0")
    roll_surface_speed: PosFloat | None = field(
        None, "this roll's surface speed omega R, instead of its angular velocity", "m/s",
        "> 0")

    @property
    def speed_key(self) -> str | None:
        """The key that sets this roll's speed, or None."""
        if self.roll_angular_velocity is not None:
            return "roll_angular_velocity"
        return "roll_surface_speed" if self.roll_surface_speed is not None else None


class RollModelSide(Section):
    """One roll's own model (``[roll.upper]``, ``[roll.lower]``); its elasticity and the
    coupling's numerics are [roll]'s."""

    model: Literal["rigid", "hitchcock", "elastic"] | None = field(
        None, "this roll's model (omit: roll.model)", "", '"rigid", "hitchcock" or "elastic"')


def roll_values(p, side: int) -> tuple[float, float]:
    """(radius m, angular velocity rad/s) of the roll on ``side`` of the pass ``p``
    (``PassConfig``): its table's, else the pass's; the lower roll at the upper's surface speed
    over ``p.speed_ratio`` when that is given (the upper roll keeps its own speed)."""
    own = getattr(p, SIDES[side])
    radius = p.roll_radius if own is None or own.roll_radius is None else own.roll_radius
    if own is not None and own.roll_angular_velocity is not None:
        return radius, own.roll_angular_velocity
    if own is not None and own.roll_surface_speed is not None:
        return radius, own.roll_surface_speed / radius
    if side == LOWER and p.speed_ratio is not None:
        R1, omega1 = roll_values(p, UPPER)
        return radius, omega1 * (R1 / radius) / p.speed_ratio   # exact omega1 when R, r equal
    return radius, p.roll_angular_velocity


def own_radius(p) -> bool:
    """Whether a side's table of the pass ``p`` gives its roll's radius."""
    return any(getattr(p, name) is not None and getattr(p, name).roll_radius is not None
               for name in SIDES.values())


def side_problems(p) -> list[str]:
    """The per-roll inputs of the pass ``p`` that conflict or do not fit the gap, each a
    ``pass.<key>: ...`` line with the allowed range."""
    out = []
    for name in SIDES.values():
        own = getattr(p, name)
        if own is not None and own.roll_angular_velocity is not None \
                and own.roll_surface_speed is not None:
            out.append(f"pass.{name}.roll_surface_speed: give one of pass.{name}."
                       f"roll_angular_velocity (rad/s) and pass.{name}.roll_surface_speed "
                       f"(m/s), not both")
    if p.speed_ratio is not None and p.lower is not None and p.lower.speed_key is not None:
        out.append(f"pass.speed_ratio: conflicts with pass.lower.{p.lower.speed_key}: the "
                   f"ratio sets the lower roll's surface speed (the upper's / speed_ratio); "
                   f"give one of them")
    if p.speed_ratio is not None and not out:
        omega = roll_values(p, LOWER)[1]
        if not (math.isfinite(omega) and omega > 0.0):
            out.append(f"pass.speed_ratio: gives the lower roll an angular velocity of "
                       f"{omega:g} rad/s; allowed: a ratio that leaves it > 0 and finite")
    if p.exit_thickness < p.entry_thickness and own_radius(p):
        names = tuple(f"pass.{name}.roll_radius" if getattr(p, name) is not None
                      and getattr(p, name).roll_radius is not None else "pass.roll_radius"
                      for name in SIDES.values())
        out += fit_problems(roll_values(p, UPPER)[0], roll_values(p, LOWER)[0],
                            p.entry_thickness - p.exit_thickness, names)
    return out
