"""Plant one bug at a time in a copy of the package and run the test suite on it (issue 20).

Each bug is a one-line textual change: the seven of issue 20 (a scaled force, a scaled torque,
a doubled friction, the a_f constant C5 x 10, resume off, the exit correction off, no contact
loss) and more of the same kind in other figures. For each the default suite runs on a copy of
``hotroll/`` and ``tests/`` (``-x``: it stops at the first failure) and the table records the
first failing test, or SURVIVED. A bug that survives is a figure without a test.

    python scripts/planted_bugs.py                    # all, table in docs/planted_bugs.md
    python scripts/planted_bugs.py --only force,torque
    python scripts/planted_bugs.py --list

It takes 1-3 minutes per caught bug on 2 cores (the whole suite for a survivor). Not in CI.
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from datetime import date
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: name -> (file, old text, new text, what it breaks). ``old`` must occur exactly once.
BUGS: dict[str, tuple[str, str, str, str]] = {
    # --- the seven of issue 20 ---
    "force": ("hotroll/fem/quantities.py",
              'out["roll_force"], out["horizontal_force"] = -out["roll_force_y"]',
              'out["roll_force"], out["horizontal_force"] = -1.25 * out["roll_force_y"]',
              "roll force x 1.25"),
    "torque": ("hotroll/fem/quantities.py",
               '"roll_torque": K * form.integrate_friction',
               '"roll_torque": 1.15 * K * form.integrate_friction',
               "roll torque x 1.15"),
    "friction_form": ("hotroll/fem/rolling_form.py",
                      "friction_term = (chi * self.friction_coefficient(w, lam=lam)",
                      "friction_term = (chi * 2.0 * self.friction_coefficient(w, lam=lam)",
                      "friction stress doubled in the weak form only"),
    "friction_coefficient": ("hotroll/fem/rolling_form.py",
                             "return self.friction.coefficient(s * s, **self.friction_arguments",
                             "return 2.0 * self.friction.coefficient(s * s, **self.friction_arguments",
                             "friction stress doubled in the form and the quantities"),
    "c5": ("hotroll/model/friction_estimate.py", "c5 = 2.0**p", "c5 = 10.0 * 2.0**p",
           "C5 of the a_f estimate (3.15) x 10"),
    "resume": ("hotroll/solvers/transient.py", "    def _load_state(self) -> bool:\n",
               "    def _load_state(self) -> bool:\n        return False\n",
               "resume switched off"),
    "exit_corrected": ("hotroll/model/contact_figures.py",
                       '    sn = np.array(profile["normal_stress"], dtype=float)\n    if len(sn) < 4:',
                       '    sn = np.array(profile["normal_stress"], dtype=float)\n    return sn\n'
                       '    if len(sn) < 4:',
                       "exit-pressure correction switched off"),
    "contact_loss": ("hotroll/model/contact_figures.py",
                     "    sn = np.asarray(normal_stress)\n",
                     "    sn = np.asarray(normal_stress)\n    return []\n",
                     "contact_loss always []"),
    # --- exact contact (issue 30) ---
    "multiplier": ("hotroll/fem/rolling_form.py",
                   "out[verts] = self.lam_scale * self.multiplier.vec",
                   "out[verts] = 1.1 * self.lam_scale * self.multiplier.vec",
                   "the reported contact pressure (the multiplier) x 1.1"),
    "multiplier_form": ('hotroll/fem/rolling_form.py',
        'term = self._lam * (lam * (v * n) + xi * (u * n))',
        'term = self._lam * (1.1 * lam * (v * n) + xi * (u * n))',
        "the multiplier's work in the weak form x 1.1"),
    "contact_end": ("hotroll/results/run_summary.py",
                    '"contact_end_angle": float(prof["angle"][-1])',
                    '"contact_end_angle": 1.1 * float(prof["angle"][-1])',
                    "the contact arc's end angle x 1.1"),
    "sticking_floor": ("hotroll/model/contact_figures.py", "STICKING_FLOOR = 1e-3",
                       "STICKING_FLOOR = 1.1e-3", "the sticking floor x 1.1"),
    "leak_to_slip": ("hotroll/results/outcome.py", "return abs(leak) / max(abs(slip), 0.01)",
                     "return 0.5 * abs(leak) / max(abs(slip), 0.01)",
                     "the leak against the slip halved (exit code 7 missed)"),
    "contact_start_angle": ("hotroll/results/run_summary.py",
                            '"contact_start_angle": float(prof["angle"][0])',
                            '"contact_start_angle": 1.1 * float(prof["angle"][0])',
                            "the contact arc's start angle x 1.1"),
    "min_contact_pressure": ("hotroll/results/run_summary.py",
                             '"min_contact_pressure": float(-np.max(prof["normal_stress"]))',
                             '"min_contact_pressure": 1.1 * float(-np.max(prof["normal_stress"]))',
                             "the smallest contact pressure x 1.1"),
    "neutral_angle_flux": ("hotroll/results/run_summary.py", '"neutral_angle_flux": ang_flux,',
                           '"neutral_angle_flux": 1.1 * ang_flux,', "the flux neutral angle x 1.1"),
    "exit_thickness": ("hotroll/results/run_summary.py",
                       '"exit_thickness": last.get("exit_thickness_measured", math.nan),',
                       '"exit_thickness": 1.1 * last.get("exit_thickness_measured", math.nan),',
                       "the exit thickness x 1.1"),
    "pressure_last_update": ("hotroll/solvers/record.py",
                             "pressure_last_update=(run.result.stats[-1].multiplier_update",
                             "pressure_last_update=(1.1 * run.result.stats[-1].multiplier_update",
                             "the pressure's last Newton change x 1.1"),
    # the neutral story is decided in results/neutral.py (issue 51, item 4)
    "sticking_zone": ("hotroll/results/neutral.py",
                      "zone = None if stick is None else (float(stick[0]), float(stick[1]))",
                      "zone = None if stick is None else (1.1 * float(stick[0]), "
                      "1.1 * float(stick[1]))",
                      "the sticking zone's angles x 1.1"),
    "neutral_noise": ("hotroll/results/neutral.py", "    if flips > 1:", "    if flips > 0:",
                      "a single sign change in a sticking zone taken for noise"),
    "sign_changes": ("hotroll/model/contact_figures.py", "np.count_nonzero(np.diff(sign))",
                     "np.count_nonzero(np.diff(sign[1:]))",
                     "the slip's first sign change in a zone not counted"),
    "misaka": ("hotroll/model/flow_stress/misaka.py", "return KGF_PER_MM2 * ops.exp(expo)",
               "return 1.1 * KGF_PER_MM2 * ops.exp(expo)", "Misaka's flow stress x 1.1"),
    "misaka_build": ("hotroll/model/flow_stress/misaka.py", 'build=lambda p, eps0: Misaka(p["carbon"], eps0=eps0)',
                     'build=lambda p, eps0: Misaka(1.1 * p["carbon"], eps0=eps0)',
                     "the case's carbon content x 1.1 on its way to the law"),
    "couplings_kept": ('hotroll/solvers/steady.py',
        '        self.couplings = self._couplings(warm=hasattr(warm, "apply"))\n',
        '        self.couplings = getattr(self, "couplings", None) or self._couplings(warm=hasattr(warm, "apply"))\n',
        "a run kept by a sweep keeps the first case's couplings"),
    "separation_point": ("hotroll/fem/free_surface.py",
                         "new = float(np.clip(min(max(new, x_e - trust), x_e + trust), lo_b, hi_b))",
                         "new = float(np.clip(min(max(hi_b - 1.1 * (hi_b - new), x_e - trust), "
                         "x_e + trust), lo_b, hi_b))",
                         "the contact end's step aims 1.1 times as far from the gap"),
    "unloading": ("hotroll/fem/rolling_form.py",
                  "c = self.compliance * depth * self._lam",
                  "c = 1.1 * self.compliance * depth * self._lam",
                  "the strip's elastic compliance in the contact x 1.1"),
    "strip_modulus": ("hotroll/model/strip_elasticity.py",
                      "return 2.0 * self.shear(T) * (1.0 + self.nu)",
                      "return 1.1 * 2.0 * self.shear(T) * (1.0 + self.nu)",
                      "the strip's default Young's modulus x 1.1"),
    "layer_depth": ("hotroll/solvers/problem.py",
                    "return 2.0 * min(rp.gap_radius, 1e3 * rp.radius) * (1.0 - nu * nu) * two_k / E",
                    "return 2.2 * min(rp.gap_radius, 1e3 * rp.radius) * (1.0 - nu * nu) * two_k / E",
                    "the strip's elastic layer depth x 1.1"),
    "nodal_traction": ("hotroll/fem/quantities.py",
                       "    out[iv[1:-1]] = (force / length)[1:-1]\n",
                       "    out[iv[1:-1]] = p[1:-1]\n",
                       "the contact pressure's nodal values: the multiplier's own"),
    "entry_pressure": ("hotroll/results/run_summary.py",
                       "    L = ENTRY_SHARE * s[-1]\n",
                       "    L = 1.1 * ENTRY_SHARE * s[-1]\n",
                       "the entry pressure averaged over 1.1 x its length"),
    "separation_angle": ("hotroll/results/run_summary.py",
                         'return float(prof["angle"][-1]) - gap',
                         'return 1.1 * (float(prof["angle"][-1]) - gap)',
                         "the reported separation angle x 1.1"),
    # --- more of the same kind ---
    "power": ("hotroll/fem/quantities.py", '"roll_power": K * form.integrate_friction',
              '"roll_power": 1.1 * K * form.integrate_friction', "roll power x 1.1"),
    "plastic_power": ("hotroll/fem/quantities.py", '"plastic_power": K * integrate(',
                      '"plastic_power": 1.1 * K * integrate(', "plastic power x 1.1"),
    "friction_power": ("hotroll/fem/quantities.py",
                       '"friction_power": K * form.integrate_friction',
                       '"friction_power": 1.1 * K * form.integrate_friction',
                       "friction power x 1.1"),
    "forward_slip": ("hotroll/fem/quantities.py",
                     '"forward_slip": sec_out["velocity"] / rp.u_roll - 1.0',
                     '"forward_slip": 1.1 * sec_out["velocity"] / rp.u_roll - 1.0',
                     "forward slip from 1.1 x the exit velocity"),
    "flux": ("hotroll/fem/quantities.py", "    q = abs(integrate(",
             "    q = 1.1 * abs(integrate(", "face flux x 1.1"),
    "neutral_interp": ("hotroll/model/contact_figures.py", "else a / (a - b)", "else b / (a - b)",
                       "neutral angle interpolated from the wrong end"),
    "symmetry_stress": ("hotroll/fem/quantities.py",
                        "sym_stress = -K * integrate(sigma_yy",
                        "sym_stress = -1.1 * K * integrate(sigma_yy",
                        "symmetry line's force from sigma_yy x 1.1"),
    "tension_force": ("hotroll/fem/quantities.py",
                      'tension = np.add(force(-form.tension_back * nh, "in")',
                      'tension = np.add(force(-1.1 * form.tension_back * nh, "in")',
                      "back tension's force x 1.1"),
    "mean_pressure": ("hotroll/results/run_summary.py",
                      'summary["mean_pressure"] = (summary["roll_force"] / summary',
                      'summary["mean_pressure"] = (1.1 * summary["roll_force"] / summary',
                      "mean pressure x 1.1"),
    "coulomb_max": ("hotroll/model/friction/coulomb.py",
                    "return smooth_minimum(self.mu * smooth_positive_part(pressure, d / self.mu), k, d)",
                    "return -smooth_minimum(-self.mu * smooth_positive_part(pressure, d / self.mu), -k, d)",
                    "Coulomb: max(mu p, k) instead of min"),
    "nh_exponent": ("hotroll/model/material.py", "(self.eps0**2 + edot2) ** ((m - 1.0) / 2.0)",
                    "(self.eps0**2 + edot2) ** (m / 2.0)",
                    "Norton-Hoff viscosity exponent (m-1)/2 -> m/2"),
    "mill_power": ("hotroll/results/engineering.py", '"mill_power": 2.0 * summary["roll_power"]',
                   '"mill_power": summary["roll_power"]', "mill power of one roll, not two"),
    # --- elastic rolls and the mill (issue 32) ---
    "roll_hitchcock": ("hotroll/model/roll_elastic.py",
                       "return 16.0 * (1.0 - self.nu**2) / (math.pi * self.E)",
                       "return 16.0 * (1.0 - self.nu**2) / (math.pi * 1.1 * self.E)",
                       "Hitchcock's constant with the roll's modulus x 1.1"),
    "roll_disc_modulus": ('hotroll/model/roll_elastic.py',
        'self.radius / self.elasticity.shear_modulus',
        'self.radius / (1.1 * self.elasticity.shear_modulus)',
        "the elastic disc's shear modulus x 1.1"),
    "roll_flattening": ('hotroll/model/roll_elastic.py',
        'return grid, self._at_gap(grid, out["u_r"]), out["hoop"]',
        'return grid, self._at_gap(grid, 1.1 * out["u_r"]), out["hoop"]',
        "the elastic roll's surface displacement x 1.1 in the coupling"),
    "mill_stretch": ("hotroll/results/engineering.py",
                     'stretch = summary["roll_force_total"] / modulus',
                     'stretch = 1.1 * summary["roll_force_total"] / modulus',
                     "the mill stretch F/M x 1.1"),
    "gauge_stretch": ("hotroll/workflows/gauge.py",
                      'g = h - S - s["roll_force_total"] / M',
                      'g = h - S - 1.1 * s["roll_force_total"] / M',
                      "the gap search's stretch x 1.1"),
    "tension_handover": ("hotroll/workflows/schedule.py",
                         "pulls = (tensions[k - 1] if k > 0 else p.back_tension,",
                         "pulls = (1.1 * tensions[k - 1] if k > 0 else p.back_tension,",
                         "a tandem stand's back tension x 1.1 of the one before's front"),
    "pyroll_pass_velocity": ("hotroll/pyroll_inputs.py",
                             "        return float(rp.velocity) / math.cos(phi)",
                             "        return 1.1 * float(rp.velocity) / math.cos(phi)",
                             "PyRolL's pass velocity taken x 1.1 as the roll speed"),
    "pyroll_flat_turned": ("hotroll/pyroll.py",
                           "_missing(nxt, self.in_profile) is None):\n        return 0",
                           "_missing(nxt, self.in_profile) is None):\n        return None",
                           "a flat strip turned by 90 degrees before a flat hotroll pass"),
    "exit_tie": ("hotroll/model/geometry.py",
                 "            if self.tie > 0.0 and self._previous_t is not None:",
                 "            if False:",
                 "a flattened roll's exit always the lowest dip (no tie: the thin strip cycles)"),
    # --- microstructure through the schedule (issue 33) ---
    "ms_pass_strain": ("hotroll/solvers/streamlines.py", "    strain = integral(edot)",
                       "    strain = 1.1 * integral(edot)",
                       "each streamline's pass strain x 1.1"),
    "ms_log_rate": ("hotroll/solvers/streamlines.py",
                    '"log_rate_mean": integral(edot * np.log(edot)) / safe,',
                    '"log_rate_mean": 1.1 * integral(edot * np.log(edot)) / safe,',
                    "each streamline's mean ln(edot) x 1.1"),
    "ms_inverse_T": ('hotroll/solvers/streamlines.py',
        '"inverse_temperature_mean": integral(edot / T) / safe}',
        '"inverse_temperature_mean": 1.1 * integral(edot / T) / safe}',
        "each streamline's mean 1/T x 1.1"),
    "ms_fraction": ("hotroll/model/microstructure/jmak.py",
                    "    return HoldResult(tau, fraction(tau, n), t_half, t_fin, T_half, W)",
                    "    return HoldResult(tau, 1.1 * fraction(tau, n), t_half, t_fin, T_half, W)",
                    "the recrystallised fraction x 1.1"),
    "ms_growth": ("hotroll/model/microstructure/jmak.py",
                  "            W += after * dt * 0.5 * (g0 + g1)",
                  "            W += 1.1 * after * dt * 0.5 * (g0 + g1)",
                  "grain growth's temperature-compensated time x 1.1"),
    "ms_grain": ("hotroll/model/microstructure/softening.py",
                 "    d_out = np.where(done, s.grown(d_rex, res.W_after), mixed)",
                 "    d_out = 1.1 * np.where(done, s.grown(d_rex, res.W_after), mixed)",
                 "the grain size handed on x 1.1"),
    "ms_mix": ("hotroll/model/microstructure/softening.py",
               "    mixed = X ** (4.0 / 3.0) * d_rex + (1.0 - X) ** 2 * ps.grain",
               "    mixed = 1.1 * X ** (4.0 / 3.0) * d_rex + (1.0 - X) ** 2 * ps.grain",
               "the partly recrystallised mix's new grains x 1.1"),
    "ms_retained": ("hotroll/model/microstructure/softening.py",
                    "                    retained_share * (1.0 - X) * ps.strain, done, coldest,",
                    "                    1.1 * retained_share * (1.0 - X) * ps.strain, done, coldest,",
                    "the retained strain x 1.1"),
    "ms_mdrx_grain": ("hotroll/model/microstructure/hodgson_gibbs.py",
                      "    mdrx_grain=PowerTerm(2.6e4, zener=-0.23),",
                      "    mdrx_grain=PowerTerm(1.1 * 2.6e4, zener=-0.23),",
                      "Hodgson and Gibbs' metadynamic grain size x 1.1"),
    "ms_columns": ("hotroll/workflows/microstructure.py",
                   '        out[f"{key}_mean"] = _profile(soft.eta, vals).mean()',
                   '        out[f"{key}_mean"] = 1.1 * _profile(soft.eta, vals).mean()',
                   "schedule.csv's section means x 1.1"),
    "ms_pyroll_grain": ("hotroll/pyroll_microstructure.py",
                        '    return {"grain_size": _mean(soft.eta, soft.grain),',
                        '    return {"grain_size": 1.1 * _mean(soft.eta, soft.grain),',
                        "the grain size a transport hands PyRolL x 1.1"),
    # --- the thermal figures (issue 16) ---
    "exit_T_surface": ("hotroll/solvers/thermal_coupling.py",
                       "surface = float(self.field.values[(ny - 1) * nx1 + self.strip.i_exit])",
                       "surface = 1.1 * float(self.field.values[(ny - 1) * nx1 + self.strip.i_exit])",
                       "exit surface temperature x 1.1"),
    "exit_T_mean": ("hotroll/solvers/thermal_coupling.py",
                    "mean = integrate(sel * u[0] * T, mesh) / flux if flux else math.nan",
                    "mean = 1.001 * integrate(sel * u[0] * T, mesh) / flux if flux else math.nan",
                    "exit mean temperature x 1.001 (1.4 K)"),
    "heat_to_roll": ('hotroll/fem/thermal_field.py',
        'heat_to_roll=self._integrate(chi * bc.contact.flux(T, bc.roll_temperature), self.top)',
        'heat_to_roll=1.1 * self._integrate(chi * bc.contact.flux(T, bc.roll_temperature), self.top)',
        'heat to the roll x 1.1'),
    "plastic_heat": ("hotroll/fem/thermal_field.py",
                     "plastic_heat=bc.taylor_quinney * self._integrate(",
                     "plastic_heat=1.1 * bc.taylor_quinney * self._integrate(",
                     "plastic heat x 1.1"),
    "strip_flux": ("hotroll/solvers/thermal_coupling.py",
                   "strip.set_stream_function(flux, total=float(flux[-1, 0]))",
                   "strip.set_stream_function(flux, total=1.1 * float(flux[-1, 0]))",
                   "the strip mesh's flux x 1.1"),
    "element_means": ("hotroll/solvers/thermal_coupling.py",
                      "        if self.flow is None:\n            return plain\n",
                      "        if True:\n            return plain\n",
                      "plain mean T per element instead of the mean consistency"),
    "rate_offset": ("hotroll/solvers/thermal_coupling.py",
                    "= np.asarray(self._rate_offset_at(T), dtype=float)",
                    "= 1.1 * np.asarray(self._rate_offset_at(T), dtype=float)",
                    "the rate exponent's temperature offset x 1.1"),
    "friction_tangent": ("hotroll/model/friction/coulomb.py",
                         "return m_a * mu * p_a, m_a",
                         "return 1.1 * m_a * mu * p_a, m_a",
                         "Newton's Coulomb tangent: d/dp x 1.1 (the results stay: only the "
                         "Jacobian is wrong)"),
    # --- schedules and PyRolL (issue 17) ---
    "inlet_T_profile": ("hotroll/fem/thermal_field.py",
                        "return np.asarray(profile(y_in / np.max(y_in)), dtype=float)",
                        "return 1.1 * np.asarray(profile(y_in / np.max(y_in)), dtype=float)",
                        "the entry temperature profile x 1.1 at the inlet"),
    "inlet_strain_profile": ("hotroll/fem/strain.py",
                             "self._inlet[fixed] = profile(y / np.max(y))",
                             "self._inlet[fixed] = 1.1 * profile(y / np.max(y))",
                             "the entry strain profile x 1.1 at the inlet"),
    "exit_strain_profile": ('hotroll/solvers/record_fields.py',
        'return [np.asarray(f(pts), dtype=float).reshape(-1) for f in fields]',
        'return [1.1 * np.asarray(f(pts), dtype=float).reshape(-1) for f in fields]',
        'the exit strain profile x 1.1'),
    "exit_T_profile": ("hotroll/solvers/record_fields.py",
                       "temperature = thermal.field.values.reshape(strip.shape)[:, -1].copy()",
                       "temperature = 1.1 * thermal.field.values.reshape(strip.shape)[:, -1]",
                       "the exit temperature profile x 1.1"),
    "transport_duration": ("hotroll/workflows/schedule.py",
                           "duration = tr.duration if tr.duration is not None",
                           "duration = 1.1 * tr.duration if tr.duration is not None",
                           "the transport's duration x 1.1"),
    "strain_retained": ("hotroll/workflows/schedule.py",
                        "state.strain.scaled(tr.strain_retained))",
                        "state.strain.scaled(1.1 * tr.strain_retained))",
                        "the retained strain x 1.1"),
    "mass_flow": ("hotroll/workflows/schedule.py",
                  'miss = summary["mass_flux_in"] / flux - 1.0',
                  'miss = 1.1 * summary["mass_flux_in"] / flux - 1.0',
                  "the tandem's flux mismatch from 1.1 x the stand's flux"),
    "pyroll_force": ("hotroll/pyroll.py",
                     'return s["roll_force"] * self.in_profile.width',
                     'return 1.1 * s["roll_force"] * self.in_profile.width',
                     "the plugin's roll force x 1.1"),
    "pyroll_torque": ("hotroll/pyroll.py",
                      'return solve(rp)["roll_torque"] * rp.in_profile.width',
                      'return 1.1 * solve(rp)["roll_torque"] * rp.in_profile.width',
                      "the plugin's roll torque x 1.1"),
    "pyroll_transport": ("hotroll/pyroll_out_profile.py", "    return res.mean\n",
                         "    return 1.1 * res.mean\n",
                         "the plugin's transport temperature x 1.1"),
    # --- the PyRolL plugin's out profiles and flow stress (issue 51 item 5) ---
    "pyroll_sequence_copy": ("hotroll/pyroll_out_profile.py",
                             "    PassSequence.post_processors.append(_sequence_values)",
                             "    pass",
                             "a sequence's out profile not given its last unit's values"),
    "pyroll_exit_T": ("hotroll/pyroll_out_profile.py",
                      '        return _P.solve(rp)["outlet_temperature_mean"]',
                      '        return 1.1 * _P.solve(rp)["outlet_temperature_mean"]',
                      "a hotroll pass's out temperature x 1.1"),
    "pyroll_constant": ("hotroll/pyroll_flow_stress.py",
                        "    sigma = given_constant(ip)\n    if sigma is not None:\n        if not",
                        "    sigma = None\n    if sigma is not None:\n        if not",
                        "the profile's constant flow_stress ignored (the grade's law rolled)"),
    "pyroll_fallback_info": ("hotroll/pyroll.py",
                             '            _LOG.warning("hotroll.pyroll: flat pass %r left',
                             '            _LOG.info("hotroll.pyroll: flat pass %r left',
                             "a pass left to PyRolL logged at INFO"),
    "pyroll_not_a_strip": ("hotroll/pyroll_case.py",
                           "    MIN_RECTANGULARITY: float = 0.9",
                           "    MIN_RECTANGULARITY: float = 0.0",
                           "a bar (hexagon, diamond, round) rolled by hotroll as a flat strip"),
    "pyroll_thermal_plugin": ("hotroll/pyroll_out_profile.py",
                              "not _P.Config.TRANSPORT_COOLING or other_transport_model():",
                              "not _P.Config.TRANSPORT_COOLING:",
                              "hotroll cools a transport another plugin's model cools"),
    # --- issue 51: input units, plausibility, threads where a core is free ---
    "fit_range_bound": ("hotroll/model/grades.py",
                        "validity_celsius=((0.03, 1.50), (0.01, 500.0), (250.0, 550.0)),",
                        "validity_celsius=((0.03, 1.50), (0.01, 500.0), (250.0, 550.0 * 1.1)),",
                        "Al99.5's upper fit temperature x 1.1"),
    "unit_slip_speed": ("hotroll/config/plausibility.py", "MAX_SURFACE_SPEED = 60.0",
                        "MAX_SURFACE_SPEED = 66.0", "the refused surface speed's bound x 1.1"),
    "unit_offset": ("hotroll/config/units.py", '"K": ("degC", 1.0, 273.15)',
                    '"K": ("degC", 1.0, 273.15 * 1.1)', "the engineer's degC shown off by 10 %"),
    "threads_busy": ("hotroll/fem/reproducible.py",
                     "    return max(1, min(n, cores() - others_running()))",
                     "    return n", "a run takes the cores another process wants"),
    "fit": ("hotroll/model/flow_stress_fit.py",
            'params["A"] = float(np.exp(params["A"]))',
            'params["A"] = 1.1 * float(np.exp(params["A"]))',
            "the fitted Hensel-Spittel A x 1.1"),
    # --- studies and the Python API (issue 18) ---
    "study_table": ("hotroll/workflows/study.py",
                    "            row.update(_scalars(summary))",
                    "            row.update(_scalars(summary))\n"
                    "            row[\"roll_force\"] = 1.1 * row[\"roll_force\"]",
                    "the study table's roll force x 1.1"),
    "api_contact": ("hotroll/results/run_dir.py",
                    "out[name_j] = (np.asarray(numbers, dtype=float) if None not in numbers",
                    "out[name_j] = (1.1 * np.asarray(numbers, dtype=float) if None not in numbers",
                    "the run directory's CSV columns x 1.1 (the API, figures, compare read them)"),
    "api_summary": ("hotroll/api.py", "            return summary[name]",
                    "            return 1.1 * summary[name] if isinstance(summary[name], float) "
                    "else summary[name]",
                    "the API's summary attributes x 1.1"),
    "study_plot": ("hotroll/results/study_plot.py",
                   "pts = sorted((_num(r.get(x)), _num(r.get(key))) for r in grp)",
                   "pts = sorted((_num(r.get(x)), 1.1 * _num(r.get(key))) for r in grp)",
                   "study.png's curves x 1.1"),
    "study_range": ("hotroll/config/study_schema.py",
                    "v = np.linspace(self.start, self.stop, self.num)",
                    "v = 1.1 * np.linspace(self.start, self.stop, self.num)",
                    "a [vary] range's values x 1.1"),
    "study_schedule_row": ("hotroll/workflows/study.py",
                           '"max_roll_force": max(r["roll_force"] for r in rows),',
                           '"max_roll_force": 1.1 * max(r["roll_force"] for r in rows),',
                           "a schedule study's largest roll force x 1.1"),
    "study_pass_columns": ("hotroll/workflows/study.py",
                           'return {f"{r[\'name\']}.{k}": r.get(k) for r in rows for k in PASS_KEYS',
                           'return {f"{r[\'name\']}.{k}": 1.1 * r.get(k) for r in rows for k in PASS_KEYS',
                           "a schedule study's per-pass columns x 1.1"),
    "study_outlet_T": ("hotroll/workflows/study.py",
                       '"outlet_temperature_mean": rows[-1].get("outlet_temperature_mean"),',
                       '"outlet_temperature_mean": 1.1 * rows[-1].get("outlet_temperature_mean"),',
                       "a schedule study's exit temperature after the last gap x 1.1"),
    "study_total_power": ("hotroll/workflows/study.py",
                          '"total_roll_power": sum(r["roll_power"] for r in rows),',
                          '"total_roll_power": 1.1 * sum(r["roll_power"] for r in rows),',
                          "a schedule study's total roll power x 1.1"),
    "estimate_refusal": ("hotroll/workflows/estimate.py",
                         "if not est.fits and not case.solver.force:",
                         "if False and not est.fits and not case.solver.force:",
                         "a mesh over the memory limit no longer refused"),
    "transient_source": ("hotroll/fem/thermal_field.py",
                         "f += bc.taylor_quinney * CF(heat_density) * w * dvol",
                         "f += 1.1 * bc.taylor_quinney * CF(heat_density) * w * dvol",
                         "the Lagrangian step's plastic heat x 1.1"),
    # --- issue 31: the heat-transfer laws, the one Newton, the typed summary ---
    "surface_law": ("hotroll/model/heat_transfer/convection_radiation.py",
                    "return self.htc * (T - T_env) + self.emissivity",
                    "return 1.1 * self.htc * (T - T_env) + self.emissivity",
                    "the free surfaces' convection x 1.1"),
    "contact_law": ("hotroll/model/heat_transfer/constant_conductance.py",
                    "        return self.htc * (T - T_env)\n",
                    "        return 1.1 * self.htc * (T - T_env)\n",
                    "the contact's heat flux x 1.1"),
    "heat_newton_scale": ("hotroll/fem/thermal_field.py",
                          "return max(float(np.max(np.abs(self.field.values))), 1e-300)",
                          "return 1e4 * max(float(np.max(np.abs(self.field.values))), 1e-300)",
                          "the heat Newton stops 1e4 x too early"),
    "summary_unit": ("hotroll/results/summary_keys.py",
                     'roll_torque: float = _f("N m/m"',
                     'roll_torque: float = _f("N m"',
                     "the roll torque's unit in summary.json"),
    # --- issue 34 session 8: the point search, the P2 values at points, the numpy heat terms ---
    "point_local": ("hotroll/fem/point_search.py",
                    'out["x"], out["y"] = local[:, 0], local[:, 1]',
                    'out["x"], out["y"] = local[:, 1], local[:, 0]',
                    "the points' local coordinates swapped"),
    "p2_edge_weight": ("hotroll/fem/spaces.py",
                       "4.0 * np.stack([lam[:, 0] * lam[:, 1]",
                       "4.4 * np.stack([lam[:, 0] * lam[:, 1]",
                       "the P2 edge weights at points x 1.1"),
    "heat_p1_jacobian": ("hotroll/fem/heat_p1.py",
                         "- (rc / 3.0) * b[:, :, None]",
                         "- (rc / 3.3) * b[:, :, None]",
                         "the numpy heat Jacobian's advection x 1/1.1"),
    "heat_p1_residual": ("hotroll/fem/heat_p1.py",
                         "- rc * (Te.mean(axis=1) - self.reference)",
                         "- 1.1 * rc * (Te.mean(axis=1) - self.reference)",
                         "the numpy heat residual's advection x 1.1"),
    "column_disp": ("hotroll/solvers/thermal_coupling.py",
                    "pos = self._col_ref + self._col_p2(self._disp.vec.FV().NumPy())",
                    "pos = self._col_ref + 1.1 * self._col_p2(self._disp.vec.FV().NumPy())",
                    "the strip columns' displacement x 1.1"),
    "krylov_direct": ("hotroll/fem/krylov.py",
                      "return bool(np.linalg.norm(res) <= rtol * np.linalg.norm(rhs))",
                      "return True",
                      "the factors alone accepted without the residual check"),
    "linear_rtol_loose": ("hotroll/fem/forms.py",
                          "    linear_rtol: float = 1e-2",
                          "    linear_rtol: float = 0.5",
                          "the flow's largest forcing term 0.5 (not 1e-2)"),
    "gmres_unweighted": ("hotroll/fem/krylov.py",
                         "        w2 = w * w\n",
                         "        w2 = (w > 0.0) * 1.0\n",
                         "GMRES's inner product unweighted (the plain 2-norm of the free rows)"),
    "strain_kept_forms": ("hotroll/fem/strain.py",
                          "inv.Update()",
                          "pass",
                          "the strain's kept factorisation not refactorised"),
    # --- issue 51 follow-ups: the command line tells the summary's story ---
    "cli_neutral_row": ("hotroll/cli/run_display.py",
                        '"h_contact", "neutral", "roll_force",',
                        '"h_contact", "neutral_angle", "roll_force",',
                        "the run's table prints the neutral angle instead of the neutral story"),
    "cli_progress_words": ("hotroll/cli/run_display.py", '        if keys == ["message"]:',
                           "        if False:",
                           "a steady solve's progress printed as message=..."),
    "cli_progress_neutral": ("hotroll/cli/run_display.py", '"roll_force", "forward_slip",\n',
                             '"roll_force", "neutral_angle", "forward_slip",\n',
                             "a time step's progress prints its own neutral angle"),
    "cli_warnings": ("hotroll/cli/common.py", "        err_console.print(line, soft_wrap=True)",
                     "        pass", "the runs' warnings not printed"),
    "cli_warnings_stdout": ("hotroll/cli/common.py",
                            "        err_console.print(line, soft_wrap=True)",
                            "        console.print(line, soft_wrap=True)",
                            "the runs' warnings printed on stdout (into a csv or json table)"),
    "cli_warnings_once": ("hotroll/cli/common.py", "    for text, runs in where.items():",
                          "    for text, runs in [(t, [n]) for n, ws in found for t in ws]:",
                          "each run's warnings printed, the same text again for every run"),
    "schedule_warnings": ("hotroll/cli/runs.py", "    _pass_warnings(out, rows)\n",
                          "    _pass_warnings(out, rows[:0])\n",
                          "a schedule's passes' warnings not printed"),
    "validate_warnings": ("hotroll/cli/validate.py", "    for text in case.warnings():",
                          "    for text in case.warnings()[:0]:",
                          "validate of a case lists no warning"),
    # --- issue 52: the full-thickness strip's per-roll figures ---
    "roll_force_per_roll": ("hotroll/solvers/gap_measure.py",
                            'f"{name}_roll_force": -side * f_strip[1],',
                            'f"{name}_roll_force": -side * (1.1 if side > 0 else 1.0) * f_strip[1],',
                            "the upper roll's force x 1.1 (full strip)"),
    "roll_torque_per_roll": ("hotroll/solvers/gap_measure.py",
                             'f"{name}_roll_torque": K * form.integrate_friction(',
                             'f"{name}_roll_torque": (1.1 if side < 0 else 1.0) * K * form.integrate_friction(',
                             "the lower roll's torque x 1.1 (full strip)"),
    "curvature": ("hotroll/solvers/gap_measure.py",
                  '"exit_curvature": float(omega) / speed,',
                  '"exit_curvature": 1.1 * float(omega) / speed,',
                  "the exit curvature x 1.1 (full strip)"),
    "lower_roll_turns": ("hotroll/fem/gap_form.py",
                         "t = CF((-side * (y - cy) / r, side * (x - cx) / r))",
                         "t = CF((-(y - cy) / r, (x - cx) / r))",
                         "the lower roll turning the wrong way (its tangent the upper's formula)"),
}


def plant(name: str, workdir: Path) -> Path:
    """A copy of the package and tests with the bug ``name`` in it."""
    path, old, new, _ = BUGS[name]
    copy = workdir / name
    shutil.rmtree(copy, ignore_errors=True)
    # the tests read docs (the tutorial, the reference page), scripts (the summary
    # comparison) and the README: a copy without them fails for a missing file, not the bug
    for part in ("hotroll", "tests", "docs", "scripts"):
        shutil.copytree(ROOT / part, copy / part, ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", copy / "pyproject.toml")
    shutil.copy(ROOT / "README.md", copy / "README.md")      # a test reads its first case
    target = copy / path
    text = target.read_text()
    if text.count(old) != 1:
        raise SystemExit(f"{name}: the text to change occurs {text.count(old)} times in {path}")
    target.write_text(text.replace(old, new))
    return copy


def run_suite(copy: Path, tests: list[str] | None = None) -> tuple[str, float]:
    t0 = time.perf_counter()
    env = dict(os.environ, PYTHONPATH=str(copy), PYTHONDONTWRITEBYTECODE="1")
    proc = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-x", "-n", "2", "--dist", "loadfile",
         "-p", "no:cacheprovider", "-o", "addopts=-m 'not slow'", *(tests or ["tests"])],
        cwd=copy, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    failed = re.findall(r"^(?:FAILED|ERROR) (\S+)", proc.stdout, re.M)
    if proc.returncode == 0:
        return "SURVIVED", wall
    return (failed[0] if failed else f"exit {proc.returncode}"), wall


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default="", help="comma-separated bug names")
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--tests", default="", help="comma-separated test files (default: all); "
                    "a bug a subset catches, the suite catches")
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "planted_bugs.md")
    args = ap.parse_args()
    names = [n for n in (args.only.split(",") if args.only else BUGS) if BUGS.get(n)]
    if args.list:
        for n in names:
            print(f"{n:22s} {BUGS[n][0]}: {BUGS[n][3]}")
        return
    rows = []
    with tempfile.TemporaryDirectory(prefix="planted-") as tmp:
        for n in names:
            copy = plant(n, Path(tmp))
            caught, wall = run_suite(copy, [t for t in args.tests.split(",") if t] or None)
            rows.append((n, BUGS[n][0], BUGS[n][3], caught, wall))
            print(f"{n:22s} {caught}  ({wall:.0f} s)", flush=True)
            shutil.rmtree(copy, ignore_errors=True)
    lines = [f"# Planted bugs ({date.today()}, `python scripts/planted_bugs.py`)", "",
             "| bug | file | change | first failing test | s |", "|---|---|---|---|---|"]
    lines += [f"| {n} | `{f}` | {d} | {c if c == 'SURVIVED' else '`' + c + '`'} | {w:.0f} |"
              for n, f, d, c, w in rows]
    caught = sum(r[3] != "SURVIVED" for r in rows)
    lines += ["", f"{caught} of {len(rows)} caught."]
    if not args.only:
        tmp_out = args.out.with_suffix(".tmp")
        tmp_out.write_text("\n".join(lines) + "\n")
        os.replace(tmp_out, args.out)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
