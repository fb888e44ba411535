"""A case with ``[spread]`` run end to end (workflows/spread.py, issue 53): the plane-strain pass,
then the 3D quarter strip across the case's width, its figures in summary.json and its files.
Case R (R = 250 mm, 10 -> 8 mm, Tresca 0.3, Norton-Hoff m = 0.05) with a bar 10 mm wide
(b0/h0 = 1), two width layers, the roll axis moved to x = 0.3 m.

Labels: [reference] an independent figure (the empirical spread formulas); [identity] what any
solution satisfies; [hand] signs and limits from the mechanics; [plumb] the files and keys."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from hotroll.config.case import load_case
from hotroll.theory.spread import hill, sparling, wusatowski
from hotroll.workflows.runner import run_case

AXIS = 0.3            # m, where the case puts the roll axis
CASE = {"pass.roll_radius": 0.25, "pass.entry_thickness": 0.01, "pass.exit_thickness": 0.008,
        "pass.roll_angular_velocity": 4.0, "pass.roll_axis_x": AXIS, "pass.width": 0.01,
        "material.law": "norton-hoff", "material.K": 1.5e8, "material.m": 0.05,
        "friction.law": "tresca", "friction.factor": 0.3, "friction.a_f": None,
        "mesh.h_contact": 1e-3, "solver.method": "steady", "plate.length": 0.2,
        "spread.edge_layer": 0.0025, "output.figures": False}


@pytest.fixture(scope="module")
def ran(tmp_path_factory):
    out = tmp_path_factory.mktemp("spread")
    case = load_case("hotroll/examples/cases/example1.toml", CASE)
    summary = run_case(case, out)
    return case, dict(summary), out


def test_the_spread_lies_in_the_formulas_band_and_is_the_exit_width_s(ran):
    """[reference] the spread inside the envelope of Hill, Sparling and Wusatowski (as PyRolL
    has them, correction factors 1) for this bar; [identity] exit width = width + spread; the
    formulas' columns are theory/spread.py's."""
    _, s, _ = ran
    b0, h0, h1, R = 0.01, 0.01, 0.008, 0.25
    formulas = [float(f(b0, h0, h1, R)) - b0 for f in (hill, sparling, wusatowski)]
    assert [s["spread_hill"], s["spread_sparling"], s["spread_wusatowski"]] == pytest.approx(
        formulas, rel=1e-12)
    assert min(formulas) <= s["spread"] <= max(formulas)
    assert s["exit_width"] == pytest.approx(s["width"] + s["spread"], rel=1e-12)
    assert s["exit_code"] == 0 and s["converged"] and s["spread_settled"]
    assert s["units"]["spread"] == "m" and s["units"]["roll_force_total"] == "N"
    # the estimate before meshing counts the 3D pass's unknowns (workflows/estimate.py: per
    # width level and layer of the 2D triangles; the 2D count's own 0.82-0.91 mesher factor)
    assert s["estimated_dofs"] == pytest.approx(s["dofs"] + s["spread_dofs"], rel=0.15)


def test_the_free_edge_lowers_the_whole_widths_force(ran):
    """[hand] the free edge lets the strip spread instead of pressing: the 3D pass's force over
    the width is below plane strain x width (and, loosely, above half of it); [identity] its
    power is its torque times omega, the mill's both rolls'."""
    _, s, _ = ran
    assert 0.5 * s["plane_strain_roll_force_total"] < s["roll_force_total"] \
        < s["plane_strain_roll_force_total"]
    assert s["plane_strain_roll_force_total"] == pytest.approx(s["roll_force"] * 0.01, rel=1e-12)
    omega = CASE["pass.roll_angular_velocity"]
    assert s["roll_power_total"] == pytest.approx(omega * s["roll_torque_total"], rel=1e-12)
    assert s["mill_power"] == pytest.approx(2.0 * s["roll_power_total"], rel=1e-12)
    assert 0.0 < s["edge_bulge"] < s["spread"]
    # the 3D pass's flux balance: in = out + through the lateral faces (the traced tops leak
    # 5.7e-4 of the inflow on this mesh, as the 2D pass's: docs/validation/spread_3d.md)
    assert abs(s["spread_mass_flux_error"]) < 1e-3
    # [identity] the power balance of the 3D form tested with the velocity, its roll power
    # the torque x omega: 6.6e-5 measured (the 2D pass's 2.3e-4)
    assert s["spread_power_balance_error"] < 3e-4


def test_the_contact_map_carries_the_roll_force(ran):
    """[identity, to the quadrature] the contact map's pressure integrated over the arc and the
    width (its levels' points (x, -R cos(angle), z), each quadrilateral two triangles, p cos
    their vertices' mean; both halves) is the vertical roll force within 2 % (the friction's
    vertical share and the rule; 0.5 % measured)."""
    _, s, out = ran
    with np.load(out / "contact_map.npz") as d:
        x, angle, p, z = d["x"], d["angle"], d["pressure"], d["z"]
    pts = np.stack([x, -0.25 * np.cos(angle), z], axis=-1)
    f = p * np.cos(angle)
    force = 0.0
    for a, b, c in (((0, 0), (1, 0), (1, 1)), ((0, 0), (1, 1), (0, 1))):
        corner = [(slice(i, i + pts.shape[0] - 1), slice(j, j + pts.shape[1] - 1))
                  for i, j in (a, b, c)]
        P = [pts[k] for k in corner]
        area = 0.5 * np.linalg.norm(np.cross(P[1] - P[0], P[2] - P[0]), axis=-1)
        force += np.sum(area * sum(f[k] for k in corner) / 3.0)
    force *= 2.0
    assert force == pytest.approx(s["roll_force_total"], rel=0.02)


def test_the_files_are_in_the_cases_frame(ran):
    """[plumb] exit_section.csv's mean half width is the exit width's half; width_along.csv and
    contact_map.npz stand where the case puts the roll axis (x = 0.3 m): the contact between
    the touching point (R sin(alpha) before the axis) and the gap (the axis), the angles in
    [0, alpha]; the widths grow from the stock's; fields_3d.vtu a 3D ParaView file."""
    _, s, out = ran
    sec = np.genfromtxt(out / "exit_section.csv", delimiter=",", names=True)
    assert 2.0 * sec["half_width"].mean() == pytest.approx(s["exit_width"], rel=1e-12)
    # the edge's bulge: the section's half width at mid-thickness over that at the surface
    # (a barrel, the widest at mid-thickness), its range
    assert sec["half_width"][0] == sec["half_width"].max() > sec["half_width"][-1]
    assert s["edge_bulge"] == pytest.approx(np.ptp(sec["half_width"]), rel=1e-12)
    assert sec["y"].max() < 0.004 < sec["y"].max() + 0.004 / 40.0
    # the exit thickness across the width: rigid rolls and the contact to the gap, so the
    # roll gap (8 mm) at every width level to the top tracing's tolerance [hand]; the edge
    # drop its difference mid-width to edge [identity]
    thick = np.genfromtxt(out / "exit_thickness.csv", delimiter=",", names=True)
    assert thick["z"][0] == pytest.approx(0.0, abs=1e-12) and np.all(np.diff(thick["z"]) > 0)
    assert thick["thickness"] == pytest.approx(np.full(thick.size, 0.008), rel=2e-3)
    assert s["edge_drop"] == pytest.approx(thick["thickness"][0] - thick["thickness"][-1],
                                           rel=1e-12, abs=1e-15)
    along = np.genfromtxt(out / "width_along.csv", delimiter=",", names=True)
    assert along["x"].min() < AXIS < along["x"].max()
    assert along["centre"][0] == pytest.approx(0.005, rel=1e-9)
    assert along["centre"][-1] == pytest.approx(0.5 * s["exit_width"], rel=0.05)
    alpha = math.acos(1.0 - 0.001 / 0.25)
    with np.load(out / "contact_map.npz") as d:
        x, angle, p, z = d["x"], d["angle"], d["pressure"], d["z"]
    assert AXIS - 0.25 * math.sin(alpha) - 1e-3 < x.min() and x.max() < AXIS + 1e-6
    assert angle.min() > -1e-6 and angle.max() < alpha + 1e-3
    assert p.shape == z.shape == x.shape == angle.shape == (3, x.shape[1]) and np.median(p) > 0.0
    assert z[0] == pytest.approx(0.0, abs=1e-12) and np.all(z[-1] >= 0.005 - 1e-12)
    # fields_3d.vtu: NGSolve's raw appended points (a UInt32 byte count, then x, y, z), the
    # quarter strip in the case's frame: x around the roll axis, z in [0, the exit half width]
    raw = (out / "fields_3d.vtu").read_bytes()
    head, data = raw.split(b'<AppendedData encoding="raw">')
    n = int(head.split(b'NumberOfPoints="')[1].split(b'"')[0])
    data = data[data.index(b"_") + 1:]
    assert int(np.frombuffer(data[:4], dtype="<u4")[0]) == 24 * n
    pts = np.frombuffer(data[4:4 + 24 * n], dtype="<f8").reshape(n, 3)
    assert pts[:, 0].min() < AXIS - 0.01 and pts[:, 0].max() > AXIS + 0.01
    assert pts[:, 2].min() == pytest.approx(0.0, abs=1e-12)
    assert pts[:, 2].max() == pytest.approx(0.5 * s["exit_width"], rel=0.05)
    assert json.loads((out / "summary.json").read_text())["spread"] == s["spread"]


