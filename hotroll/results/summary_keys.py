"""The keys of ``summary.json``, each declared once as a field of ``SummaryKeys`` with its SI
unit, its label for a person, its meaning, the HTML page's group and the condition it exists
under (``when``); an asymmetric pass's per-roll entry (``ROLL_ENTRY``) beside them.
``results/summary.py``'s ``Summary`` reads them as a mapping and generates the reference page
from them."""
from __future__ import annotations

from dataclasses import dataclass

from hotroll.results.spread_keys import SpreadKeys
from hotroll.results.summary_fields import ABSENT, GROUPS, _f  # noqa: F401 (re-exported)

#: An asymmetric pass's ``rolls`` entry (one per roll, the upper's first): key -> (SI unit or
#: None, meaning). Each figure is that roll's history column (``upper_<key>``, ``lower_<key>``:
#: solvers/gap_measure.py), the window's mean; x positions where the case puts the roll axes.
ROLL_ENTRY: dict[str, tuple[str | None, str]] = {
    "side": (None, "`upper` or `lower`"),
    "radius": ("m", "the roll's radius"),
    "surface_speed": ("m/s", "the roll's surface speed omega R"),
    "roll_force": ("N/m", "the strip's push on the roll along its axis direction (> 0), per m "
                   "of width"),
    "horizontal_force": ("N/m", "the roll's horizontal force on the strip (> 0: drives it on)"),
    "roll_torque": ("N m/m", "the torque the roll's drive supplies (< 0: the strip drives the "
                    "roll, a braking roll)"),
    "roll_power": ("W/m", "the power the roll's drive supplies (< 0: the roll takes power)"),
    "contact_length": ("m", "the arc in contact"),
    "neutral_angle": ("rad", "where the slip changes sign, from the roll's vertical centre "
                      "line, positive towards the entry; null where it does not"),
    "neutral_x": ("m", "x of the neutral point"),
    "forward_slip": ("-", "v_exit / U of this roll - 1"),
    "contact_start": ("m", "x where the strip first touches this roll"),
    "contact_end": ("m", "x where it leaves this roll"),
    "min_contact_pressure": ("Pa", "the lowest contact pressure on this roll"),
    "contact_end_kind": (None, "how its contact ends: `gap`, `separation`, `recovery`, `wrap`, "
                         "`bound` (as the top-level key)"),
    "roll_overlap": ("m", "how deep the free surface after its contact's end lies inside it"),
    "contact_end_pressure": ("Pa", "the contact pressure at its contact's end"),
}
#: ... and a flattening roll's (``[roll] model`` or its side's table: hitchcock or elastic),
#: from its contact at the end of the solve (the half model's top-level ``roll_*`` keys).
ROLL_FLATTENING_ENTRY: dict[str, tuple[str | None, str]] = {
    "roll_model": (None, "`hitchcock` or `elastic`"),
    "roll_flattening": ("m", "how far its flattened surface lies below the rigid roll through "
                        "the same gap, largest over its contact"),
    "roll_equivalent_radius": ("m", "the radius of the circle that fits its flattened surface "
                               "over its contact"),
    "roll_updates": ("-", "its surface's updates in the fixed point"),
    "roll_last_move": ("m", "the largest move of its arc in the last update"),
    "roll_shape_error": ("-", "how far its surface lies from the one its final tractions "
                         "give, over the largest flattening"),
}
_ASYM = "; an asymmetric pass: "
_WHOLE = _ASYM + "the whole strip"



