"""The coupled steady pass (issue 16): the thermal figures of summary.json, contact.csv,
top.csv and fields.npz against independent numbers, and the direction of the coupling.
The case is hotroll/examples/cases/thermal_pass.toml (R = 0.3 m, 100 -> 80 mm,
Hensel-Spittel with a temperature term, rho c = 7600 x 650 J/(m^3 K)), auto mesh."""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from casebuild import shared_scope

from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.workflows.runner import run_case

CASE = example_path("thermal_pass")
RHO_C = 7600.0 * 650.0
T_ENTRY = 1373.15


def form_stress_at_centres(run, material, seed: int = 7):
    """The run's element temperatures set at random between 900 K and T_ENTRY (its thermal
    coupling's, the rate exponent's offset with them), then at every third element's centre:
    the form's Norton-Hoff stress (Pa, its consistency and rate offset at that temperature),
    the regularised rate sqrt(eps0^2 + edot^2) (2.21) of the run's velocity, and the
    element's temperature (K). The form must vary its exponent with the temperature."""
    from hotroll.fem.forms import strain_rate
    from hotroll.model.material import edot_squared

    form, th = run.form, run.thermal
    assert th.m_varies and form.m_material is not form.m
    rng = np.random.default_rng(seed)
    th.T_mean.vec.FV().NumPy()[:] = rng.uniform(900.0, T_ENTRY, th.T_mean.space.ndof)
    th._set_ratio()
    e2 = edot_squared(strain_rate(form.nonlinear.velocity))
    sigma = material.K * form.material.sigma_ef_reg(e2, m=form.m_material, K=form.consistency)
    mesh = run.mesh
    pts = [mesh(*centre) for centre in
           (np.mean([mesh.vertices[v.nr].point for v in el.vertices], axis=0)
            for el in list(mesh.Elements())[::3])]
    got = np.array([sigma(p) for p in pts])
    rate = np.sqrt(np.array([e2(p) for p in pts]) + material.eps0**2)
    temp = np.array([th.T_mean(p) for p in pts])
    return got, rate, temp
HARD_COULOMB = {"material.A": 1.5e9, "friction.law": "coulomb", "friction.mu": 0.3,
                "friction.a_f": None}


@pytest.fixture(scope=shared_scope)
def adiabatic(tmp_path_factory):
    """No heat transfer to the roll or the air, Coulomb mu = 0.3 (friction heat too), A ten
    times the case's (about 100 MPa at 1100 degC, a steel's: a 5.5 K rise, not 0.5 K)."""
    case = load_case(CASE).with_overrides(**HARD_COULOMB, **{
        "thermal.htc_contact": 0.0, "thermal.htc_air": 0.0, "thermal.emissivity": 0.0})
    return run_case(case, tmp_path_factory.mktemp("adiabatic"))


def test_adiabatic_exit_temperature_rise(adiabatic):
    """Adiabatic limit: the mixing-cup exit temperature rises by (beta x plastic power +
    f_s x friction power) / (rho c Q), Q the inlet's flux (the strip mesh carries it through
    every section: solvers/thermal_coupling.py) (measured 0.05 % apart on a 5.5 K rise; the issue's
    bound is 1 %). The heat sources are the mechanics' powers carried to the strip mesh:
    plastic heat = 0.9 x plastic power (measured +0.02 %: the density's means over the strip
    vertices' cells, integrated as P1; -0.2 % on a mesh refined 16x at the contact's start;
    +0.24 % read at the vertices until 2026-11-29), friction heat = 0.5 x friction power
    (measured -0.3 %: the flux's means over the surface's dual segments in contact; -2.1 %
    refined 16x, where Coulomb's flux peaks at the contact's start within a strip cell;
    +2.2 % read beside the vertices)."""
    s = adiabatic
    rise = (s["plastic_heat"] + s["friction_heat_to_strip"]) / (RHO_C * s["mass_flux_in"])
    assert s["exit_temperature_mean"] - T_ENTRY == pytest.approx(rise, rel=5e-3)
    assert s["plastic_heat"] == pytest.approx(0.9 * s["plastic_power"], rel=0.005)
    assert s["friction_heat_to_strip"] == pytest.approx(0.5 * s["friction_power"], rel=0.03)
    assert s["heat_to_roll"] == 0.0 and s["heat_to_air"] == 0.0


@pytest.fixture(scope=shared_scope)
def chilled(tmp_path_factory):
    """The case as written: cold roll (20 kW/(m^2 K), 350 K), air and radiation."""
    out = tmp_path_factory.mktemp("chill")
    return run_case(load_case(CASE), out), out


