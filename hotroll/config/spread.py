"""The ``[spread]`` section (issue 53): present, the pass is also solved on the 3D quarter strip
across its width (``solvers/spread_3d.py``) after the plane-strain one, and the summary gains
the spread, the exit width and the whole width's force and torque from it.

The 3D strip is the 2D pass's mesh extruded in width layers, thin at the free edge and growing
towards mid-width. What it does not carry yet is refused here, by name, before any computation
(``problems``).
"""
from __future__ import annotations

from typing import Literal

from hotroll.config.base import PosFloat, Section, field
from hotroll.config.roll_sides import UPPER

#: b0/h0 the 3D pass takes: below, a bar narrower than a quarter of its thickness (an edger's
#: pass, not flat rolling); above, a plate whose quarter needs more width layers than a laptop
#: holds and whose mid-width is plane strain (the force per width within 1 % of it from
#: b0/h0 = 8 on, docs/validation/spread_3d.md)
WIDTH_RATIO = (0.25, 16.0)


class SpreadConfig(Section):
    """The 3D pass's width layers (m) and its fixed point."""

    edge_layer: Literal["auto"] | PosFloat = field(
        "auto", "the width layer at the free edge, at most pass.width / 2 (auto: "
        "mesh.h_contact, at most the half width)", "m", '"auto" or a number > 0')
    growth: float = field(1.2, "each width layer this much thicker than the next one towards "
                          "the edge", "", "in [1, 2]", ge=1.0, le=2.0)
    largest_layer: Literal["auto"] | PosFloat = field(
        "auto", "the thickest width layer, at least edge_layer (auto: 4 edge layers)", "m",
        '"auto" or a number > 0')
    max_rounds: int = field(30, "the 3D pass's rounds of Newton and the lateral face's update",
                            "", "an integer in [1, 200]", ge=1, le=200)

    def layers(self, half_width: float, h_contact: float) -> tuple[float, float, float]:
        """(edge layer, growth, largest layer), m, with "auto" resolved."""
        edge = min(h_contact, half_width) if self.edge_layer == "auto" else self.edge_layer
        largest = 4.0 * edge if self.largest_layer == "auto" else self.largest_layer
        return float(edge), float(self.growth), float(largest)


def problems(case) -> list[str]:
    """Why the case cannot run its ``[spread]`` section, each a ``section.key: ...`` line
    (none without the section)."""
    s = case.spread
    if s is None:
        return []
    out = []
    need = "(the 3D pass starts from the steady solver's plane-strain pass)"
    if case.solver.method != "steady":
        out.append(f'solver.method: [spread] needs "steady" {need}, got "{case.solver.method}"')
    width = case.pass_.width
    if width is None:
        out.append("pass.width: [spread] needs the strip's width (m)")
    else:
        ratio = width / case.pass_.entry_thickness
        lo, hi = WIDTH_RATIO
        if not lo <= ratio <= hi:
            out.append(f"pass.width: [spread] takes width / entry thickness in [{lo:g}, "
                       f"{hi:g}] (narrower: an edger's pass; wider: plane strain at mid-width, "
                       f"run without [spread]), got {width:g} m / "
                       f"{case.pass_.entry_thickness:g} m = {ratio:.3g}")
        if s.edge_layer != "auto" and s.edge_layer > width / 2:
            out.append(f"spread.edge_layer: must be <= pass.width / 2 = {width / 2:g} m, got "
                       f"{s.edge_layer:g} m")
    if s.edge_layer != "auto" and s.largest_layer != "auto" and s.largest_layer < s.edge_layer:
        out.append(f"spread.largest_layer: must be >= spread.edge_layer ({s.edge_layer:g} m), "
                   f"got {s.largest_layer:g} m")
    if not case.roll_gap().symmetric:
        out.append("pass: [spread] needs a symmetric pass: an asymmetric one (two rolls that "
                   "differ) runs the full-thickness strip; the 3D strip is the half strip over "
                   "one roll")
    if case.pass_.roll_gap is not None:
        out.append("pass.roll_gap: not with [spread] (the gap's force would be the 3D pass's)")
    model = case.roll.model_of(UPPER)
    if model != "rigid":
        out.append(f'roll.model: [spread] needs "rigid" (the 3D strip has no flattening roll '
                   f'yet), got "{model}"')
    if case.plate.free_surface != "traced":
        out.append('plate.free_surface: [spread] needs "traced" (the 3D strip\'s free '
                   'surfaces are stream surfaces)')
    if case.contact.resolved(case.solver.method) != "multiplier":
        out.append('contact.method: [spread] needs the exact contact ("auto" or '
                   f'"multiplier"), got "{case.contact.method}" (the penalty)')
    return out