def test_the_spread_figure_is_drawn(ran):
    """[plumb] fig_spread.png from the run's files."""
    from hotroll.results.figures import RunFiles
    from hotroll.results.figures.spread import fig_spread

    _, _, out = ran
    path = fig_spread(RunFiles(out), out / "fig_spread.png")
    assert path is not None and path.stat().st_size > 10_000


def test_the_html_page_shows_the_width_and_spread(ran):
    """[plumb] report.html: the "Width and spread" group, the spread's key figure, the [spread]
    inputs."""
    from hotroll.results.report import write_report

    _, s, out = ran
    html = write_report(out).read_text()
    assert "Width and spread" in html and "edge_layer" in html
    assert f"{1e3 * s['spread']:.4g}" in html


@pytest.mark.parametrize("mode", ["transported", "frozen"])
def test_the_cases_strain_mode_reaches_the_3d_pass(monkeypatch, mode):
    """[plumb] ``spread.strain`` is the 3D pass's ``strain`` (the pass itself faked)."""
    from hotroll.workflows import spread

    seen = {}

    class Stop(Exception):
        pass

    def fake(run, half, **kw):
        seen.update(kw, half=half)
        raise Stop

    monkeypatch.setattr(spread, "Spread3D", fake)
    case = load_case("hotroll/examples/cases/example1.toml", {**CASE, "spread.strain": mode})
    with pytest.raises(Stop):
        spread.solve_spread(case, run=None)
    assert seen["strain"] == mode and seen["half"] == pytest.approx(0.005)
    assert seen["entry_temperature"] is None


