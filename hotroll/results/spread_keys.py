"""The summary keys of the ``[spread]`` section's 3D pass (issue 53; ``model/spread_result.py``),
declared as ``results/summary_keys.py``'s are (the HTML page's group "Width and spread")."""
from __future__ import annotations

from dataclasses import dataclass

from hotroll.results.summary_fields import _f

_G, _W = "Width and spread", "spread"


@dataclass(eq=False)
class SpreadKeys:
    """The 3D pass's keys (``SummaryKeys`` inherits them)."""

    exit_width: float = _f("m", "exit width", "the strip's mean width at the exit (over its "
                           "thickness)", group=_G, when=_W)
    spread: float = _f("m", "spread", "exit width - `width`", group=_G, when=_W)
    edge_bulge: float = _f("m", "edge bulge", "the exit edge's largest half width over the "
                           "thickness minus its smallest (one edge: the barrelling)", group=_G,
                           when=_W)
    edge_drop: float = _f("m", "edge drop", "the exit thickness at mid-width minus at the edge "
                          "(exit_thickness.csv: each width level's)", group=_G, when=_W)
    spread_hill: float = _f("m", "spread, Hill", "Hill's formula as PyRolL has it "
                            "(theory/spread.py, correction factors 1)", group=_G, when=_W)
    spread_sparling: float = _f("m", "spread, Sparling", "Sparling's formula (theory/spread.py)",
                                group=_G, when=_W)
    spread_wusatowski: float = _f("m", "spread, Wusatowski", "Wusatowski's formula "
                                  "(theory/spread.py, correction factors 1)", group=_G, when=_W)
    plane_strain_roll_force_total: float = _f(
        "N", "roll force, plane strain x width", "`roll_force` (the plane-strain pass, per m) "
        "times `width`: what the 3D pass's `roll_force_total` is compared with", group=_G,
        when=_W)
    spread_forward_slip: float = _f(
        "-", "forward slip, whole width", "the 3D pass's mean exit speed (its outlet's flux "
        "over the outlet's area) over the roll's surface speed, minus 1: below the "
        "plane-strain `forward_slip` where the strip spreads", group=_G, when=_W)
    spread_mass_flux_error: float = _f(
        "-", "3D mass flux error", "(out + through the lateral faces - in) / in of the 3D "
        "pass", group=_G, when=_W)
    spread_power_balance_error: float = _f(
        "-", "3D power balance error", "|roll + tension - plastic - friction power| / roll "
        "power of the 3D pass, its roll power torque x omega", group=_G, when=_W)
    midplane_pressure_rms_deviation: float = _f(
        "-", "mid-width pressure deviation (RMS)", "the 3D pass's pressure on the mid-width "
        "plane against the plane-strain pass's, RMS over the 2D pressure's", group=_G, when=_W)
    midplane_contact_pressure_rms_deviation: float = _f(
        "-", "mid-width contact pressure deviation (RMS)", "the 3D pass's contact pressure "
        "on the arc at mid-width against the plane-strain pass's, RMS over the 2D contact "
        "pressure's (the bite only: how far the middle of the strip is from plane strain)",
        group=_G, when=_W)
    midplane_contact_pressure_l2_deviation: float = _f(
        "-", "mid-width contact pressure deviation (L2)", "the same difference in the L2 norm "
        "along the arc over the 2D contact pressure's (the vertex RMS weighs each vertex "
        "alike, so it weighs the singular contact start more on a mesh refined there)",
        group=_G, when=_W)
    midplane_stress_l2_deviation: float = _f(
        "-", "mid-width stress deviation (L2)", "the 3D pass's stress tensor on the mid-width "
        "plane against the plane-strain pass's, L2 over the plane (ahead of the bite and "
        "after it too) over the 2D stress's", group=_G, when=_W)
    midplane_bite_stress_l2_deviation: float = _f(
        "-", "mid-width stress deviation in the bite (L2)", "the same from the contact's "
        "start to its end (the deforming zone) over the 2D stress's there", group=_G, when=_W)
    exit_temperature_offset: dict | None = _f(
        None, "exit temperature across the width", "the 3D pass's outlet: the temperature "
        "less mid-width's at the same height (K), `values` one row per `eta` (0 the centre, "
        "1 the surface) of one per `zeta` (0 mid-width, 1 the edge), carried through the bite "
        "from the entry's (`spread.temperature_profile` or `spread.temperature_section`); "
        "null without one", group=_G, when=_W)
    spread_settled: bool = _f(None, "3D pass settled", "Newton converged and the lateral face "
                              "moved less than its tolerance", group=_G, when=_W)
    spread_rounds: int = _f(None, "3D rounds", "rounds of Newton and the lateral face's "
                            "update", group=_G, when=_W)
    spread_newton_iterations: int = _f(None, "3D Newton iterations", "in all", group=_G,
                                       when=_W)
    spread_dofs: int = _f(None, "3D unknowns", "of the quarter strip's flow problem", group=_G,
                          when=_W)
    spread_layers: int = _f(None, "width layers", "of the quarter strip", group=_G, when=_W)
    spread_edge_layer: float = _f("m", "edge layer", "the width layer at the free edge",
                                  group=_G, when=_W)
    spread_edge_zone: float | None = _f("m", "edge zone", "the outer part of the half width "
                                        "the 3D pass models (`spread.edge_zone`); null: the "
                                        "whole half width", group=_G, when=_W)
    spread_wall_time: float = _f("s", "3D wall time", "the 3D pass's set-up and solve",
                                 group=_G, when=_W)
