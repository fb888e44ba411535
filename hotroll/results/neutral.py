"""The neutral point's one story (docs/theory.md 1e): a point, or none (a sticking zone, a strip
that skids, no contact). ``decide`` makes the decision once, on the solved contact profile;
the summary carries it (``neutral_point``, ``neutral_angle``, ``sticking_zone``,
``sticking_zone_x``, ``neutral_angle_reason`` and the story in words, ``neutral``), and every
place that shows a neutral point reads it back from there (``Neutral.from_summary``): the
figures, the HTML page, the command line's table.

The flux angle (``neutral_angle_flux``: where the strip's mean velocity, the mass flux over its
half-height, equals the roll's horizontal speed U cos phi) is not the neutral point and is not
part of this story: on a sticking arc it lies inside the zone where nothing is neutral.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from hotroll.model import contact_figures as Q

#: the summary keys the story is written to (``Neutral.to_summary``)
KEYS = ("neutral", "neutral_point", "neutral_angle", "neutral_angle_reason",
        "neutral_angle_in_sticking_zone", "sticking_zone", "sticking_zone_x")
#: what the figures and the page call it
LABEL = "neutral point"


def _finite(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _pair(v) -> tuple[float, float] | None:
    if v is None or len(v) < 2 or not all(_finite(x) for x in v[:2]):
        return None
    return float(v[0]), float(v[1])


def angle_text(rad: float) -> str:
    """An angle in degrees and radians: ``3.823° (0.06673 rad)``."""
    return f"{math.degrees(rad):.4g}° ({rad:.4g} rad)"


def zone_text(zone: tuple[float, float]) -> str:
    """A zone of the arc from its entry side: ``from 22.06° to 1.879° (0.3851 to 0.0328 rad)``."""
    a, b = zone
    return (f"from {math.degrees(a):.4g}° to {math.degrees(b):.4g}° ({a:.4g} to {b:.4g} rad)")


@dataclass(frozen=True)
class Neutral:
    """The neutral story of a run. ``kind``: ``"point"`` (a neutral point at ``angle``, rad
    from the roll's vertical centre line, positive towards the entry; ``point`` (x, y), m),
    ``"sticking"`` (none: the strip sticks over ``zone``, where the slip's sign is noise),
    ``"skids"`` (none: the outlet penalty drives the strip) or ``"none"`` (no slip measured,
    no contact). ``zone`` (rad, entry side first) and ``zone_x`` (m) the longest sticking
    zone, with any kind."""

    kind: str
    angle: float | None = None
    point: tuple[float, float] | None = None
    zone: tuple[float, float] | None = None
    zone_x: tuple[float, float] | None = None
    reason: str | None = None
    in_zone: bool = False

    # --- what is shown ---------------------------------------------------------------------
    @property
    def angle_deg(self) -> float | None:
        return None if self.angle is None else math.degrees(self.angle)

    @property
    def zone_deg(self) -> tuple[float, float] | None:
        return None if self.zone is None else tuple(math.degrees(a) for a in self.zone)

    @property
    def text(self) -> str:
        """The story in words, every number with its unit; after "neutral point: "."""
        if self.kind == "point":
            where = angle_text(self.angle)
            return where + (f"; sticking zone {zone_text(self.zone)}" if self.zone else "")
        if self.kind == "sticking":
            return f"none: sticking zone {zone_text(self.zone)}"
        if self.kind == "skids":
            return "none: the strip skids (the outlet penalty drives it)"
        return "none: no slip measured on the contact"

    @property
    def label(self) -> str:
        """``neutral point: <text>``: the figures' legend, the page's note."""
        return f"{LABEL}: {self.text}"

    def marks(self, axis: str = "x") -> list[tuple[str, tuple[float, ...], str]]:
        """What a figure draws, as (``"line"`` or ``"span"``, its position, its label): the
        neutral point's line, or the sticking zone's span where there is no point. ``axis``:
        ``"x"`` (m, the case's frame) or ``"angle"`` (degrees)."""
        if self.kind == "point":
            at = self.point[0] if axis == "x" and self.point else (
                self.angle_deg if axis == "angle" else None)
            return [] if at is None else [("line", (at,), self.label)]
        if self.kind == "sticking":
            at = self.zone_x if axis == "x" else self.zone_deg
            return [] if at is None else [("span", (min(at), max(at)), self.label)]
        return []

    # --- the summary -------------------------------------------------------------------------
    def to_summary(self) -> dict:
        return {"neutral": self.text,
                "neutral_point": list(self.point) if self.point else None,
                "neutral_angle": self.angle,
                "neutral_angle_reason": self.reason,
                "neutral_angle_in_sticking_zone": bool(self.in_zone),
                "sticking_zone": list(self.zone) if self.zone else None,
                "sticking_zone_x": list(self.zone_x) if self.zone_x else None}

    @classmethod
    def from_summary(cls, s: Mapping) -> Neutral:
        """The story a summary tells (a summary of before the key ``neutral``: the same rules
        on its keys)."""
        angle = s.get("neutral_angle")
        zone, zone_x = _pair(s.get("sticking_zone")), _pair(s.get("sticking_zone_x"))
        common = {"zone": zone, "zone_x": zone_x, "reason": s.get("neutral_angle_reason"),
                  "in_zone": bool(s.get("neutral_angle_in_sticking_zone"))}
        if _finite(angle):
            return cls("point", angle=float(angle), point=_pair(s.get("neutral_point")),
                       **common)
        if s.get("outlet_driven"):
            return cls("skids", **common)
        if zone is not None and common["reason"]:
            return cls("sticking", **common)
        return cls("none", **common)


def decide(prof: dict, rp, h: float, angle: float, outlet_driven: bool) -> Neutral:
    """The neutral story of a solved contact profile (the roll's frame), ``angle`` the split
    of the slip's signs (``Q.neutral_index``; the window's mean), ``h`` the contact mesh size.

    Where the split lies in a sticking zone (slip below ``Q.STICKING_FLOOR`` of the roll speed
    over more than 2h) in which the slip changes sign more than once, the signs are noise and
    no point is neutral; one clean sign change in a short sticking stretch keeps its point. A
    strip the outlet penalty drives (``outlet_driven``) skids: no point is neutral."""
    R = rp.radius
    stick = Q.sticking_zone(prof, rp.u_roll, 2.0 * h)
    zone = None if stick is None else (float(stick[0]), float(stick[1]))
    zone_x = None
    if zone is not None:
        ang, x = np.asarray(prof["angle"], float), np.asarray(prof["x"], float)
        order = np.argsort(ang)
        zone_x = tuple(float(np.interp(a, ang[order], x[order])) for a in zone)
    finite = math.isfinite(angle)
    in_zone = zone is not None and finite and zone[1] - h / R <= angle <= zone[0] + h / R
    flips = Q.slip_sign_changes(prof, list(zone)) if in_zone else 0
    common = {"zone": zone, "zone_x": zone_x, "in_zone": in_zone}
    if outlet_driven:
        return Neutral("skids", reason="the outlet penalty drives the strip (it skids on the "
                       "roll): no point is neutral", **common)
    if flips > 1:
        return Neutral("sticking", reason=(
            f"the slip changes sign {flips} times in the sticking zone {zone[0]:.4g} .. "
            f"{zone[1]:.4g} rad (|v_s| below {Q.STICKING_FLOOR:g} of the roll speed): the "
            "strip moves with the roll, no point is neutral"), **common)
    if not finite:
        return Neutral("none", angle=angle, **common)
    cx, cy = rp.centre
    return Neutral("point", angle=float(angle),
                   point=(cx - R * math.sin(angle), cy - R * math.cos(angle)), **common)
