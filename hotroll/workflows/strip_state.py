"""The strip between a schedule's passes (``workflows/schedule.py``): its thickness, temperature
and strain profiles over the half thickness (and the grain size with a microstructure model),
the state it enters the schedule with and the state a pass hands on from its summary (an
asymmetric pass's whole-thickness profile folded about the middle)."""
from __future__ import annotations

import math

import numpy as np

from hotroll.config.schedule import Schedule
from hotroll.model.profile import ThicknessProfile, folded
from hotroll.model.section import SectionProfile
from hotroll.workflows.schedule_rolls import asymmetric_exit


class StripState:
    """The strip between passes: full thickness (m), temperature and strain profiles, with a
    microstructure model the austenite grain size (m), and its width (m; None: per unit width;
    with [spread] each pass's exit width is the next one's). ``section``: with [spread] the
    temperature over the quarter cross-section (``model/section.py``; its mid-width column is
    ``temperature``), or None (the same at every width)."""

    def __init__(self, thickness: float, temperature: ThicknessProfile,
                 strain: ThicknessProfile, grain: ThicknessProfile | None = None,
                 width: float | None = None, section: SectionProfile | None = None):
        self.thickness, self.temperature, self.strain = thickness, temperature, strain
        self.grain, self.width, self.section = grain, width, section

    def to_dict(self) -> dict:
        d = {"thickness": self.thickness, "temperature_profile": self.temperature.pairs(),
             "strain_profile": self.strain.pairs()}
        if self.grain is not None:
            d["grain_size_profile"] = self.grain.pairs()
        if self.width is not None:
            d["width"] = self.width
        if self.section is not None:
            d["temperature_section"] = self.section.to_dict()
        return d


def entry_state(sch: Schedule) -> StripState:
    t_prof, e_prof = sch.entry_profiles()
    mic = sch.microstructure
    return StripState(sch.strip.thickness,
                      t_prof or ThicknessProfile.uniform(sch.strip.temperature),
                      e_prof or ThicknessProfile.uniform(sch.strip.strain),
                      None if mic.kinetics is None else ThicknessProfile.uniform(mic.grain_size),
                      sch.strip.width)


def exit_state(sch: Schedule, case, summary: dict,
               grain: ThicknessProfile | None = None,
               entry: StripState | None = None) -> StripState:
    """The state at the pass's outlet (``summary["exit_profile"]``); without a strain field
    (a law independent of strain) the homogeneous exit strain, uniform. ``grain``: the grain
    size entering the pass (it changes in the transport after it). ``entry``: the state the
    pass entered with; an isothermal pass (no [thermal] in its case) hands on its temperature
    profile unchanged, and a pass without a temperature or strain profile (an isothermal one
    whose law ignores the strain) its strain profile raised by the pass's mean strain; its width
    the pass's exit width where a [spread] pass has one
    (``asymmetric_exit``). An asymmetric pass's profile (the whole thickness) is folded about
    the middle (``ThicknessProfile.fold``: the mean of the two halves, the next pass's half
    thickness; its through-thickness shear is not handed on)."""
    prof = folded(summary.get("exit_profile"))
    # the width: the 3D pass's exit width ([spread]), else the pass's own (or None)
    width = summary.get("exit_width") or case.pass_.width
    if entry is not None and (prof is None or (prof["temperature"] is None
                                               and prof["strain"] is None)):
        return StripState(exit_thickness(case, summary),
                          *asymmetric_exit(summary, entry.temperature, entry.strain), grain,
                          width, entry.section)
    T = (entry.temperature if case.thermal is None and entry is not None
         else ThicknessProfile(tuple(prof["eta"]), tuple(prof["temperature"])))
    if prof.get("strain") is not None:
        strain = ThicknessProfile(tuple(prof["eta"]), tuple(prof["strain"]))
        e = ThicknessProfile(strain.eta, tuple(np.maximum(strain.values, 0.0)))
    else:
        e = ThicknessProfile.uniform(summary["homogeneous_exit_strain"])
    # the 3D pass's outlet across the width: the plane-strain exit profile plus what the
    # entry's width profile left there (carried through the bite)
    offset = summary.get("exit_temperature_offset")
    if case.thermal is None and entry is not None:     # an isothermal pass: unchanged
        section = entry.section
    elif offset is None and entry is not None and entry.section is not None:
        # a pass not handed the section (its law ignores T): carried through as the bite
        # carries it (the difference from mid-width's unchanged)
        section = SectionProfile.across(T, entry.section.offset_dict())
    else:
        section = SectionProfile.across(T, offset) if offset is not None else None
    return StripState(exit_thickness(case, summary), T, e, grain, width, section)



def exit_thickness(case, summary) -> float:
    """The strip's thickness leaving the pass (m), the next pass's entry: the solve's own, the
    outlet's measured ``exit_thickness``; where the run has none (a report's run whose head
    had not passed), the pass's set one (the case's, or the one found with the force when the
    pass gives its roll gap, ``workflows/gauge.py``)."""
    measured = summary.get("exit_thickness")
    if measured is not None and math.isfinite(measured) and measured > 0.0:
        return float(measured)
    return set_exit_thickness(case, summary)


def set_exit_thickness(case, summary) -> float:
    """The exit thickness the pass was solved for (m): the case's (the rigid roll gap), or
    the gaugemeter's h1 = S + F/M of a pass given by its roll gap."""
    found = summary.get("gauge_thickness")
    return float(found) if found is not None else case.pass_.exit_thickness
