"""The SI unit of every figure hotroll writes or prints: summary.json (and its ``units`` map),
history.csv, the schedule and study tables, the command line and the HTML page. One table;
each key once (per unit width of the upper roll where the key is per unit width). A key that is
not here reads "-" (counts such as ``nonlinear_iterations``)."""

#: key -> SI unit ("-": dimensionless)
UNITS: dict[str, str] = {
    # summary: mechanics, engineering figures, checks, contact
    "roll_force": "N/m", "roll_torque": "N m/m", "roll_power": "W/m", "horizontal_force": "N/m",
    "forward_slip": "-", "neutral_angle": "rad", "neutral_point": "m", "contact_length": "m",
    "entry_velocity": "m/s", "exit_velocity": "m/s", "mass_flux_in": "m^2/s",
    "mass_flux_out": "m^2/s", "plastic_power": "W/m", "friction_power": "W/m",
    "penalty_power": "W/m", "outlet_penalty_power": "W/m", "tension_power": "W/m", "a_f": "m^-m",
    "balance_error": "-", "power_balance_error": "-", "penalty_share": "-", "mass_flux_error": "-",
    "symmetry_stress_force_y": "N/m", "free_top_force_share": "-", "h_contact": "m",
    "wall_time_s": "s", "estimated_memory": "B", "estimated_seconds": "s", "time": "s", "dt": "s",
    "K": "Pa s^m", "m": "-", "roll_centre": "m", "roll_radius": "m", "roll_surface_speed": "m/s",
    "contact_start": "m", "contact_end": "m", "back_tension": "Pa", "front_tension": "Pa",
    "exit_strain": "-", "homogeneous_exit_strain": "-", "mean_flow_stress": "Pa",
    "mean_strain_rate": "1/s", "mean_pressure": "Pa", "width": "m", "roll_force_total": "N",
    "roll_torque_total": "N m", "roll_power_total": "W", "mill_power": "W", "temperature": "K",
    "surface_residual_h": "h", "force_balance": "N/m", "neutral_angle_flux": "rad",
    "sticking_zone": "rad", "contact_start_angle": "rad", "contact_end_angle": "rad",
    "min_contact_pressure": "Pa", "leak_to_slip": "-", "exit_thickness": "m",
    "pressure_last_update": "Pa",
    # summary and history: the temperature
    "exit_temperature_mean": "K", "exit_temperature_surface": "K", "max_temperature": "K",
    "min_temperature": "K", "plastic_heat": "W/m", "friction_heat_to_strip": "W/m",
    "heat_to_roll": "W/m", "heat_to_air": "W/m", "advected_in": "W/m", "advected_out": "W/m",
    "conducted_in": "W/m", "heat_balance_error": "-", "thermal_iterations": "-",
    "thermal_dofs": "-", "thermal_layer": "m",
    # the schedule table (schedule.csv)
    "entry_thickness": "m", "reduction": "-", "roll_angular_velocity": "rad/s",
    "mill_power_total": "W", "mass_flux": "m^2/s", "entry_temperature_mean": "K",
    "outlet_temperature_mean": "K", "entry_strain_mean": "-", "exit_strain_mean": "-",
    "newton_iterations": "-", "fe_solves": "-", "wall_time": "s", "transport_duration": "s",
    "transport_heat_lost": "J/m^2", "next_entry_temperature_mean": "K",
    "next_entry_temperature_surface": "K", "next_entry_strain_mean": "-",
    # a schedule study's own columns
    "passes": "-", "max_roll_force": "N/m", "total_roll_power": "W/m",
}
