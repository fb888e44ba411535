"""The solved pass as data (issue 52, stage 1): what a solver ends in, and all the results layer
reads (``results/run_summary.py``). Numpy only: the solvers fill it from their FE objects
(``solvers/record.py``), ``results/`` reads it and imports neither ``fem/`` nor ``solvers/``
(the ``results-no-fe`` contract, pyproject.toml). The one FE piece is the ParaView writer, a
callable the solver attaches (``Solution.write_vtk``) and the results call without knowing
what it holds.

Positions are in the solver's frame (the steady solver's: the roll axis at x = 0);
``Solution.frame_shift`` moves them to the case's. Every stress, force and power is in SI units
(the reference law's K applied), as the summary gives them.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from hotroll.model.geometry import RollPass
from hotroll.model.spread_result import SpreadResult


@dataclass(frozen=True)
class PassData:
    """The pass as solved: the contact mesh size ``h`` (m), the reference law's consistency
    ``K`` (Pa s^m) and rate exponent ``m`` (-), the entry strain (-) and the entry (or uniform)
    temperature (K)."""

    h: float
    K: float
    m: float
    entry_strain: float = 0.0
    temperature: float = 1373.15


@dataclass(frozen=True)
class RollContact:
    """One roll's contact with the strip (one today: the upper roll of the half model).

    ``rp``: the roll's arc in the solver's frame (its speed, radius and, for a flattening
    roll, its surface). ``profile``: the contact nodes from entry to exit, columns ``x``, ``y``
    (m), ``angle`` (rad from the roll's vertical centre line), ``v_slip`` (m/s), ``normal_stress``,
    ``shear_stress`` (Pa), ``vertex`` (1 at a mesh vertex, 0 at an edge midpoint) and, where the
    run has them, ``normal_stress_multiplier``, ``shear_flow_stress`` (Pa), ``temperature`` (K),
    ``heat_flux_to_roll`` (W/m^2). ``method``: the ``[contact] method`` (``"penalty"`` or
    ``"multiplier"``); ``exact``: a multiplier carries the pressure (no exit correction).
    ``unilateral``: the contact's end is a shape unknown; ``end_x`` (m) that end and
    ``end_bounds`` (m, m) its allowed range (the steady solver's unilateral contact, else None).
    ``pressure_last_update`` (Pa): what the pressure moved in the last Newton step (exact
    contact, steady; else None). A flattening roll (``flattening``): its updates, its last
    update's largest move (m) and its shape error (-: max |w - w(p, q)| over max |w(p, q)|
    on the contact); None for a rigid roll. ``overlap`` (m): how deep the free surface after
    the contact's end lies inside the roll at its deepest (0 outside it; the steady solver's,
    else None); ``wraps``: the strip curls onto the roll and its contact goes on past the gap
    (a rigid-plastic strip, the full strip between two rolls)."""

    rp: RollPass
    profile: Mapping[str, np.ndarray]
    method: str
    exact: bool
    unilateral: bool = False
    end_x: float | None = None
    end_bounds: tuple[float, float] | None = None
    pressure_last_update: float | None = None
    flattening: bool = False
    roll_updates: int | None = None
    roll_last_move: float | None = None
    roll_shape_error: float | None = None
    overlap: float | None = None
    wraps: bool = False


#: ``VertexFields``'s arrays in the order fields.npz has them (then the rolls' edges and arcs)
FIELD_NAMES = ("points", "triangles", "v", "pressure", "edot", "strain", "sigma_ef",
               "temperature", "flow_temperature")


@dataclass(frozen=True)
class VertexFields:
    """The fields at the mechanics mesh's vertices, SI: the deformed vertices ``points``
    (nv x 2, m), ``triangles`` (nt x 3 vertex numbers), the velocity ``v`` (nv x 2, m/s), the
    ``pressure`` (Pa), the equivalent strain rate ``edot`` (1/s), the ``strain`` (-), the flow
    stress ``sigma_ef`` (Pa) at that strain, rate and flow temperature, the ``temperature`` (K)
    and the ``flow_temperature`` (K, the one the flow stress takes); ``contact_edges``: per
    roll, its contact edges as pairs of vertex numbers."""

    points: np.ndarray
    triangles: np.ndarray
    v: np.ndarray
    pressure: np.ndarray
    edot: np.ndarray
    strain: np.ndarray
    sigma_ef: np.ndarray
    temperature: np.ndarray
    flow_temperature: np.ndarray
    contact_edges: tuple[np.ndarray, ...] = ()

    def arrays(self) -> dict[str, np.ndarray]:
        """The arrays of ``FIELD_NAMES``, in that order."""
        return {k: getattr(self, k) for k in FIELD_NAMES}


@dataclass
class Solution:
    """What a solver ends in. ``run`` returns its state: the status, one history row per step
    (transient) or per Newton solve and coupling update (steady), the step and time reached;
    ``solution_record()`` adds what the results read (the ``results-no-fe`` seam):

    - ``time_stepping``: the report's scheme (True) or the direct steady solver;
      ``window``: the summary's means are over the last ``window`` history rows;
      ``frame_shift`` (m): the solver's frame to the case's (added to every x written);
    - ``pass_data``: ``PassData``; ``contacts``: one ``RollContact`` per roll (a tuple: one
      today, two in a full-thickness model); ``tops``: per free top, its nodes sorted by x,
      columns ``x``, ``y`` (m), ``v1``, ``v2`` (m/s) and where the run has it ``temperature`` (K);
    - ``fields``: ``VertexFields``; ``thermal_strip``: the temperature's own strip mesh
      (``points`` m, ``triangles``, ``temperature`` K) or None;
    - ``quantities``: figures integrated over the mesh, ``mean_flow_stress`` (Pa) and
      ``mean_strain_rate`` (1/s) over the deformation zone;
    - ``exit_profile``: the outlet's state through the half thickness (eta, temperature K,
      strain, pass_strain, log_rate_mean, inverse_temperature_mean; ``solvers/record.py``) or
      None; ``exit_strain``: the exit strip's mean strain (-), None without a strain field;
    - ``solve_stats``: the solve's counts, ``newton_solves``, ``coupling_updates``,
      ``fixed_point_settled``, ``surface_residual_h`` (steady) or ``dt`` (s, transient);
      ``dofs``: the flow's unknowns; ``nonlinear``: ``"newton"`` or ``"picard"``;
    - ``write_vtk(path, shift)``: writes the ParaView file(s), positions moved by ``shift``
      (m); None where no FE objects are at hand;
    - ``spread``: the 3D pass across the width (``[spread]``, ``model/spread_result.py``) or
      None.
    """

    step: int = 0
    time: float = 0.0
    history: list = field(default_factory=list)
    status: str = "running"   # running | steady | unsettled | end_time | max_steps | wall_time | failed
    failure: str = ""         # why a failed run stopped
    time_stepping: bool = False
    window: int = 1
    frame_shift: float = 0.0
    pass_data: PassData | None = None
    contacts: tuple[RollContact, ...] = ()
    tops: tuple[Mapping[str, np.ndarray], ...] = ()
    fields: VertexFields | None = None
    thermal_strip: Mapping[str, np.ndarray] | None = None
    quantities: Mapping[str, float] = field(default_factory=dict)
    exit_profile: dict | None = None
    exit_strain: float | None = None
    solve_stats: Mapping[str, object] = field(default_factory=dict)
    dofs: int | None = None
    nonlinear: str | None = None
    write_vtk: Callable[[Path, float], Path] | None = field(default=None, repr=False)
    spread: SpreadResult | None = None
