"""The 3D pass with spread as data (issue 53): what ``solvers/spread_3d.py`` ends in and the
results layer reads (numpy only, as ``model/solution.py``). SI units; forces, torques and
powers of one roll over the strip's whole width; positions in the solver's frame (the roll
axis at x = 0; ``Solution.frame_shift`` moves them)."""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np


@dataclass(frozen=True)
class SpreadResult:
    """The 3D quarter strip's pass (``solvers/spread_record.spread_record``):

    - ``stock_width``, ``exit_width`` (m): the strip's width at entry and its mean at exit
      (over the exit thickness), ``spread`` their difference;
    - ``exit_section``: ``y`` (m, from the mid-plane) and ``half_width`` (m) at the outlet;
    - ``exit_thickness``: ``z`` (m, from mid-width to the edge, one per width level) and the
      strip's full ``thickness`` (m) at the outlet there; with the strain carried through the
      3D flow also its ``strain`` (-, the mean over the thickness there);
    - ``width_along``: ``x`` (m) and the half width there at mid-thickness (``centre``) and on
      the strip's surface (``surface``), m;
    - ``contact_map``: the contact pressure (Pa) over the arc, ``pressure`` (width levels x
      arc vertices, from entry to exit: the multiplier's nodal forces over their areas, its
      own nodal values in ``pressure_multiplier``), at ``x`` (m), ``angle`` (rad from the
      roll's vertical centre line) and ``z`` (m, across the width), each of the same shape
      (the contact's start differs from level to level);
    - ``roll_force``, ``roll_torque`` (N, N m): one roll over the whole width; ``roll_power``
      (W) torque times the roll's angular velocity;
    - ``flux_in``, ``flux_out``, ``flux_edge`` (m^3/s of the whole strip) through the entry,
      the exit and the lateral faces;
    - ``forward_slip`` (-): the whole strip's mean exit speed (the outlet's flux over its
      area) over the roll's surface speed, minus 1;
    - ``power_balance_error`` (-): |roll + tension power - plastic - friction power| / roll
      power of the 3D pass (torque x omega: an identity of any converged solution that checks
      the torque);
    - ``midplane``: the mid-width plane's deviations from the plane-strain pass (-: pressure
      largest and RMS over the 2D pressure's, the same of the arc's contact pressure, velocity
      over the roll speed);
    - ``settled``, ``rounds``, ``newton_iterations``, ``dofs``, ``layers`` (width layers of the
      quarter), ``edge_layer`` (m), ``wall_time`` (s); ``zone_cut`` (m): where an edge zone's
      graded layers begin (0: the whole half width graded; inside it one layer in
      generalized plane strain);
      ``failure``: why its solve stopped (a linear solve failed), or "";
    - ``exit_temperature_offset``: with an entry temperature across the width, its difference
      from mid-width's at the outlet (K; ``eta``, ``zeta``, ``values`` one row per eta), or
      None;
    - ``write_vtk(path, shift)``: the 3D fields for ParaView, positions moved by ``shift`` (m).
    """

    stock_width: float
    exit_width: float
    exit_section: Mapping[str, np.ndarray]
    exit_thickness: Mapping[str, np.ndarray]
    width_along: Mapping[str, np.ndarray]
    contact_map: Mapping[str, np.ndarray]
    roll_force: float
    roll_torque: float
    roll_power: float
    flux_in: float
    flux_out: float
    flux_edge: float
    midplane: Mapping[str, float]
    power_balance_error: float
    settled: bool
    rounds: int
    newton_iterations: int
    dofs: int
    layers: int
    edge_layer: float
    wall_time: float
    zone_cut: float = 0.0
    failure: str = ""
    forward_slip: float = float("nan")
    exit_temperature_offset: Mapping[str, list] | None = None
    write_vtk: Callable[[Path, float], Path] | None = field(default=None, repr=False)

    @property
    def spread(self) -> float:
        """Exit width minus stock width (m)."""
        return self.exit_width - self.stock_width

    @property
    def edge_bulge(self) -> float:
        """How far the exit edge bulges: its largest half width over the thickness minus its
        smallest (m, one edge; the barrelling)."""
        half = np.asarray(self.exit_section["half_width"], dtype=float)
        return float(half.max() - half.min())

    @property
    def edge_drop(self) -> float:
        """The exit thickness at mid-width minus at the edge (m)."""
        t = np.asarray(self.exit_thickness["thickness"], dtype=float)
        return float(t[0] - t[-1])

    @property
    def mass_flux_error(self) -> float:
        """(flux out + flux through the lateral faces - flux in) / flux in (-)."""
        return (self.flux_out + self.flux_edge - self.flux_in) / self.flux_in
