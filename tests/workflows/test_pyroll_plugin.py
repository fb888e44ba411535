"""The PyRolL plugin (hotroll/pyroll.py, issue 17) in a real pyroll-core PassSequence: two flat
passes and a transport on a coarse mesh. Its force, torque, exit velocity, forward slip,
exit temperature and strain equal hotroll's own runs of the same passes, built here from the
sequence's numbers in PyRolL's conventions (whole width, one roll, full thickness, K), to
1e-6; the FE solve is cached (two solves for the whole sequence); the transport cools as
hotroll's interpass model; a grooved pass is left to PyRolL's other plugins."""
from __future__ import annotations

import math

import numpy as np
import pytest
from casebuild import shared_scope

pr = pytest.importorskip("pyroll.core", reason="the [pyroll] extra (scripts/setup.sh installs it)")

import hotroll.pyroll as hp  # noqa: E402
import hotroll.pyroll_flow_stress as hf  # noqa: E402
from hotroll.config.case import case_from_dict  # noqa: E402
from hotroll.model.interpass import cool, enthalpy_mean  # noqa: E402
from hotroll.model.thermal_properties import ThermalProperties  # noqa: E402
from hotroll.workflows.runner import run_case  # noqa: E402

WIDTH, R, MU = 1.2, 0.3, 0.25
PROPS = dict(density=7600.0, specific_heat_capacity=650.0, thermal_conductivity=30.0)


def _flat(label: str, gap: float, speed: float):
    return pr.RollPass(label=label, gap=gap, rotation=False, coulomb_friction_coefficient=MU,
                       roll=pr.Roll(groove=pr.FlatGroove(usable_width=WIDTH), nominal_radius=R,
                                    rotational_frequency=speed / (2.0 * math.pi * R)))


@pytest.fixture(scope=shared_scope)
def sequence():
    hp.Config.MESH = {"h_contact": 0.008}
    hp.Config.SOLVER = {"threads": 1}
    hp.reset_stats()
    ip = pr.Profile.box(height=0.1, width=WIDTH, temperature=1373.15, strain=0.0,
                        material="S355J2", **PROPS)
    seq = pr.PassSequence([_flat("R1", 0.08, 0.3), pr.Transport(label="T1", duration=20.0),
                           _flat("R2", 0.065, 0.37)])
    seq.solve(ip)
    return seq, dict(hp.STATS)


def _own_run(tmp_path, name, h0, h1, speed, T0, strain, sweep):
    """hotroll's own run of a pass, its case written from the numbers (not by the plugin), in
    a sweep that starts each pass from the last (as hotroll's schedule and the plugin do:
    the start moves the result within the coupling tolerance, 1e-3 on this coarse mesh)."""
    th = hp.Config.THERMAL
    case = case_from_dict({
        "name": name,
        "pass": {"roll_radius": R, "entry_thickness": h0, "exit_thickness": h1,
                 "roll_angular_velocity": speed / R, "width": WIDTH},
        "plate": {"length": 5.0 * math.sqrt(R * 0.5 * (h0 - h1)), "temperature": T0,
                  "entry_strain": strain},
        "material": {"law": "hensel-spittel", "grade": "S355J2", "density": 7600.0,
                     "specific_heat": 650.0, "conductivity": 30.0},
        "friction": {"law": "coulomb", "mu": MU},
        "mesh": {"h_contact": 0.008},
        "solver": {"method": "steady", "threads": 1},
        "output": {"figures": False, "vtk": False},
        "thermal": {k: th[k] for k in ("htc_contact", "roll_temperature", "htc_air",
                                       "emissivity", "ambient_temperature")},
    })
    return run_case(case, tmp_path / name, resume=False, sweep=sweep)


def _outlet_mean(s):
    eta = np.asarray(s["exit_profile"]["eta"])
    w = np.zeros_like(eta)
    w[:-1] += 0.5 * np.diff(eta)
    w[1:] += 0.5 * np.diff(eta)
    props = ThermalProperties(7600.0, 650.0, 30.0)
    return (enthalpy_mean(props, np.asarray(s["exit_profile"]["temperature"]), w),
            float(w @ np.asarray(s["exit_profile"]["strain"])))


def test_the_passes_are_hotrolls_own_runs(sequence, tmp_path):
    from hotroll.workflows.sweep import Sweep

    seq, stats = sequence
    r1, t1, r2 = seq.units
    own = Sweep(similar=True, history=False)
    for rp, h0, h1, speed in ((r1, 0.1, 0.08, 0.3), (r2, 0.08, 0.065, 0.37)):
        ip = rp.in_profile
        s = _own_run(tmp_path, rp.label, h0, h1, speed, round(ip.temperature, 2), ip.strain,
                     own)
        assert rp.roll_force == pytest.approx(s["roll_force"] * WIDTH, rel=1e-6)
        assert rp.roll.roll_torque == pytest.approx(s["roll_torque"] * WIDTH, rel=1e-6)
        assert rp.forward_slip_ratio == pytest.approx(s["forward_slip"], rel=1e-6)
        assert rp.out_profile.velocity == pytest.approx(s["exit_velocity"], rel=1e-6)
        assert rp.roll.neutral_angle == pytest.approx(-s["neutral_angle"], rel=1e-6)
        T_out, e_out = _outlet_mean(s)
        assert rp.out_profile.temperature == pytest.approx(T_out, rel=1e-9)
        assert rp.out_profile.strain == pytest.approx(e_out, rel=1e-9)
        # PyRolL's own bookkeeping: the entry velocity from the FE exit by volume constancy
        assert ip.velocity == pytest.approx(s["exit_velocity"] * h1 / h0, rel=1e-9)
        # ... which differs from the FE's entry velocity by the run's discrete flux error and
        # by how far the FE's exit thickness lies from h1 (a strip that leaves the roll before
        # the gap thins on; one that recovers elastically past it thickens: a few 1e-4)
        off = abs(s["exit_thickness"] / h1 - 1.0)
        assert off < 1e-3
        assert abs(ip.velocity / s["entry_velocity"] - 1.0) <= (
            1.05 * s["mass_flux_error"] + off + 1e-6)
    # strain: 0 into both passes (PyRolL's transport recrystallises), more than homogeneous out
    assert r2.in_profile.strain == 0.0
    assert r1.out_profile.strain > 2.0 / math.sqrt(3.0) * math.log(0.1 / 0.08)


