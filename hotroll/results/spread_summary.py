"""The ``[spread]`` section's figures and files (issue 53): from the 3D pass's record
(``model/spread_result.SpreadResult``) to summary keys (``results/spread_keys.py``) and to
``exit_section.csv``, ``exit_thickness.csv``, ``width_along.csv``, ``contact_map.npz`` and ``fields_3d.vtu``."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from hotroll.model.spread_result import SpreadResult
from hotroll.results.output import write_csv, write_npz
from hotroll.theory.spread import hill, sparling, wusatowski


def spread_figures(case, sp: SpreadResult, roll_force: float) -> dict:
    """The summary keys of the 3D pass ``sp`` of ``case`` (``roll_force``: the plane-strain
    pass's, N/m): its spread and widths, the whole width's force, torque and powers (these
    replace plane strain x width), the formulas' spreads, its checks and costs."""
    p = case.pass_
    b0, h0, h1, R = p.width, p.entry_thickness, p.exit_thickness, p.roll_radius
    return {
        "exit_width": sp.exit_width, "spread": sp.spread, "edge_bulge": sp.edge_bulge,
        "edge_drop": sp.edge_drop,
        "spread_hill": float(hill(b0, h0, h1, R)) - b0,
        "spread_sparling": float(sparling(b0, h0, h1, R)) - b0,
        "spread_wusatowski": float(wusatowski(b0, h0, h1, R)) - b0,
        "roll_force_total": sp.roll_force, "roll_torque_total": sp.roll_torque,
        "roll_power_total": sp.roll_power, "mill_power": 2.0 * sp.roll_power,
        "plane_strain_roll_force_total": roll_force * b0,
        "spread_mass_flux_error": sp.mass_flux_error,
        "spread_forward_slip": sp.forward_slip,
        "spread_power_balance_error": sp.power_balance_error,
        "midplane_pressure_rms_deviation": sp.midplane["midplane_pressure_rms_deviation"],
        "midplane_contact_pressure_rms_deviation":
            sp.midplane["midplane_contact_pressure_rms_deviation"],
        "midplane_contact_pressure_l2_deviation":
            sp.midplane["midplane_contact_pressure_l2_deviation"],
        "midplane_stress_l2_deviation": sp.midplane["midplane_stress_l2_deviation"],
        "midplane_bite_stress_l2_deviation":
            sp.midplane["midplane_bite_stress_l2_deviation"],
        "spread_settled": sp.settled, "spread_rounds": sp.rounds,
        "spread_newton_iterations": sp.newton_iterations, "spread_dofs": sp.dofs,
        "spread_layers": sp.layers, "spread_edge_layer": sp.edge_layer,
        "spread_edge_zone": (b0 / 2 - sp.zone_cut) if sp.zone_cut > 0.0 else None,
        "spread_wall_time": sp.wall_time,
        "exit_temperature_offset": (None if sp.exit_temperature_offset is None
                                    else dict(sp.exit_temperature_offset))}


def formula_warning(back: float, front: float) -> str | None:
    """What the formulas' spreads say beside a pass with tension (``back``, ``front``: Pa), or
    None: Hill's, Sparling's and Wusatowski's have no tension term, and tension narrows the
    spread (docs/notes/issue53-sweep.md: 10 and 20 MPa on the bundled narrow bar, 24 % less
    spread, below all three)."""
    if back == 0.0 and front == 0.0:
        return None
    return (f"spread_hill, spread_sparling, spread_wusatowski: the formulas have no tension "
            f"term; with back and front tension {back / 1e6:.3g} and {front / 1e6:.3g} MPa the "
            "3D spread lies below them (tension narrows the spread)")


def zone_warning(sp: SpreadResult) -> str | None:
    """What an edge zone says (None without one): its interior is held in generalized plane
    strain, right once the edge's 3D flow has died out at the cut, how far in that is
    depends on the pass (docs/validation/spread_3d.md, "The edge zone's interior")."""
    if sp.zone_cut <= 0.0:
        return None
    return (f"spread.edge_zone: the interior inside the cut ({sp.zone_cut:.4g} m from "
            f"mid-width) is one layer in generalized plane strain; the spread is right once "
            f"the edge's 3D flow has died out at the cut, which varies from pass to pass "
            f"(measured against the whole width: Case R's strip at b0/h0 8 within 1.3 % with "
            f"a zone of 1 h0, at b0/h0 16 54 % and 11 % too small with 2 and 4 h0, within 1 % "
            f"with 6 h0; a roughing slab 31, 10 and 0.8 % too small with 1.5, 2.25 and 3 h0): "
            f"widen the zone and compare (a study over spread.edge_zone: the bundled "
            f"study edge_zone)")


def unsettled(sp: SpreadResult, max_rounds: int) -> str | None:
    """Why the 3D pass's figures are not an answer, or None."""
    if sp.settled:
        return None
    if sp.failure:
        return (f"not settled: the 3D pass across the width stopped after {sp.rounds} "
                f"rounds: {sp.failure}")
    return (f"not settled: the 3D pass across the width did not settle in {sp.rounds} rounds "
            f"(spread.max_rounds = {max_rounds}): its Newton, its traced tops or its lateral "
            "face did not converge")


def write_spread_files(out: Path, sp: SpreadResult, shift: float, vtk: bool) -> None:
    """exit_section.csv (y m, half width m), exit_thickness.csv (z m, thickness m; strain -
    where it is carried through the 3D flow),
    width_along.csv (x m, half width at mid-thickness
    and on the surface, m), contact_map.npz (x, angle rad, z m, pressure and pressure_multiplier
    Pa) and, with ``vtk``,
    fields_3d.vtu; x where the case puts the roll axis (``shift``)."""
    write_csv(out / "exit_section.csv", dict(sp.exit_section))
    write_csv(out / "exit_thickness.csv", dict(sp.exit_thickness))
    along = dict(sp.width_along)
    write_csv(out / "width_along.csv", {**along, "x": np.asarray(along["x"]) + shift})
    cmap = dict(sp.contact_map)
    write_npz(out / "contact_map.npz", **{**cmap, "x": np.asarray(cmap["x"]) + shift})
    if vtk and sp.write_vtk is not None:
        sp.write_vtk(out / "fields_3d.vtu", shift)