def _handed(case, monkeypatch) -> dict:
    """The keywords ``workflows/spread.solve_spread`` hands the 3D pass of ``case`` (the pass
    faked: it records them and stops)."""
    from hotroll.workflows import spread

    seen = {}

    class Stop(Exception):
        pass

    def fake(run, half, **kw):
        seen.update(kw)
        raise Stop

    monkeypatch.setattr(spread, "Spread3D", fake)
    with pytest.raises(Stop):
        spread.solve_spread(case, run=None)
    return seen


def test_the_cases_entry_temperature_across_the_width_reaches_the_3d_pass(monkeypatch):
    """[plumb] ``spread.temperature_profile`` (and ``spread.temperature_section``) is the 3D
    pass's ``entry_temperature``, over the cross-section: the profile across the width added
    to the plate's through the thickness (the pass itself faked)."""
    grade = {**CASE, "material.law": "hensel-spittel", "material.grade": "C45",
             "material.m": None, "material.K": None}
    case = load_case("hotroll/examples/cases/example1.toml", {
        **grade, "spread.temperature_profile": [[0.0, 1373.15], [1.0, 1273.15]]})
    f = _handed(case, monkeypatch)["entry_temperature"]
    assert float(f(0.0, 0.0)) == 1373.15 and float(f(0.7, 0.5)) == pytest.approx(1323.15)
    section = {"eta": [0.0, 1.0], "zeta": [0.0, 1.0],
               "values": [[1373.15, 1300.0], [1373.15, 1250.0]]}
    case = load_case("hotroll/examples/cases/example1.toml", {
        **grade, "spread.temperature_section": section})
    assert _handed(case, monkeypatch)["entry_temperature"].to_dict() == section


def test_the_cases_linear_solver_reaches_the_3d_pass(monkeypatch):
    """[plumb] ``spread.linear_solver`` is the 3D pass's ``linear_solver`` (the pass faked)."""
    case = load_case("hotroll/examples/cases/example1.toml",
                     {**CASE, "spread.linear_solver": "amg+gmres"})
    assert _handed(case, monkeypatch)["linear_solver"] == "amg+gmres"