def test_one_fe_solve_per_pass(sequence):
    """PyRolL asked for the force and torque dozens of times; two FE solves in all, the
    second started from the first (the sequence's sweep)."""
    seq, stats = sequence
    assert stats["fe_solves"] == 2 and stats["warm_starts"] == 1
    assert stats["cache_hits"] >= 20
    r1 = seq.units[0]
    before = dict(hp.STATS)
    hp.solve(r1)
    assert hp.STATS["fe_solves"] == before["fe_solves"]
    assert hp.STATS["cache_hits"] == before["cache_hits"] + 1


def test_the_transport_cools_by_hotrolls_interpass_model(sequence):
    seq, _ = sequence
    r1, t1, r2 = seq.units
    T_in = r1.out_profile.temperature
    want = cool([0.0], [T_in], 0.04, 20.0, ThermalProperties(7600.0, 650.0, 30.0),
                hp.Config.THERMAL["htc_air"], hp.Config.THERMAL["emissivity"],
                t1.environment_temperature).mean   # PyRolL's default 293 K
    assert t1.out_profile.temperature == pytest.approx(want, rel=1e-12)
    assert r2.in_profile.temperature == pytest.approx(want, rel=1e-12)
    assert 5.0 < T_in - want < 50.0


def test_a_grooved_pass_is_left_to_other_plugins():
    rp = pr.RollPass(label="box", gap=0.01, rotation=False,
                     roll=pr.Roll(groove=pr.BoxGroove(depth=0.01, r1=0.002, r2=0.005,
                                                      ground_width=0.05, flank_angle=80),
                                  nominal_radius=0.3, rotational_frequency=1.0))
    assert not hp.is_flat(rp)
    for hook in (hp.roll_force, hp.forward_slip_ratio):
        assert hook.function(rp) is None


def test_a_flow_stress_function_is_fitted_and_used(sequence, tmp_path):
    """The in profile's flow_stress_function (here hotroll's S355J2 law as a plain Python
    function, PyRolL's convention for an explicit hook: a function of the profile returning
    it) is fitted over the pass's range (error < 1 %, the fit has no e^(m4/eps) term) and
    rolls R1 within 1 % of the force the grade itself gives (the strip's modulus given as
    the profile's elastic_modulus, the grade's E(T): without it a function without a grade is
    rigid-plastic)."""
    from hotroll.model.grades import get_grade
    from hotroll.model.strip_elasticity import FAMILIES

    law = get_grade("S355J2").law()
    ip = pr.Profile.box(height=0.1, width=WIDTH, temperature=1373.15, strain=0.0,
                        flow_stress_function=lambda profile: law.sigma,
                        elastic_modulus=FAMILIES["steel"].youngs_modulus(1373.15), **PROPS)
    rp = _flat("R1fit", 0.08, 0.3)
    before = dict(hp.STATS)
    rp.solve(ip)
    # one more FE solve, counted as a warm start exactly when it started from another pass
    assert hp.STATS["fe_solves"] == before["fe_solves"] + 1
    assert hp.STATS["warm_starts"] - before["warm_starts"] == int(
        rp.hotroll_result.get("warm_start_from") is not None)
    fit = rp.hotroll_result["flow_stress_fit"]
    assert fit["source"] == "in_profile.flow_stress_function"
    assert fit["max_rel_error"] < 0.01
    assert rp.roll_force == pytest.approx(sequence[0].units[0].roll_force, rel=0.01)


def test_the_fitting_box_is_the_passs_range():
    """The box the in profile's flow_stress_function is fitted over, by hand: strains from the
    entry's to 1.5 x the pass's increment 2/sqrt3 ln(h0/h1) past it, strain rates 0.05 to 4
    x the mean U/l_c x increment, temperatures from 250 K below the entry (not below 300 K)
    to 60 K above it."""
    from types import SimpleNamespace

    from hotroll.model.grades import get_grade

    law = get_grade("S355J2").law()

    class Profile:
        flow_stress_function = staticmethod(law.sigma)

        def has_value(self, name):
            return name == "flow_stress_function"

    for T0, T_lo in ((1373.15, 1123.15), (500.0, 300.0)):
        rp = SimpleNamespace(in_profile=Profile(), label="box")
        _, info = hf.material(rp, T0, 0.1, 0.01, 0.008, 2.0, 0.02, 0.1)
        inc = 2.0 / math.sqrt(3.0) * math.log(0.01 / 0.008)
        rate = 2.0 / 0.02 * inc
        assert info["strain"] == pytest.approx((0.1, 0.1 + 1.5 * inc), rel=1e-12)
        assert info["strain_rate"] == pytest.approx((0.05 * rate, 4.0 * rate), rel=1e-12)
        assert info["temperature"] == pytest.approx((T_lo, T0 + 60.0), rel=1e-12)
