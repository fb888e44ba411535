"""The SI unit of every figure hotroll writes or prints: summary.json (and its ``units`` map),
history.csv, the schedule and study tables, the command line and the HTML page. One table;
each key once (per unit width of the upper roll where the key is per unit width). The summary's
keys take their unit from their declaration (``results/summary.py``); the others are here. A
key that is not in the table reads "-" (counts such as ``nonlinear_iterations``)."""
from hotroll.results.summary import Summary

#: key -> SI unit ("-": dimensionless)
UNITS: dict[str, str] = {
    **Summary.units_map(),
    # history: the temperature's own iterations
    "thermal_iterations": "-",
    # the schedule table (schedule.csv)
    "entry_thickness": "m", "entry_width": "m", "reduction": "-", "roll_angular_velocity": "rad/s",
    "mill_power_total": "W", "mass_flux": "m^2/s", "entry_temperature_mean": "K",
    "outlet_temperature_mean": "K", "entry_strain_mean": "-", "exit_strain_mean": "-",
    "newton_iterations": "-", "fe_solves": "-", "wall_time": "s", "transport_duration": "s",
    "transport_heat_lost": "J/m^2", "next_entry_temperature_mean": "K",
    "next_entry_temperature_surface": "K", "next_entry_strain_mean": "-",
    "next_entry_temperature_edge": "K", "next_entry_temperature_section_mean": "K",
    # the microstructure (issue 33): pass and transport columns
    "drx_onset_share": "-", "zener_log_mean": "ln(1/s)", "critical_strain_centre": "-",
    "critical_strain_surface": "-", "kinetics_strain_centre": "-",
    "kinetics_strain_surface": "-", "recrystallised_fraction_mean": "-",
    "recrystallised_fraction_surface": "-", "recrystallised_fraction_centre": "-",
    "grain_size_mean": "m", "grain_size_surface": "m", "grain_size_centre": "m",
    "retained_strain_mean": "-", "retained_strain_surface": "-", "retained_strain_centre": "-",
    "mechanism_surface": "-", "mechanism_centre": "-", "kinetics_temperature_min": "K",
    "kinetics_extrapolated_share": "-",
    # an asymmetric pass's rolls in the schedule table (workflows/schedule_rolls.py)
    **{f"{side}_{key}": unit for side in ("upper", "lower") for key, unit in (
        ("roll_radius", "m"), ("roll_surface_speed", "m/s"), ("roll_force", "N/m"),
        ("roll_torque", "N m/m"), ("roll_power", "W/m"))},
    # a tandem's tensions (schedule.csv, schedule.json)
    "back_tension": "Pa", "front_tension": "Pa", "interstand_tensions": "Pa",
    "flux_mismatch": "-", "tension_runs": "-", "stand_flux_error": "-",
    # a schedule study's own columns
    "passes": "-", "max_roll_force": "N/m", "total_roll_power": "W/m",
}
