"""The ``[spread]`` section (issue 53): present, the pass is also solved on the 3D quarter strip
across its width (``solvers/spread_3d.py``) after the plane-strain one, and the summary gains
the spread, the exit width and the whole width's force and torque from it.

The 3D strip is the 2D pass's mesh extruded in width layers, thin at the free edge and growing
towards mid-width. What it does not carry yet is refused here, by name, before any computation
(``problems``).
"""
from __future__ import annotations

from typing import Any, Literal

import numpy as np
from pydantic import Field, field_validator

from hotroll.config.base import PosFloat, Section, field
from hotroll.config.roll_sides import UPPER
from hotroll.config.sections import check_profile
from hotroll.model.profile import ProfileError, ThicknessProfile
from hotroll.model.section import SectionProfile

#: b0/h0 the 3D pass takes: below, a bar narrower than a quarter of its thickness (an edger's
#: pass, not flat rolling); above, a plate whose quarter needs more width layers than a laptop
#: holds: wider plates take the edge-zone model (``edge_zone``, its graded width up to the
#: same bound, the interior one layer in generalized plane strain; docs/validation/
#: spread_3d.md, "The edge zone's interior")
WIDTH_RATIO = (0.25, 16.0)


class TemperatureSection(Section):
    """The entry temperature over the quarter cross-section (K): ``values[i][j]`` at
    ``eta[i]`` (y / half thickness) and ``zeta[j]`` (z / half width), bilinear between."""

    eta: list[float] = field(..., "through the half thickness, 0 (centre) to 1 (surface)", "",
                             "increasing strictly from 0 to 1")
    zeta: list[float] = field(..., "across the half width, 0 (mid-width) to 1 (the edge)", "",
                              "increasing strictly from 0 to 1")
    values: list[list[float]] = field(..., "the temperature, one row per eta of one value "
                                      "per zeta", "K", "> 0, one row per eta of one value per "
                                      "zeta")

    @field_validator("eta", "zeta")
    @classmethod
    def _axis(cls, v: Any, info) -> Any:
        try:
            SectionProfile(tuple(v), (0.0, 1.0), tuple((1.0, 1.0) for _ in v))
        except ProfileError as e:
            raise ValueError(str(e).replace("eta", info.field_name)) from None
        return v

    @field_validator("values")
    @classmethod
    def _values(cls, v: Any, info) -> Any:
        eta, zeta = info.data.get("eta"), info.data.get("zeta")
        shape = (len(eta), len(zeta)) if eta is not None and zeta is not None else None
        rows = [len(r) for r in v]
        if shape is not None and (len(v), *set(rows)) != shape:
            raise ValueError(f"one row per eta ({shape[0]}) of one value per zeta "
                             f"({shape[1]}), got {len(v)} rows of {sorted(set(rows))} values")
        low = min(min(r) for r in v) if v and all(v) else None
        if low is None or not low > 0.0:
            raise ValueError(f"temperatures must be > 0 K, got {low!r}")
        return v

    def profile(self) -> SectionProfile:
        return SectionProfile(tuple(self.eta), tuple(self.zeta),
                              tuple(tuple(r) for r in self.values))


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
    edge_zone: PosFloat | None = field(
        None, "the edge-zone model of a wide strip: only this outer part of the half width "
        "graded in width layers, the interior inside it one layer in generalized plane strain "
        "(u_x, u_y uniform across it, its lateral strain free), at most pass.width / 2 (omit: "
        "the whole half width graded)", "m", "> 0")
    strain: Literal["transported", "frozen"] = field(
        "transported", "a strain-dependent flow stress's strain: carried through the 3D flow "
        "(the edge's own hardening) or the plane-strain pass's in every width layer", "",
        '"transported" or "frozen"')
    temperature_profile: list[tuple[float, float]] | None = field(
        None, "entry temperature across the half width, [[zeta, T], ...] with zeta = z / "
        "half width from 0 (mid-width) to 1 (the edge), linear between, its mid-width value "
        "plate.temperature: the edges' cooling before the pass, carried through the bite "
        "(omit: the plane-strain pass's temperature at every width)", "K",
        "pairs with zeta increasing strictly from 0 to 1 and T > 0", columns=("", "K"))
    temperature_section: TemperatureSection | None = Field(
        None, description="entry temperature over the quarter cross-section (eta through the "
        "half thickness, zeta across the half width, values in K), its mid-width column the "
        "plate's entry profile (plate.temperature_profile or plate.temperature): what a "
        "schedule hands on after its interpass cooling across the width (omit: as "
        "temperature_profile)")
    max_rounds: int = field(30, "the 3D pass's rounds of Newton and the lateral face's update",
                            "", "an integer in [1, 200]", ge=1, le=200)
    linear_solver: Literal["umfpack", "amg+gmres"] = field(
        "umfpack", "the 3D pass's linear solver: UMFPACK's factors (the fastest where they fit "
        "in memory) or GMRES with smoothed-aggregation AMG (no factors: a fraction of the "
        "memory, about twice the time a Newton step; for meshes whose factors do not fit)",
        "", '"umfpack" or "amg+gmres"')

    @field_validator("temperature_profile")
    @classmethod
    def _profile(cls, v: Any) -> Any:
        return check_profile("temperature_profile", v)

    def modelled(self, half_width: float) -> float:
        """The width the 3D strip models from its edge (m): the edge zone or the half width."""
        return half_width if self.edge_zone is None else min(self.edge_zone, half_width)

    def layers(self, half_width: float, h_contact: float) -> tuple[float, float, float]:
        """(edge layer, growth, largest layer), m, with "auto" resolved."""
        edge = (min(h_contact, self.modelled(half_width)) if self.edge_layer == "auto"
                else self.edge_layer)
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
        h0 = case.pass_.entry_thickness
        ratio = width / h0
        lo, hi = WIDTH_RATIO
        if ratio < lo:
            out.append(f"pass.width: [spread] takes width / entry thickness >= {lo:g} "
                       f"(narrower: an edger's pass), got {width:g} m / {h0:g} m = "
                       f"{ratio:.3g}")
        elif s.edge_zone is None and ratio > hi:
            out.append(f"pass.width: [spread] models the whole width up to width / entry "
                       f"thickness = {hi:g}, got {width:g} m / {h0:g} m = {ratio:.3g}: give "
                       f"spread.edge_zone (m, the outer part of the half width in 3D, up to "
                       f"{hi / 2:g} x entry thickness)")
        if s.edge_zone is not None and s.edge_zone > width / 2:
            out.append(f"spread.edge_zone: must be <= pass.width / 2 = {width / 2:g} m, got "
                       f"{s.edge_zone:g} m")
        elif s.edge_zone is not None and 2.0 * s.edge_zone / h0 > hi:
            out.append(f"spread.edge_zone: at most {hi / 2:g} x entry thickness = "
                       f"{hi / 2 * h0:g} m (the 3D strip's width), got {s.edge_zone:g} m")
        if s.edge_layer != "auto" and s.edge_layer > s.modelled(width / 2):
            out.append(f"spread.edge_layer: must be <= the modelled width (pass.width / 2 or "
                       f"spread.edge_zone) = {s.modelled(width / 2):g} m, got "
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
    if s.temperature_profile is not None and s.temperature_section is not None:
        out.append("spread.temperature_section: not with spread.temperature_profile (give "
                   "one of the two)")
    elif s.temperature_profile is not None or s.temperature_section is not None:
        out.extend(_profile_problems(case, s))
    if case.solver.method == "steady" and case.contact.resolved("steady") != "multiplier":
        out.append('contact.method: [spread] needs the exact contact ("auto" or '
                   f'"multiplier"), got "{case.contact.method}" (the penalty)')
    return out


def entry_section(case) -> SectionProfile | None:
    """The 3D pass's entry temperature over the cross-section: ``temperature_section``, or
    ``temperature_profile`` across the width added to the plate's through the thickness
    (uniform: plate.temperature), or None."""
    s = case.spread
    if s is None or (s.temperature_profile is None and s.temperature_section is None):
        return None
    if s.temperature_section is not None:
        return s.temperature_section.profile()
    prof = (case.plate.entry_profiles()[0]
            or ThicknessProfile.uniform(case.plate.temperature))
    add = [t - s.temperature_profile[0][1] for _, t in s.temperature_profile]
    return SectionProfile.across(prof, {"eta": [0.0, 1.0],
                                        "zeta": [z for z, _ in s.temperature_profile],
                                        "values": [add, add]})


def temperature_matters(law, t: float) -> bool:
    """True if the flow stress law changes with the temperature (at ``t`` against 100 K
    below)."""
    return float(law.sigma(0.1, 1.0, t)) != float(law.sigma(0.1, 1.0, t - 100.0))


def _profile_problems(case, s) -> list[str]:
    """Why the entry temperature across the width (``spread.temperature_profile`` or
    ``spread.temperature_section``) cannot be taken: its mid-width value not the plate's, a
    law whose flow stress does not change with the temperature, a temperature outside the
    law's, a profile that varies inside an edge zone's cut (its interior is one layer, uniform
    across the width)."""
    key = ("spread.temperature_profile" if s.temperature_profile is not None
           else "spread.temperature_section")
    out = []
    sec = entry_section(case)
    t_plate = case.plate.temperature
    prof = case.plate.entry_profiles()[0]
    # both columns at every node of either (each is linear between its own)
    eta = np.asarray(sec.eta) if prof is None else np.union1d(sec.eta, prof.eta)
    plate = np.full(eta.size, t_plate) if prof is None else prof(eta)
    mid = sec.mid_width()(eta)
    if s.temperature_profile is not None:
        if abs(s.temperature_profile[0][1] - t_plate) > 1e-9 * t_plate:
            out.append(f"{key}: its mid-width value (zeta = 0) is the plane-strain pass's, "
                       f"plate.temperature = {t_plate:g} K, got "
                       f"{s.temperature_profile[0][1]:g} K")
    elif np.max(np.abs(mid - plate)) > 1e-9 * t_plate:
        worst = int(np.argmax(np.abs(mid - plate)))
        out.append(f"{key}: its mid-width column (zeta = 0) is the plane-strain pass's entry "
                   f"profile (plate.temperature_profile, or plate.temperature), at eta = "
                   f"{eta[worst]:g}: {plate[worst]:g} K, got {mid[worst]:g} K")
    law = case.material.flow_stress()
    temps = sec.array.ravel()
    if not temperature_matters(law, t_plate):
        out.append(f'{key}: the flow stress law "{case.material.law}" does not depend on the '
                   "temperature (a grade's law does)")
    else:
        bad = [t for t in temps if not 0.0 < float(law.rate_exponent(t)) <= 1.0]
        if bad:
            out.append(f"{key}: the law's rate exponent leaves (0, 1] at {min(bad):g} K "
                       f"(allowed: {law.admissible_temperature_range()} K)")
    width = case.pass_.width
    if s.edge_zone is not None and width is not None:
        cut = 1.0 - s.edge_zone / (0.5 * width)
        if not sec.is_uniform_across(cut):
            out.append(f"{key}: must be the plate's temperature up to the edge zone's cut "
                       f"(zeta = 1 - spread.edge_zone / (pass.width / 2) = {cut:.4g}): the "
                       "plane-strain pass's figures inside the cut are at mid-width's")
    return out