@dataclass(eq=False)
class _CoreKeys:
    """The keys of every pass (``SummaryKeys``)."""

    # --- the run ------------------------------------------------------------------------------
    case_name: str = _f(None, "case", "the case's name")
    method: str = _f(None, "method", "`steady` or `transient`")
    status: str = _f(None, "status", "`steady`, `unsettled`, `failed`, `end_time`, ...")
    failure: str | None = _f(None, "failure", "the reason a run failed or is not conserved")
    converged: bool = _f(None, "converged", "steady, its last solve converged, not outlet driven")
    steady_state: bool = _f(None, "steady state", "the run reached its steady state")
    outlet_driven: bool = _f(None, "outlet driven", "no neutral point: the outlet penalty drives "
                             "the strip (exit code 6)")
    # --- the pass (group "Pass", in the page's order) -----------------------------------------
    roll_force: float = _f("N/m", "roll force, one roll", "per m of width, one roll" + _ASYM
                           + "the mean of the two rolls' (each in `rolls`)", group="Pass")
    roll_force_total: float = _f("N", "roll force, whole width", "one roll's force over the whole "
                                 "width: `roll_force` x `width`, with `[spread]` the 3D "
                                 "pass's", group="Pass", when="width")
    roll_torque: float = _f("N m/m", "roll torque, one roll", "per m of width, one roll"
                            + _ASYM + "the mean of the two rolls' (each in `rolls`)",
                            group="Pass")
    roll_torque_total: float = _f("N m", "roll torque, whole width", "one roll's torque (with "
                                  "`[spread]` the 3D pass's)", group="Pass", when="width")
    roll_power: float = _f("W/m", "roll power, one roll", "per m of width, one roll" + _ASYM
                           + "the mean of the two rolls' (each in `rolls`)", group="Pass")
    roll_power_total: float = _f("W", "roll power, whole width", "one roll's power (with "
                                 "`[spread]` the 3D pass's)", group="Pass",
                                 when="width")
    mill_power: float = _f("W", "mill power, both rolls", "both rolls' power",
                           group="Pass", when="width")
    forward_slip: float = _f("-", "forward slip", "v_exit / |U_roll| - 1" + _ASYM + "the mean "
                             "of the two rolls' (each in `rolls`)", group="Pass")
    neutral: str = _f(None, "neutral point", "the neutral story in words, the one every "
                      "output shows (`results/neutral.py`): the point's angle in degrees and "
                      "radians, or `none: sticking zone from ... to ...` (the strip skids, "
                      "no slip measured)", group="Pass")
    neutral_angle: float | None = _f("rad", "neutral angle", "from the roll's vertical centre "
                                     "line, positive towards the entry; null where no point is "
                                     "neutral (`neutral`)", group="Pass")
    neutral_point: list | None = _f("m", "neutral point (x, y)", "(x, y) on the roll; null "
                                    "where no point is neutral", group="Pass")
    sticking_zone: list | None = _f("rad", "sticking zone (from, to)", "start and end angle of "
                                    "the longest stretch slipping below 1e-3 of the roll speed",
                                    group="Pass")
    sticking_zone_x: list | None = _f("m", "sticking zone (x from, x to)", "where "
                                      "`sticking_zone` starts and ends", group="Pass")
    mean_pressure: float | None = _f("Pa", "mean roll pressure", "roll force over contact "
                                     "length", group="Pass")
    mean_flow_stress: float = _f("Pa", "mean flow stress in the gap", "mean over the roll gap",
                                 group="Pass")
    mean_strain_rate: float = _f("1/s", "mean strain rate in the gap", "mean over the roll gap",
                                 group="Pass")
    contact_length: float = _f("m", "contact arc length", "the arc in contact" + _ASYM
                               + "the mean of the two rolls'", group="Pass")
    entry_velocity: float = _f("m/s", "entry velocity", "", group="Pass")
    exit_velocity: float = _f("m/s", "exit velocity", "", group="Pass")
    exit_strain: float | None = _f("-", "exit strain (mean)", "the strain carried to the exit",
                                   group="Pass")
    homogeneous_exit_strain: float = _f("-", "homogeneous exit strain", "entry strain + 2/sqrt3 "
                                        "ln(h0/h1)", group="Pass")
    horizontal_force: float = _f("N/m", "horizontal roll force", "the roll's horizontal force on "
                                 "the plate" + _ASYM + "the mean of the two rolls'",
                                 group="Pass")
    speed_ratio: float = _f("-", "speed ratio", "the upper roll's surface speed over the "
                            "lower's", group="Pass", when="asymmetric")
    rolls: list = _f(None, "the two rolls", "one entry per roll, the upper's then the lower's, "
                     "each with the keys of the table below (their units in `units` as "
                     "`rolls.<key>`); neutral story, contact start and end, angles and "
                     "pressures of the legacy one-roll keys are the upper roll's",
                     group="Pass", when="asymmetric")
    cross_shear_length: float = _f("m", "cross-shear zone length", "the distance between the "
                                   "two rolls' neutral points (0 for equal rolls; null where a "
                                   "roll has none)", group="Pass", when="asymmetric")
    exit_curvature: float = _f("1/m", "exit curvature", "the exit strip's curvature from its "
                               "rigid rotation over its speed; > 0 curls up (towards the upper "
                               "roll)", group="Pass", when="asymmetric")
    exit_surface_curvature: float = _f("1/m", "exit curvature from the surfaces", "the "
                                       "same curvature from the traced free surfaces' "
                                       "centreline (a second measure: it should equal "
                                       "exit_curvature)", group="Checks", when="asymmetric")
    exit_angle: float = _f("rad", "exit angle", "the exit strip's direction, > 0 upwards",
                           group="Pass", when="asymmetric")
    exit_shear_strain_upper: float = _f("-", "exit shear strain, upper surface", "the "
                                        "engineering shear strain gamma_xy the pass leaves at "
                                        "the strip's upper surface (> 0: the upper layers "
                                        "moved forward relative to the lower)", group="Pass",
                                        when="asymmetric")
    exit_shear_strain_mid: float = _f("-", "exit shear strain, mid-thickness", "gamma_xy at "
                                      "the strip's mid-thickness at the exit", group="Pass",
                                      when="asymmetric")
    exit_shear_strain_lower: float = _f("-", "exit shear strain, lower surface", "gamma_xy "
                                        "at the strip's lower surface at the exit",
                                        group="Pass", when="asymmetric")
    exit_shear_strain_mean: float = _f("-", "exit shear strain, thickness mean", "gamma_xy "
                                       "averaged through the thickness at the exit (0 for "
                                       "equal rolls)", group="Pass", when="asymmetric")
    entry_guide_force_y: float = _f("N/m", "entry guide force", "the vertical force the entry "
                                    "guide (v_y = 0 on the inlet) puts on the strip",
                                    group="Pass", when="asymmetric")
    vertical_balance_error: float = _f("-", "vertical balance error", "|rolls' and entry "
                                       "guide's vertical forces| over the upper roll's force "
                                       "(an identity of a converged solve)", group="Checks",
                                       when="asymmetric")
    a_f: float | None = _f("m^-m", "friction coefficient a_f", "the viscoplastic friction "
                           "parameter used (estimated or given); null for another law",
                           group="Pass")
    # --- temperature and heat (with [thermal]) -------------------------------------------------
    exit_temperature_mean: float = _f("K", "exit temperature, mean", "the outlet's mean",
                                      group="Temperature and heat", when="thermal")
    exit_temperature_surface: float = _f("K", "exit temperature, surface", "the surface at the "
                                         "gap" + _ASYM + "the upper roll's surface",
                                         group="Temperature and heat", when="thermal")
    exit_temperature_surface_lower: float = _f("K", "exit temperature, lower surface",
                                               "an asymmetric pass: the lower roll's surface "
                                               "at the gap", group="Temperature and heat",
                                               when="thermal, asymmetric")
    max_temperature: float = _f("K", "max temperature", "over the strip",
                                group="Temperature and heat", when="thermal")
    min_temperature: float = _f("K", "min temperature", "over the strip",
                                group="Temperature and heat", when="thermal")
    plastic_heat: float = _f("W/m", "plastic heat", "half strip" + _WHOLE,
                             group="Temperature and heat", when="thermal")
    friction_heat_to_strip: float = _f("W/m", "friction heat to the strip", "half strip"
                                       + _WHOLE, group="Temperature and heat", when="thermal")
    heat_to_roll: float = _f("W/m", "heat to the roll", "half strip" + _WHOLE
                             + " (to both rolls)", group="Temperature and heat", when="thermal")
    heat_to_air: float = _f("W/m", "heat to the air", "half strip" + _WHOLE,
                            group="Temperature and heat", when="thermal")
    advected_in: float = _f("W/m", "advected in", "heat carried in through the inlet",
                            group="Temperature and heat", when="thermal")
    advected_out: float = _f("W/m", "advected out", "heat carried out through the outlet",
                             group="Temperature and heat", when="thermal")
    conducted_in: float = _f("W/m", "conducted in", "heat conducted in through the inlet",
                             group="Temperature and heat", when="thermal")
    # --- checks -------------------------------------------------------------------------------
    balance_error: float = _f("-", "force balance error", "the sum of `force_balance` over the "
                              "roll force" + _ASYM + "the vertical balance's "
                              "(`vertical_balance_error`)", group="Checks")
    power_balance_error: float = _f("-", "power balance error", "", group="Checks")
    mass_flux_error: float = _f("-", "mass flux error", "|out - in| / in", group="Checks")
    heat_balance_error: float = _f("-", "heat balance error", "", group="Checks", when="thermal")
    penalty_share: float = _f("-", "penalty power share", "penalty power over roll power",
                              group="Checks")
    free_top_force_share: float = _f("-", "free top force share", "the constrained model's share "
                                     "of the roll load on the free tops", group="Checks")
    surface_residual_h: float | None = _f("h", "last free-surface move (in mesh sizes h)",
                                          "the steady fixed point's last move of the free tops",
                                          group="Checks")
    unconverged_steps_in_window: int = _f(None, "unconverged steps in window", "left out of the "
                                          "means", group="Checks")
    exit_correction_normal_force_change: float = _f(None, "exit correction normal force change",
                                                    "what the exit-pressure correction changes",
                                                    group="Checks")
    # --- solver -------------------------------------------------------------------------------
    h_contact: float = _f("m", "contact mesh size", "", group="Solver")
    dofs: int = _f(None, "unknowns", "of the flow problem", group="Solver")
    steps: int = _f(None, "steps", "time steps (transient); 0 for the steady solver",
                    group="Solver")
    time: float | None = _f("s", "time", "simulated time (transient)", group="Solver")
    dt: float | None = _f("s", "dt", "time step (transient)", group="Solver")
    newton_solves: int | None = _f(None, "newton solves", "steady: Newton solves", group="Solver")
    coupling_updates: int | None = _f(None, "coupling updates", "steady: updates of a_f and the "
                                      "free tops", group="Solver")
    nonlinear_iterations: int = _f(None, "nonlinear iterations", "in all", group="Solver")
    iterations_per_step: float | None = _f(None, "iterations per step", "transient",
                                           group="Solver")
    averaged_over_steps: int = _f(None, "averaged over steps", "the window of the summary means",
                                  group="Solver")
    wall_time_s: float = _f("s", "wall time", "of the solve and the files", group="Solver")
    # --- the rest -----------------------------------------------------------------------------
    neutral_angle_reason: str | None = _f(None, "why no neutral point", "why `neutral_angle` "
                                          "is null")
    neutral_angle_in_sticking_zone: bool = _f(None, "neutral angle in sticking zone", "the sign "
                                              "change lies in the sticking zone")
    neutral_angle_flux: float | None = _f("rad", "angle where the strip's mean speed is the "
                                          "roll's horizontal speed", "from the mass flux: "
                                          "y(phi) U cos(phi) = q, slab theory's neutral angle "
                                          "of the computed flux; not the neutral point "
                                          "(`neutral`), defined on a sticking arc too")
    mass_flux_in: float = _f("m^2/s", "mass flux in", "half strip" + _ASYM + "the whole strip")
    mass_flux_out: float = _f("m^2/s", "mass flux out", "half strip" + _ASYM + "the whole strip")
    plastic_power: float = _f("W/m", "plastic power", "")
    friction_power: float = _f("W/m", "friction power", "")
    penalty_power: float = _f("W/m", "penalty power", "")
    outlet_penalty_power: float = _f("W/m", "outlet penalty power", "")
    tension_power: float = _f("W/m", "tension power", "")
    force_balance: dict = _f("N/m", "force balance", "the forces on the plate (x, y) from the "
                             "roll, the free tops, the cut faces (`tension`) and the symmetry "
                             "line" + _ASYM + "from each roll (`upper_roll`, `lower_roll`) and "
                             "the entry guide")
    symmetry_stress_force_y: float = _f("N/m", "symmetry stress force y", "the force through the "
                                        "symmetry line from the stress on it")
    contact_loss: list = _f(None, "contact loss", "stretches (x from, x to) where the pressure "
                            "turns tensile")
    contact_loss_detected: bool = _f(None, "contact loss detected", "")
    contact_method: str = _f(None, "contact method", "`multiplier` or `penalty`")
    unilateral: bool = _f(None, "unilateral", "the strip may leave the roll (true, the default) "
                          "or is held to it up to the gap (false: bilateral)")
    contact_end_kind: str | None = _f(None, "contact end", "`gap`, `separation` (the strip "
                                      "leaves the roll before the gap), `recovery` (an elastic "
                                      "strip past it), `wrap` (a strip that curls onto the roll, "
                                      "past the gap), `bound` or `held` (bilateral)")
    roll_overlap: float | None = _f("m", "roll overlap", "how deep the free surface after a "
                                    "contact's end lies inside its roll (0: outside; over "
                                    "0.02 contact elements: exit code 10)")
    separation_angle: float | None = _f("rad", "separation angle", "where the strip leaves "
                                        "the roll before the gap (angle from the gap)",
                                        group="Pass")
    contact_end_pressure: float | None = _f("Pa", "contact end pressure", "the contact "
                                            "pressure at the contact's end")
    contact_start_angle: float | None = _f("rad", "contact start angle", "")
    contact_end_angle: float | None = _f("rad", "contact end angle", "")
    min_contact_pressure: float | None = _f("Pa", "min contact pressure", "the most tensile "
                                            "(lowest) contact pressure")
    entry_pressure: float | None = _f("Pa", "entry pressure", "the contact pressure's mean "
                                      "over the first 5 % of the contact from its start (the "
                                      "corner's own value is singular, growing as h^-m)")
    exit_thickness: float = _f("m", "exit thickness", "measured (unilateral: below the gap)")
    pressure_last_update: float | None = _f("Pa", "pressure last update", "exact contact: the "
                                            "last Newton step's multiplier change")
    fixed_point_settled: bool | None = _f(None, "fixed point settled", "the steady "
                                          "free-surface/a_f fixed point settled")
    free_surface: str = _f(None, "free surface", "`traced` or `constrained`")
    nonlinear: str = _f(None, "nonlinear solver", "`newton` or `picard`")
    roll_centre: list = _f("m", "roll centre", "(x, y)")
    roll_radius: float = _f("m", "roll radius", "")
    roll_surface_speed: float = _f("m/s", "roll surface speed", "")
    contact_start: list | None = _f("m", "contact start", "(x, y)")
    contact_end: list | None = _f("m", "contact end", "(x, y)")
    K: float = _f("Pa s^m", "consistency K", "reference value for a temperature- or "
                  "strain-dependent law")
    m: float = _f("-", "rate exponent m", "reference value for a temperature-dependent law")
    friction_law: str = _f(None, "friction law", "")
    friction_mu: float | None = _f(None, "friction mu", "Coulomb's mu")
    friction_factor: float | None = _f(None, "friction factor", "Tresca's factor")
    back_tension: float = _f("Pa", "back tension", "")
    front_tension: float = _f("Pa", "front tension", "")
    thermal: bool = _f(None, "thermal", "whether `[thermal]` is on")
    thermal_dofs: int = _f("-", "thermal unknowns", "the strip mesh's unknowns", when="thermal")
    thermal_layer: float = _f("m", "thermal layer", "the chilled layer's thickness",
                              when="thermal")
    mill_modulus: float = _f("N/m", "mill modulus", "the stand's modulus M (`[pass] "
                             "mill_modulus`)", group="Pass", when="mill")
    mill_stretch: float = _f("m", "mill stretch", "F/M: the stand's stretch under the whole "
                             "width's force", group="Pass", when="mill")
    gap_setting: float = _f("m", "gap to set", "the no-load roll gap S = h1 - F/M that gives "
                            "the exit thickness (gaugemeter equation)", group="Pass", when="mill")
    roll_gap: float = _f("m", "roll gap set", "the no-load gap S given (`[pass] roll_gap`); the "
                         "exit thickness h1 = S + F/M was found with the force", group="Pass",
                         when="gap")
    gauge_thickness: float = _f("m", "exit thickness from the gap", "h1 = S + F/M, the pass's "
                                "exit thickness the search found (the measured one: "
                                "`exit_thickness`)", group="Pass", when="gap")
    gauge_solves: int = _f(None, "FE solves for the gap", "solves of the pass at trial exit "
                           "thicknesses until |h1 - S - F/M| <= 1e-4 h1", group="Solver",
                           when="gap")
    roll_model: str = _f(None, "roll model", "`hitchcock` or `elastic` (`[roll] model`)",
                         group="Pass", when="roll")
    roll_flattening: float = _f("m", "roll flattening", "how far the flattened surface lies "
                                "below the rigid roll through the same gap: largest over the "
                                "contact (at its entry)", group="Pass", when="roll")
    roll_equivalent_radius: float = _f("m", "equivalent roll radius", "R' of the circle that "
                                       "fits the flattened surface over the contact",
                                       group="Pass", when="roll")
    roll_updates: int = _f("-", "roll updates", "the surface's updates in the fixed point",
                           when="roll")
    roll_shape_error: float = _f("-", "roll shape error", "max |w - w(p, q)| / max |w(p, q)| over "
                                 "the contact: how far the roll's surface lies from the one its "
                                 "final tractions give (the disc's rim or Hitchcock's circle)",
                                 when="roll")
    roll_last_move: float = _f("m", "roll's last move", "the largest move of the arc the strip "
                               "lies on (its height at fixed x, the roll's axis shift included) "
                               "in the roll's last update: below roll.tolerance x h1/2 once "
                               "settled; how far from settled an unsettled run stopped",
                               when="roll")
    estimated_dofs: int = _f(None, "estimated unknowns", "the estimate made before meshing",
                             when="run")
    estimated_memory: float = _f("B", "estimated memory", "the estimate made before meshing",
                                 when="run")
    estimated_seconds: float = _f("s", "estimated seconds", "the estimate made before meshing",
                                  when="run")
    warm_start_from: str | None = _f(None, "warm start from", "the neighbour a warm start came "
                                     "from", when="run")
    warm_start_failed: bool = _f(None, "warm start failed", "solved again from cold", when="run")
    warnings: list = _f(None, "warnings", "what the case's plausibility check reports and the "
                        "run went on with (config/plausibility.py): a pass outside its flow-"
                        "stress fit's ranges (the figure and the range), a steel below its "
                        "austenite, a nondimensional case; each `section.key: ...`", when="run")
    solver_threads: list = _f(None, "solver threads", "the thread counts the run's parallel "
                              "regions used (a Newton step, the meshing, the measures: "
                              "fem/reproducible.threads_now, the cores no other running "
                              "process wanted; serial between them)", when="run")
    leak_to_slip: float = _f("-", "leak to slip", "the leak through the roll over the forward "
                             "slip")
    not_conserved: bool = _f(None, "not conserved", "a conservation check failed")
    contact_unresolved: bool = _f(None, "contact not resolved", "the strip lies inside a roll "
                                  "past a contact's end, or a contact's end is held at the end "
                                  "of its range (exit code 10)")
    width: float | None = _f("m", "width", "`[pass] width`")
    temperature: float | None = _f("K", "plate temperature", "the plate's uniform (or entry) "
                                   "temperature; null where nothing depends on it (no "
                                   "`[thermal]`, a flow-stress law without temperature)")
    exit_profile: dict | None = _f(None, "exit profile", "the outlet's temperature and strain "
                                   "profiles over eta (0 the centre line, 1 the surface); in a "
                                   "thermal run each streamline's pass strain and "
                                   "strain-weighted means of ln(edot) and 1/T" + _ASYM
                                   + "eta from -1 (the lower surface) to 1 (the upper), with "
                                   "the shear strain gamma_xy (`shear_strain`)")
    units: dict = _f(None, "units", "each figure's SI unit")
    exit_code: int = _f(None, "exit code", "see cli.md#exit-codes")


@dataclass(eq=False)
class SummaryKeys(SpreadKeys, _CoreKeys):
    """Every key of summary.json, ABSENT until set (``Summary`` holds the values): the core
    keys first, then the 3D pass's (``results/spread_keys.py``)."""
