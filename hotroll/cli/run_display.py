"""How one run shows on the terminal: while it solves, a throttled progress line with the
time left on a time-stepped run (``Progress``, ``run_end_time``); after it, its summary table in
the units a person reads (``summary_table``). The commands that run cases are
``cli/passes.py``'s."""

import math
import time
from typing import Any

from rich.text import Text

from hotroll.cli.common import Column, ResultTable, Shown, console, eta_text
from hotroll.config.case import Case
from hotroll.results.engineering import display
from hotroll.results.gap_summary import MEAN_OF_ROLLS
from hotroll.results.units import UNITS
from hotroll.solvers.settling import default_end_time

#: ``neutral``: the neutral story in words (``results/neutral.py``: the point's angle in degrees
#: and radians, or none and the sticking zone), the one the figures and the page tell; not its
#: parts (``neutral_point``, ``neutral_angle``, ``neutral_angle_reason``, ``sticking_zone``)
SUMMARY_KEYS = ["status", "free_surface", "h_contact", "neutral", "roll_force", "roll_torque",
                "roll_power", "forward_slip", "mean_pressure", "mean_flow_stress",
                "mean_strain_rate", "exit_strain", "roll_force_total", "roll_torque_total",
                "mill_power", "a_f", "balance_error", "converged", "steps",
                "nonlinear_iterations", "wall_time_s"]
#: A flattening roll, a mill modulus, a roll gap: shown where the summary has them.
MILL_KEYS = ["contact_length", "roll_model", "roll_equivalent_radius", "roll_flattening",
             "roll_updates", "mill_stretch", "gap_setting", "roll_gap", "gauge_thickness",
             "gauge_solves"]
#: An asymmetric pass (two rolls that differ): the strip's figures, then each roll's
#: (``rolls``; the one-roll keys above are the two rolls' means: results/gap_summary.py).
GAP_KEYS = ["speed_ratio", "cross_shear_length", "exit_curvature", "exit_angle",
            "entry_guide_force_y"]
ROLL_KEYS = ["surface_speed", "roll_force", "roll_torque", "roll_power", "forward_slip",
             "neutral_angle", "contact_length", "min_contact_pressure"]
#: With [spread]: the 3D pass's width figures (its whole-width force and torque replace plane
#: strain x width in roll_force_total, roll_torque_total).
SPREAD_KEYS = ["exit_width", "spread", "spread_hill", "spread_sparling", "spread_wusatowski",
               "edge_bulge", "edge_drop", "plane_strain_roll_force_total", "spread_forward_slip",
               "spread_mass_flux_error",
               "spread_power_balance_error",
               "spread_settled", "spread_dofs", "spread_wall_time"]
#: With [thermal]: shown after the mechanics' figures (units from summary.json's ``units``).
THERMAL_KEYS = ["exit_temperature_mean", "exit_temperature_surface", "plastic_heat",
                "friction_heat_to_strip", "heat_to_roll", "heat_to_air", "heat_balance_error"]

#: A time step's figures in its progress line; not its neutral angle (the slip's sign split of
#: one step, noise on a sticking arc: the run's neutral story is the summary's ``neutral``). A
#: report with only a ``message`` (the steady solver's Newton solves and coupling updates) is
#: printed as its words alone.
PROGRESS_KEYS = ["step", "time", "m", "a_f", "iterations", "roll_force", "forward_slip",
                 "message"]


class Progress:
    """Throttled one-line progress report from the runner's progress dicts; on a time-stepped
    run (``end_time``: the simulated time it stops at, s) with the time left to that end,
    estimated from the measured rate of the steps so far."""

    def __init__(self, every: float = 2.0, end_time: float | None = None, clock=None):
        self.every, self.last, self.end_time = every, -math.inf, end_time
        self.clock = clock or time.monotonic
        self.start: tuple[float, float] | None = None      # (wall s, simulated s) of a step

    def __call__(self, info: dict) -> None:
        now = self.clock()
        eta = self._eta(now, info.get("time"))
        if now - self.last < self.every and "message" not in info:
            return
        self.last = now
        keys = [k for k in PROGRESS_KEYS if k in info] or list(info)
        if keys == ["message"]:
            parts = [str(info["message"])]
        else:
            parts = [f"{k}={_fmt(info[k])}"
                     + (f" {UNITS[k]}" if k in UNITS and UNITS[k] != "-" else "")
                     for k in keys if isinstance(info[k], (int, float, str, bool))]
        if eta is not None:
            parts.append(eta)
        console.print(Text("  " + "  ".join(parts), style="dim"), soft_wrap=True)

    def _eta(self, now: float, t: Any) -> str | None:
        """The time left to ``end_time`` at the rate measured since the first step seen
        (a resumed run's first step is its own start; a new run restarts the clock)."""
        if self.end_time is None or not isinstance(t, (int, float)) or not math.isfinite(t):
            return None
        if self.start is None or t <= self.start[1]:
            self.start = (now, t)
            return None
        rate = (now - self.start[0]) / (t - self.start[1])        # wall s per simulated s
        return eta_text(rate * max(self.end_time - t, 0.0),
                        f"the steps so far, to end_time {self.end_time:.4g} s; a steady state "
                        f"ends the run sooner")


def run_end_time(case: Case) -> float | None:
    """The simulated time a time-stepped run stops at (s): the case's, else the automatic
    one (``solvers/settling.default_end_time``), capped by its step limit; None when steady."""
    if case.solver.method != "transient":
        return None
    end = case.solver.end_time or default_end_time(case.pass_.roll_pass())
    return min(end, case.solver.max_steps * case.dt)


def _fmt(v: Any) -> str:
    if isinstance(v, bool) or not isinstance(v, (int, float, list, tuple)):
        return str(v)
    if isinstance(v, (list, tuple)):
        return ", ".join(_fmt(x) for x in v)
    return f"{v:.6g}" if isinstance(v, float) else str(v)


def summary_table(case: Case, summary: dict) -> ResultTable:
    """The run's figures: shown in the units a person reads (MN/m, kN m/m, ...) to 4-6
    digits, written unrounded in the SI unit of summary.json (csv, json)."""
    table = ResultTable(f"{case.name}: summary", [Column("quantity", left=True),
                                                  Column("value"), Column("unit", left=True)])
    thermal = THERMAL_KEYS if summary.get("thermal") else []
    # absent keys are not shown; the contact length only beside a flattened roll's figures
    mill = [k for k in MILL_KEYS if k != "contact_length" or summary.get("roll_model")]
    rolls = summary.get("rolls") or []
    gap = GAP_KEYS if rolls else []
    spread = SPREAD_KEYS if summary.get("spread") is not None else []
    keys = SUMMARY_KEYS[:-4] + mill + gap + spread + thermal + SUMMARY_KEYS[-4:]  # before the run's own
    units = summary.get("units", {})

    def row(name: str, key: str, value, si: str | None) -> None:
        text, unit = display(key, value, si)
        si = UNITS.get(key, si or "")
        table.rows.append([name, Shown(text if text is not None else _fmt(value), value),
                           Shown(unit or si, si)])

    for key in keys:
        value = summary.get(key)
        if value is not None:
            row(f"{key} (mean of the two rolls)" if rolls and key in ("roll_force", *MEAN_OF_ROLLS) else key,
                key, value, units.get(key))
        if key == "entry_guide_force_y":        # each roll's figures after the strip's
            for entry in rolls:
                for k in ROLL_KEYS:
                    if entry.get(k) is not None:
                        row(f"{entry['side']} roll: {k}", k, entry[k],
                            units.get(f"rolls.{k}"))
    return table