@pytest.fixture(scope=shared_scope)
def isothermal(tmp_path_factory):
    """The same pass without [thermal], at the entry temperature."""
    return run_case(load_case(CASE).with_overrides(thermal=None), tmp_path_factory.mktemp("iso"))


def test_heat_balance_and_roll_chill(chilled, isothermal):
    """Enthalpy out - in = plastic + friction heat - heat to the roll - heat to the air + the
    inlet's conduction, recomputed from the summary's terms (measured 4e-8 of the heat to the
    roll). The roll chills the strip: exit mean below the entry temperature, the exit surface
    below the mean, and the colder strip needs more force than the isothermal pass at the
    entry temperature (measured +2.8 %, Hensel-Spittel m1 = -0.0025 1/degC)."""
    s, _ = chilled
    gap = (s["advected_out"] - s["advected_in"] - s["conducted_in"]
           - (s["plastic_heat"] + s["friction_heat_to_strip"] - s["heat_to_roll"]
              - s["heat_to_air"]))
    assert abs(gap) < 1e-4 * s["heat_to_roll"]
    # the reported error is that identity without the inlet's conduction, over the larger of
    # the heat gained and the heat lost
    gain = s["plastic_heat"] + s["friction_heat_to_strip"]
    lost = s["heat_to_roll"] + s["heat_to_air"]
    assert s["heat_balance_error"] == pytest.approx(
        abs(s["advected_out"] - s["advected_in"] - (gain - lost)) / max(gain, lost), rel=1e-6)
    assert s["heat_balance_error"] < 5e-3   # measured 2.5e-3: the cooled top at the inlet
    assert s["exit_temperature_surface"] < s["exit_temperature_mean"] < T_ENTRY
    # measured +2.8 % with exact contact (+3.7 % with the penalty, earlier)
    assert s["roll_force"] > 1.01 * isothermal["roll_force"]


def test_thermal_layer_and_strip_size_by_hand(chilled):
    """thermal_layer = sqrt(alpha l_c / U): alpha = k / (rho c) = 30 / (7600 x 650) m^2/s, the
    projected contact length l_c = sqrt(2 R d - d^2) with the draft d = 10 mm per roll, U =
    omega R = 0.3 m/s (1.25 mm)."""
    s, out = chilled
    R, d = 0.3, 0.01
    lc = math.sqrt(2.0 * R * d - d * d)
    assert s["thermal_layer"] == pytest.approx(math.sqrt(30.0 / RHO_C * lc / 0.3), rel=1e-12)
    assert s["units"]["thermal_layer"] == "m"
    # thermal_dofs: the strip mesh's vertices (P1), as written in thermal.npz
    strip = np.load(out / "thermal.npz")
    assert s["thermal_dofs"] == len(strip["points"]) == len(strip["temperature"])


def test_temperature_along_the_contact_and_the_top(chilled):
    """contact.csv and top.csv against the summary, each recomputed here by another route:
    - the heat to the roll is the contact's heat flux htc (T - T_roll) integrated along the
      contact nodes (trapezoid; the summary integrates the field with its quadrature and the
      the contact's ends by x: measured 0.48 %, the steep chill at the contact start between
      the mechanics' vertices);
    - the exit surface temperature (the strip mesh's top node at the contact's end: the gap, or
      where the strip leaves the roll before it) is top.csv's there (the strip field found at
      the mechanics' vertex there: 1e-9);
    - the contact's temperature is the top's at the same nodes, and the fields' at the
      vertices (the same samples read three ways: 1e-12)."""
    s, out = chilled
    contact = np.genfromtxt(out / "contact.csv", delimiter=",", names=True)
    top = np.genfromtxt(out / "top.csv", delimiter=",", names=True)
    fields = dict(np.load(out / "fields.npz"))
    T_roll, htc = 350.0, 2.0e4
    assert contact["heat_flux_to_roll"] == pytest.approx(htc * (contact["temperature"] - T_roll),
                                                         rel=1e-12)
    seg = np.hypot(np.diff(contact["x"]), np.diff(contact["y"]))
    q = contact["heat_flux_to_roll"]
    heat = float(np.sum(0.5 * (q[1:] + q[:-1]) * seg))
    assert heat == pytest.approx(s["heat_to_roll"], rel=0.01)
    gap = np.argmin(np.abs(top["x"] - s["contact_end"][0]))     # the gap unless it separates
    assert abs(top["x"][gap] - s["contact_end"][0]) < 1e-9
    assert s["exit_temperature_surface"] == pytest.approx(top["temperature"][gap], rel=1e-9)
    for xc, Tc in zip(contact["x"], contact["temperature"]):
        i = np.argmin(np.abs(top["x"] - xc))
        assert top["temperature"][i] == pytest.approx(Tc, rel=1e-12)
    vert = contact["vertex"] > 0
    pts = fields["points"]
    for xc, yc, Tc in zip(contact["x"][vert], contact["y"][vert], contact["temperature"][vert]):
        i = np.argmin(np.hypot(pts[:, 0] - xc, pts[:, 1] - yc))
        assert fields["temperature"][i] == pytest.approx(Tc, rel=1e-12)


