"""The full-thickness strip's temperature (issue 52: the couplings loop over the rolls): one
strip mesh over the whole thickness, each surface cooled by its own roll and heated by its own
friction (solvers/thermal_coupling.py with ``lower``).

The pass is hotroll/examples/cases/thermal_pass.toml (R = 0.3 m, 100 -> 80 mm, Hensel-Spittel
with a temperature term, a cold roll, air and radiation) with Tresca's friction (factor 0.8).
Each check is labelled: identities of the discrete problem (equal rolls against the half
model, the mirror, the heat balance) and the adiabatic limit, whose exit temperature rise is
the plastic and friction heat over the advected heat capacity (an energy balance by hand)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.solvers.full_steady import FullSteadyRun
from hotroll.solvers.record_fields import exit_profiles
from hotroll.solvers.record_full import exit_profile
from hotroll.solvers.steady import SteadyRun
from hotroll.workflows.build import build_model, steady_settings

OVER = {"friction.law": "tresca", "friction.factor": 0.8, "friction.a_f": None}
ADIABATIC = {"thermal.htc_contact": 0.0, "thermal.htc_air": 0.0, "thermal.emissivity": 0.0}
RHO_C = 7600.0 * 650.0
T_ENTRY = 1373.15
#: an entry temperature profile over the half thickness (centre, surface), K
PROFILE = [[0.0, T_ENTRY], [1.0, T_ENTRY - 100.0]]
THERMAL = ("exit_temperature_mean", "exit_temperature_surface", "heat_to_roll", "heat_to_air",
           "plastic_heat", "friction_heat_to_strip")


def _problem(**extra):
    case = load_case(example_path("thermal_pass"), {**OVER, **extra})
    problem, _ = build_model(case)
    return case, problem, steady_settings(case)


def _tight(st):
    """The couplings' tolerances / 100 (the traced tops', the temperature's, Newton's): an
    identity then holds to the fixed point's limit, not to the two runs' paths."""
    return replace(st, surface_tol=st.surface_tol / 100, thermal_rtol=st.thermal_rtol / 100,
                   tol=st.tol / 100)


def _full(case, problem, st, speeds=(1.0, 1.0), swap=False):
    rp = problem.rp
    rolls = {1: replace(rp, omega=rp.omega * speeds[0]),
             -1: replace(rp, omega=rp.omega * speeds[1])}
    if swap:
        rolls = {1: rolls[-1], -1: rolls[1]}
    run = FullSteadyRun(problem, st, case.plate.length, rolls,
                        {1: problem.friction, -1: problem.friction})
    sol = run.run()
    th = run.thermal
    T_mean, T = th.T_mean.vec.FV().NumPy(), th.field.values
    bounds = (float(T_mean.min()), float(T_mean.max()), float(T.min()), float(T.max()))
    return sol.status, sol.history[-1], exit_profile(run), bounds


@pytest.fixture(scope="module")
def runs():
    case, problem, st = _problem()
    half = SteadyRun(problem, st, case.plate.length)
    out = {"half": (half.run().status, half.state.history[-1], exit_profiles(half))}
    pcase, pproblem, pst = _problem(**{"plate.temperature_profile": PROFILE})
    pst = _tight(pst)
    phalf = SteadyRun(pproblem, pst, pcase.plate.length)
    out["half_profile"] = (phalf.run().status, phalf.state.history[-1])
    out["equal_profile"] = _full(pcase, pproblem, pst)
    out["equal"] = _full(*_problem())
    out["r110"] = _full(*_problem(), speeds=(1.1, 1.0))
    out["r110_swapped"] = _full(*_problem(), speeds=(1.1, 1.0), swap=True)
    out["adiabatic"] = _full(*_problem(**ADIABATIC), speeds=(1.1, 1.0))
    return out


def test_every_run_settles(runs):
    for name, (status, *_) in runs.items():
        assert status == "steady", name


def test_equal_rolls_give_the_half_model(runs):
    """Identity: two equal rolls on the mirrored strip (its temperature mesh mirrored too) are
    the half model's discrete problem twice: the temperatures equal, the heat flows (the whole
    strip's) twice the half strip's, the forces equal. To the coupled fixed point's tolerance,
    not round-off (the full strip settles along another path: its coupling threshold tightens
    after three rounds): measured 1e-7 in force, 4e-7 K/K in the temperatures, 2e-6 in the
    heat to the roll, 7e-6 in the plastic heat (2e-6 read at the vertices, before the
    sources' cell means), 3e-5 in the friction heat. (Before the strip's
    samples were taken inside their cells, solvers/thermal_sampling.py, the friction heat
    differed by 7e-3 and the force by 5e-6: a point search's pick between two elements.)"""
    half, full = runs["half"][1], runs["equal"][1]
    for side in ("upper", "lower"):
        assert full[f"{side}_roll_force"] == pytest.approx(half["roll_force"], rel=1e-6)
    for key in ("exit_temperature_mean", "exit_temperature_surface"):
        assert full[key] == pytest.approx(half[key], rel=1e-6)
    assert full["exit_temperature_surface_lower"] == pytest.approx(
        half["exit_temperature_surface"], rel=1e-6)
    for key, rel in (("heat_to_roll", 2e-5), ("heat_to_air", 2e-5), ("plastic_heat", 2e-5),
                     ("friction_heat_to_strip", 2e-4)):
        assert full[key] == pytest.approx(2.0 * half[key], rel=rel), key


def test_swapping_the_rolls_mirrors_the_temperatures(runs):
    """Identity: the swapped stand is the mirror image of the same discrete problem (the
    temperature's strip mesh and its samples of the mechanics mirror too:
    solvers/thermal_sampling.py): the two surfaces' exit temperatures trade places, the
    strip's heat flows and the rolls' forces stay, to round-off (measured 4e-14)."""
    a, b = runs["r110"][1], runs["r110_swapped"][1]
    assert b["exit_temperature_surface"] == pytest.approx(a["exit_temperature_surface_lower"],
                                                          rel=1e-10)
    assert b["exit_temperature_surface_lower"] == pytest.approx(a["exit_temperature_surface"],
                                                                rel=1e-10)
    for key in ("exit_temperature_mean", "heat_to_roll", "plastic_heat",
                "friction_heat_to_strip"):
        assert b[key] == pytest.approx(a[key], rel=1e-10), key
    assert b["upper_roll_force"] == pytest.approx(a["lower_roll_force"], rel=1e-10)


def test_the_faster_roll_heats_its_surface_more(runs):
    """Physics, by hand: equal rolls' friction heats both surfaces alike; the faster upper roll
    slips more against the strip (its forward zone shorter, its backward slip larger), so its
    friction heat, and with the same chill its exit surface, rise above the lower's."""
    eq, r = runs["equal"][1], runs["r110"][1]
    assert abs(eq["exit_temperature_surface"] - eq["exit_temperature_surface_lower"]) < 1e-3
    assert r["exit_temperature_surface"] > r["exit_temperature_surface_lower"] + 1.0
    assert r["friction_heat_to_strip"] > eq["friction_heat_to_strip"]


def test_heat_balance_and_chill(runs):
    """Identity of the steady heat equation: advected out - in - conducted in = plastic +
    friction heat - heat to the rolls - heat to the air (the reported error without the
    inlet's conduction: measured 2.5e-3, as the half model's). With it the gap is the heat
    equation's residual after the fixed point's last (one, chord) step, so it is bounded by
    the temperature's tolerance thermal_rtol (1e-4) of the heat to the rolls, as the half
    model's test (test_thermal_coupling): measured 7e-9 / 3.6e-6 (equal / r = 1.1, 16x),
    5.7e-8 and 1.5e-8 at r = 1.1 with thermal_rtol / 10 and / 100, 1e-15 once the last
    flow's heat equation is solved to convergence; both surfaces chilled below
    the mean, the mean below the entry temperature."""
    for name in ("equal", "r110"):
        s = runs[name][1]
        gap = (s["advected_out"] - s["advected_in"] - s["conducted_in"]
               - (s["plastic_heat"] + s["friction_heat_to_strip"] - s["heat_to_roll"]
                  - s["heat_to_air"]))
        assert abs(gap) < 1e-4 * s["heat_to_roll"], name
        assert s["heat_balance_error"] < 5e-3
        assert max(s["exit_temperature_surface"], s["exit_temperature_surface_lower"]) \
            < s["exit_temperature_mean"] < T_ENTRY


def test_adiabatic_rise_is_the_heat_over_the_heat_capacity(runs):
    """Independent (an energy balance by hand): with no heat to the rolls or the air, the
    mixing-cup exit temperature rises by (beta x plastic power + f_s x friction power) /
    (rho c Q), Q the whole strip's flux, beta = 0.9 and f_s = 0.5 (thermal_pass's defaults);
    the friction power is both rolls' (each surface heated by its own roll's slip). Measured:
    the rise 7e-4 apart, plastic heat +0.14 %, friction heat +1.1 % (the sources carried to the
    strip mesh's vertices and integrated as P1, as in the half model's test)."""
    s = runs["adiabatic"][1]
    assert s["heat_to_roll"] == 0.0 and s["heat_to_air"] == 0.0
    rise = (s["plastic_heat"] + s["friction_heat_to_strip"]) / (RHO_C * s["mass_flux_in"])
    assert s["exit_temperature_mean"] - T_ENTRY == pytest.approx(rise, rel=5e-3)
    assert s["plastic_heat"] == pytest.approx(0.9 * s["plastic_power"], rel=0.012)
    assert s["friction_heat_to_strip"] == pytest.approx(0.5 * s["friction_power"], rel=0.12)


def test_the_exit_profile_spans_the_whole_thickness(runs):
    """The outlet's profile (record_full.exit_profile: eta -1..1, the thermal strip's rows).
    Identities: equal rolls give the half model's profile mirrored (temperature at +-eta
    the half's at eta, measured 2e-7 K/K) and the shear antisymmetric (the redundant shear of
    symmetric rolling, +-0.12 at the surfaces here);
    the speed ratio's profile has the shear the history reports at the surfaces
    (``exit_shear_strain_upper``/``_lower``: the outlet's vertex values; the profile samples
    just inside the face)."""
    half, eq, r = runs["half"][2], runs["equal"][2], runs["r110"][2]
    eta, T = np.asarray(eq["eta"]), np.asarray(eq["temperature"])
    assert eta[0] == -1.0 and eta[-1] == 1.0 and np.all(np.diff(eta) > 0.0)
    np.testing.assert_allclose(T, T[::-1], rtol=1e-6)
    np.testing.assert_allclose(np.interp(half["eta"], eta, T), half["temperature"], rtol=1e-6)
    # the streamlines' histories (the microstructure's kinetics): mirrored (measured 7e-15)
    # and the half model's (measured 9e-6)
    for key in ("pass_strain", "log_rate_mean", "inverse_temperature_mean"):
        v = np.asarray(eq[key])
        np.testing.assert_allclose(v, v[::-1], rtol=1e-10)
        np.testing.assert_allclose(np.interp(half["eta"], eta, v), half[key], rtol=5e-5)
    g_eq = np.asarray(eq["shear_strain"])
    np.testing.assert_allclose(g_eq, -g_eq[::-1], atol=1e-5 * np.max(np.abs(g_eq)))
    row = runs["r110"][1]
    g = np.asarray(r["shear_strain"])
    assert g[-1] == pytest.approx(row["exit_shear_strain_upper"], rel=1e-3, abs=1e-6)
    assert g[0] == pytest.approx(row["exit_shear_strain_lower"], rel=1e-3, abs=1e-6)
    assert np.max(np.abs(g)) > 1e-2


def test_an_entry_profile_enters_both_halves(runs):
    """Identity: an entry temperature profile (100 K colder at the surface) enters the full
    strip mirrored about the mid-plane (its inlet's |y|), so equal rolls give the half model's
    exit temperatures on both surfaces, at the couplings' tolerances / 100 (``_tight``:
    measured 2.5e-9 in the mean, 4e-8 at the surface; at the default tolerances the two
    paths' 1.9e-5 and 6.6e-6); read at y (not |y|), the lower half entered at the centre's
    temperature (found in review)."""
    half, full = runs["half_profile"][1], runs["equal_profile"][1]
    assert full["exit_temperature_mean"] == pytest.approx(half["exit_temperature_mean"],
                                                          rel=1e-6)
    for key in ("exit_temperature_surface", "exit_temperature_surface_lower"):
        assert full[key] == pytest.approx(half["exit_temperature_surface"], rel=1e-6), key
    assert half["exit_temperature_mean"] < runs["half"][1]["exit_temperature_mean"] - 10.0


def test_every_element_takes_a_temperature_of_the_strip(runs):
    """The mechanics elements' flow temperatures (the K-means of the strip vertices inside
    each, or the strip field at its centroid: solvers/thermal_sampling.py) lie within the
    strip field's range: none without a sample (an element left with no weight once took
    0 K, found in review)."""
    for name in ("equal", "r110", "r110_swapped", "equal_profile"):
        lo, hi, t_lo, t_hi = runs[name][3]
        assert t_lo - 1e-9 <= lo and hi <= t_hi + 1e-9, name


def test_the_full_strips_form_stress_is_the_law_with_a_temperature_dependent_rate_exponent():
    """[identity] the half model's check (tests/solvers/test_thermal_coupling.py) on the full
    strip, built and not solved: with Hensel-Spittel's m8 (m = m3 + m8 T_C) the GapForm's
    Norton-Hoff stress, its consistency and rate offset m(T) - m_ref at each element's
    temperature, is the law's sigma(eps, edot, T) at every point and rate, in a temperature
    field from 900 to 1373 K."""
    from test_thermal_coupling import form_stress_at_centres  # the same directory

    case, problem, st = _problem(**{"material.m8": 1e-4, "material.m3": 0.15})
    rp = problem.rp
    run = FullSteadyRun(problem, st, case.plate.length, {1: rp, -1: rp},
                        {1: problem.friction, -1: problem.friction})
    run._cold_start()                       # the kinematic guess: a flow to take rates of
    got, rate, temp = form_stress_at_centres(run, problem.material)
    assert len(got) > 100 and np.ptp(temp) > 400.0 and np.ptp(np.log(rate)) > 3.0
    expected = problem.flow_stress.sigma(case.plate.entry_strain, rate, temp)
    assert got == pytest.approx(np.asarray(expected), rel=1e-9)


def test_an_elements_temperature_is_the_k_mean_of_its_vertices_by_hand():
    """[hand] thermal_sampling.k_means on three elements: element 0 owns 1000 and 1200 K (equal
    weights), element 1 two vertices at 900 K, element 2 none (the caller gives it its
    centroid's temperature afterwards; the last element, still one entry of the ne). Without
    a law the plain weighted means; with K(T) = exp(-T/100) element 0 takes the T whose K is
    the mean of its vertices' K, 1000 - 100 ln((1 + e^-2)/2) = 1056.6 K (harder than the plain
    1100 K), element 1's uniform 900 K unchanged."""
    from hotroll.solvers.thermal_sampling import k_means

    owner = np.array([0, 0, 1, 1])
    vals = np.array([1000.0, 1200.0, 900.0, 900.0])
    w = np.array([1.0, 1.0, 1.0, 3.0])
    plain = k_means(owner, 3, vals, w)
    assert plain.shape == (3,) and plain[:2] == pytest.approx([1100.0, 900.0], rel=1e-15)
    got = k_means(owner, 3, vals, w, lambda T: np.exp(-np.asarray(T) / 100.0))
    assert got.shape == (3,)
    assert got[0] == pytest.approx(1000.0 - 100.0 * np.log(0.5 * (1.0 + np.exp(-2.0))),
                                   rel=1e-9)
    assert got[1] == 900.0