def test_exit_surface_temperature_against_the_semi_infinite_body(chilled):
    """The chilled layer (delta ~ 1.2 mm) is thin against the strip (40 mm): a surface point
    in contact for t_c = l_c / U with a roll at T_r through htc is a semi-infinite body with a
    convective surface, T_s = T_i - (T_i - T_r)(1 - exp(b^2) erfc(b)), b = htc sqrt(alpha
    t_c) / k (Carslaw and Jaeger 2.7): 855 K. The FE surface is at 888 K, its drop 6.4 %
    smaller (measured at issue 52 session 2), and falls towards it as the strip mesh is refined
    (docs/studies/thermal_mesh.md, measured at its own commit); the plastic heat and the
    strip's thinning are left out of the closed form."""
    s, out = chilled
    T_i, T_r, htc, k = T_ENTRY, 350.0, 2.0e4, 30.0
    t_c = s["contact_length"] / s["roll_surface_speed"]
    b = htc * math.sqrt(k / RHO_C * t_c) / k
    T_s = T_i - (T_i - T_r) * (1.0 - math.exp(b * b) * math.erfc(b))
    drop = T_i - s["exit_temperature_surface"]
    assert drop == pytest.approx(T_i - T_s, rel=0.11)


def test_written_flow_stress_is_the_law_at_the_local_temperature(chilled):
    """fields.npz's sigma_ef is Hensel-Spittel at each vertex's own strain rate and flow
    temperature (the mechanics elements' means of the strip field): the plastic power int
    sigma edot dx from the written fields against the solve's (measured +0.7 %)."""
    from hotroll.model.flow_stress import HenselSpittel

    s, out = chilled
    f = dict(np.load(out / "fields.npz"))
    law = HenselSpittel(A=1.5e8, m1=-0.0025, m3=0.15)
    assert f["sigma_ef"] == pytest.approx(law.sigma(0.0, f["edot"], f["flow_temperature"]),
                                          rel=1e-9)
    dens = f["sigma_ef"] * f["edot"]
    p, t = f["points"], f["triangles"]
    e1, e2 = p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    assert float(np.sum(area * dens[t].mean(axis=1))) == pytest.approx(s["plastic_power"],
                                                                        rel=0.03)


def test_hotter_entry_lowers_the_force(tmp_path_factory, chilled, isothermal):
    """Hensel-Spittel's exp(m1 T): an isothermal pass 50 K hotter needs exp(-0.0025 x 50) =
    0.8825 times the force, exactly (the solve is homogeneous in the flow stress); the coupled
    pass 50 K hotter about the same (measured 0.8843: the chill and the radiation differ a
    little)."""
    case = load_case(CASE).with_overrides(**{"plate.temperature": T_ENTRY + 50.0})
    hot_iso = run_case(case.with_overrides(thermal=None), tmp_path_factory.mktemp("hot_iso"))
    assert hot_iso["roll_force"] / isothermal["roll_force"] == pytest.approx(
        math.exp(-0.0025 * 50.0), rel=1e-6)
    hot = run_case(case, tmp_path_factory.mktemp("hot"))
    assert hot["roll_force"] / chilled[0]["roll_force"] == pytest.approx(
        math.exp(-0.0025 * 50.0), rel=0.01)


def test_deformation_heating_lowers_the_force(tmp_path_factory, adiabatic):
    """The adiabatic pass heats by deformation and friction only: its force lies below the
    isothermal pass at the entry temperature and above the law at the hottest temperature
    reached, F_iso exp(m1 (T_max - T_entry)) (measured 0.9909 between 0.9787 and 1)."""
    iso = run_case(load_case(CASE).with_overrides(thermal=None, **HARD_COULOMB),
                   tmp_path_factory.mktemp("iso_coulomb"))
    ratio = adiabatic["roll_force"] / iso["roll_force"]
    assert math.exp(-0.0025 * (adiabatic["max_temperature"] - T_ENTRY)) < ratio < 1.0


def test_temperature_figure_shows_the_written_data(chilled, monkeypatch):
    """fig_temperature.png by its data: both field panels colour thermal.npz's vertex
    temperatures (the strip mesh), the surface panel draws top.csv's temperature against x, the exit mean and
    surface temperatures as horizontal lines, and the contact's heat flux (MW/m^2)."""
    from matplotlib.figure import Figure

    import hotroll.results.figures as P

    s, out = chilled
    figs = {}
    real_savefig = Figure.savefig
    monkeypatch.setattr(P.plt, "close", lambda *a, **k: None)

    def savefig(fig, path, *a, **k):
        figs[re.sub(r"\.tmp\w*\.", ".", Path(path).name)] = fig   # atomic (files.py)
        return real_savefig(fig, path, *a, **k)

    monkeypatch.setattr(Figure, "savefig", savefig)
    P.plot_all(out)
    fig = figs["fig_temperature.png"]
    fields = dict(np.load(out / "thermal.npz"))
    top = np.genfromtxt(out / "top.csv", delimiter=",", names=True)
    contact = np.genfromtxt(out / "contact.csv", delimiter=",", names=True)
    field_axes, surface, flux = fig.axes[:2], fig.axes[2], fig.axes[-1]   # then colour bars, twin
    assert surface.get_ylabel() == "T [K]" and flux.get_ylabel().startswith("heat flux")
    for ax in field_axes:
        colours = [c.get_array() for c in ax.collections if c.get_array() is not None]
        assert any(np.allclose(np.asarray(a, float), fields["temperature"]) for a in colours)

    def lines(ax):
        return [(np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float))
                for line in ax.get_lines()]

    assert any(len(x) == len(top) and np.allclose(x, top["x"]) and
               np.allclose(y, top["temperature"]) for x, y in lines(surface))
    levels = {float(y[0]) for x, y in lines(surface) if len(y) == 2 and y[0] == y[1]}
    assert any(abs(v - s["exit_temperature_mean"]) < 1e-9 for v in levels)
    assert any(abs(v - s["exit_temperature_surface"]) < 1e-9 for v in levels)
    assert any(np.allclose(y, contact["heat_flux_to_roll"] / 1e6) for _, y in lines(flux))


def test_form_stress_is_the_law_with_a_temperature_dependent_rate_exponent():
    """With Hensel-Spittel's m8 (m = m3 + m8 T_C), the form's Norton-Hoff stress K_ref K(eps,
    T)/K_ref 3^((m(T)+1)/2) edot^m(T), its consistency and rate offset at each element's
    temperature, is the law's sigma(eps, edot, T) at every point and rate, in a temperature
    field from 900 to 1373 K (exponent 0.24 to 0.29 against m_ref 0.29)."""
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.runner import build_model, steady_settings

    case = load_case(CASE).with_overrides(**{"material.m8": 1e-4, "material.m3": 0.15})
    model, _ = build_model(case)
    run = SteadyRun(model, steady_settings(case), case.plate.length)
    run._cold_start()
    law = model.flow_stress
    got, rate, temp = form_stress_at_centres(run, model.material)
    assert len(got) > 100 and np.ptp(temp) > 400.0 and np.ptp(np.log(rate)) > 3.0
    expected = law.sigma(case.plate.entry_strain, rate, temp)
    assert got == pytest.approx(np.asarray(expected), rel=1e-9)


def test_a_law_without_temperature_settles_with_the_heat_field(tmp_path):
    """Norton-Hoff (no T in the law) with [thermal]: the element temperatures are the plain
    means (K is the same at every T: the bisection of the K-mean would follow the rounding and
    the coupling never settled, found rolling a Norton-Hoff schedule), the run settles, and
    its force is the isothermal run's (the temperature does not enter the law) to 2e-5."""
    over = {"material.law": "norton-hoff", "material.A": None, "material.m1": None,
            "material.m3": None, "material.K": 5.0e7, "material.m": 0.15,
            "friction.law": "coulomb", "friction.mu": 0.3, "friction.a_f": None,
            "mesh.h_contact": 0.008}
    case = load_case(CASE).with_overrides(**over)
    coupled = run_case(case, tmp_path / "coupled")
    iso = run_case(case.with_overrides(thermal=None), tmp_path / "iso")
    assert coupled["exit_code"] == 0 and coupled["status"] == "steady"
    # measured 3.1e-6 with exact contact (the coupled fixed point stops at another point of
    # its tolerance than the isothermal one), 1e-6 with the penalty
    assert coupled["roll_force"] == pytest.approx(iso["roll_force"], rel=2e-5)
    fields = np.load(tmp_path / "coupled" / "fields.npz")
    assert np.all(np.isfinite(fields["flow_temperature"]))
