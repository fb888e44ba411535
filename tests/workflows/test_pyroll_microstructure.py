"""hotroll's microstructure through a PyRolL sequence (issue 33 item 4; hotroll/pyroll_microstructure.py,
docs/validation/microstructure-pyroll.md): a C-Mn strip 20 -> 16 mm at 1050 degC, d0 = 100 um,
a 1 s transport and a second pass, Hodgson and Gibbs' set, on a coarse mesh (two FE solves,
about 3 s).

- the transport's out profile carries hotroll's softening of the pass's exit profile (the means
  and the arrays over eta), and the next pass enters with the retained-strain profile;
- the three-way comparison on mean values: (a) hotroll's kinetics on one point (the section
  means), (b) pyroll-jmak-recrystallization 3.0.0 with the same constants and means (in its own
  process: its hooks stay registered once imported), (c) hotroll's FE through the thickness;
- both plugins loaded: hotroll's values win where MICROSTRUCTURE is on (own process)."""
from __future__ import annotations

import importlib.util
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from casebuild import shared_scope

pr = pytest.importorskip("pyroll.core", reason="the [pyroll] extra (scripts/setup.sh installs it)")

import hotroll.pyroll as hp  # noqa: E402
import hotroll.pyroll_microstructure as hm  # noqa: E402
from hotroll.model.interpass import cool  # noqa: E402
from hotroll.model.microstructure import get_set  # noqa: E402
from hotroll.model.microstructure.softening import pass_state, soften  # noqa: E402
from hotroll.model.profile import ThicknessProfile  # noqa: E402
from hotroll.model.thermal_properties import ThermalProperties  # noqa: E402
from hotroll.workflows.microstructure import on_rows  # noqa: E402

SET = "hodgson_gibbs_cmn"
WIDTH, R, SPEED, D0, T0, DURATION = 1.0, 0.3, 1.0, 100e-6, 1323.15, 1.0
PROPS = dict(density=7600.0, specific_heat_capacity=650.0, thermal_conductivity=30.0)
MESH = {"h_contact": 0.0016}

#: (b): pyroll-jmak-recrystallization on the given means, in a process of its own; with
#: "fe": also a hotroll pass and transport with both plugins loaded (JMAK's imported first).
JMAK_RUN = r'''
import json, math, sys
import pyroll.core as pr
import pyroll.jmak_recrystallization as jm
from pyroll.jmak_recrystallization.config import Config as JC
from pyroll.jmak_recrystallization.transport import transport_out_grain_size

a = json.load(sys.stdin)
JC.BASE_STRAIN, JC.BASE_STRAIN_RATE = 0.0, 0.0    # no +0.01 offsets: the set's own laws
P = a["params"]
out = {}


@pr.RollPass.strain_rate(tryfirst=True)       # the FE section's mean rate (PyRolL's own is
def _rate(self):                              # strain / contact time)
    return a["rate"] if self.label == "mean" else None


ip = pr.Profile.box(
    height=a["h0"], width=1.0, temperature=a["T"], strain=0.0, material="hotroll-mean",
    grain_size=a["d0"], recrystallized_fraction=0.0, flow_stress=100e6,
    jmak_dynamic_recrystallization_parameters=jm.JMAKRecrystallizationParameters(**P["dynamic"]),
    jmak_static_recrystallization_parameters=jm.JMAKRecrystallizationParameters(**P["static"]),
    jmak_metadynamic_recrystallization_parameters=jm.JMAKRecrystallizationParameters(
        **P["metadynamic"]),
    jmak_grain_growth_parameters=jm.JMAKGrainGrowthParameters(**P["growth"]))
rp = pr.RollPass(label="mean", gap=a["h1"], rotation=False, velocity=1.0, strain=a["strain"],
                 roll=pr.Roll(groove=pr.FlatGroove(usable_width=1.2), nominal_radius=0.3))
tr = pr.Transport(label="T", duration=a["duration"])
pr.PassSequence([rp, tr]).solve(ip)
op = tr.out_profile
out["b"] = {"pass_mechanism": rp.recrystallization_mechanism,
            "critical_strain": float(rp.recrystallization_critical_strain),
            "mechanism": tr.recrystallization_mechanism,
            "half_time": float(tr.recrystallization_reference_time),
            "recrystallized_fraction": float(op.recrystallized_fraction),
            "recrystallized_grain_size": float(tr.recrystallized_grain_size),
            "grain_size": float(op.grain_size), "strain": float(op.strain),
            "temperatures": [float(rp.in_profile.temperature), float(op.temperature)],
            "strain_rate": float(rp.strain_rate), "strain_in": float(tr.in_profile.strain)}

if a.get("fe"):
    import hotroll.pyroll as hp
    hp.Config.MESH = a["fe"]["mesh"]
    hp.Config.SOLVER = {"threads": 1}
    hp.Config.MICROSTRUCTURE = a["fe"]["set"]
    f = a["fe"]
    p1 = pr.RollPass(label="P1", gap=f["h1"], rotation=False, coulomb_friction_coefficient=0.3,
                     roll=pr.Roll(groove=pr.FlatGroove(usable_width=1.0), nominal_radius=f["R"],
                                  rotational_frequency=f["speed"] / (2 * math.pi * f["R"])))
    t1 = pr.Transport(label="T1", duration=f["duration"])
    ip = pr.Profile.box(height=f["h0"], width=1.0, temperature=f["T0"], strain=0.0,
                        material=["S355J2", "C-Mn"], grain_size=f["d0"],
                        recrystallized_fraction=0.0, **f["props"])
    pr.PassSequence([p1, t1]).solve(ip)
    rec = t1.hotroll_microstructure
    out["both"] = {"grain_size": float(t1.out_profile.grain_size),
                   "strain": float(t1.out_profile.strain),
                   "recrystallized_fraction": float(t1.out_profile.recrystallized_fraction),
                   "hotroll": {k: rec[k + "_mean"] for k in
                               ("grain_size", "retained_strain", "recrystallised_fraction")},
                   "jmak_grain_size": float(transport_out_grain_size(t1.out_profile)),
                   "pass_grain_size": float(p1.out_profile.grain_size)}
print(json.dumps(out))
'''


def _flat(label: str, gap: float):
    return pr.RollPass(label=label, gap=gap, rotation=False, coulomb_friction_coefficient=0.3,
                       roll=pr.Roll(groove=pr.FlatGroove(usable_width=WIDTH), nominal_radius=R,
                                    rotational_frequency=SPEED / (2.0 * math.pi * R)))


def _strip(**kw):
    return pr.Profile.box(height=0.02, width=WIDTH, temperature=T0, strain=0.0,
                          material="S355J2", **PROPS, **kw)


@pytest.fixture(scope=shared_scope)
def rolled():
    saved = (hp.Config.MESH, hp.Config.SOLVER, hp.Config.MICROSTRUCTURE)
    hp.Config.MESH, hp.Config.SOLVER, hp.Config.MICROSTRUCTURE = MESH, {"threads": 1}, SET
    hp.reset_stats()
    try:
        seq = pr.PassSequence([_flat("P1", 0.016), pr.Transport(label="T1", duration=DURATION),
                               _flat("P2", 0.013)])
        seq.solve(_strip(grain_size=D0))
        yield seq
    finally:
        hp.Config.MESH, hp.Config.SOLVER, hp.Config.MICROSTRUCTURE = saved


def _mean(eta, values) -> float:
    return ThicknessProfile(tuple(eta), tuple(np.asarray(values, dtype=float))).mean()


def _own_softening(p1, t1):
    """hotroll's schedule functions on the pass's exit profile, built here: the pass state
    (entry strain 0 + the streamlines' pass strain), the recorded cooling of the exit
    temperature profile over the transport (in pyroll-core's air at 293 K), the softening."""
    kin = get_set(SET)
    prof = hp.solve(p1)["exit_profile"]
    eta = np.asarray(prof["eta"])
    ps = pass_state(kin, eta, np.asarray(prof["pass_strain"]), np.full(eta.size, D0),
                    prof["log_rate_mean"], prof["inverse_temperature_mean"],
                    prof["temperature"])
    th = hp.Config.THERMAL
    res = cool(eta, np.asarray(prof["temperature"]), 0.008, DURATION,
               ThermalProperties(7600.0, 650.0, 30.0), th["htc_air"], th["emissivity"],
               float(t1.environment_temperature), record=True)
    return ps, soften(kin, ps, res.times, on_rows(res.history, res.y, ps.eta)), res


def test_the_transport_carries_hotrolls_softening(rolled):
    p1, t1, p2 = rolled.units
    ps, soft, _ = _own_softening(p1, t1)
    op = t1.out_profile
    assert op.grain_size == pytest.approx(_mean(soft.eta, soft.grain), rel=1e-9)
    assert op.recrystallized_fraction == pytest.approx(_mean(soft.eta, soft.fraction), rel=1e-9)
    assert op.strain == pytest.approx(_mean(soft.eta, soft.retained_strain), rel=1e-9)
    np.testing.assert_allclose(op.hotroll_profile_eta, soft.eta, rtol=0, atol=1e-12)
    np.testing.assert_allclose(op.hotroll_grain_size_profile, soft.grain, rtol=1e-9)
    np.testing.assert_allclose(op.hotroll_recrystallized_fraction_profile, soft.fraction,
                               rtol=1e-9)
    np.testing.assert_allclose(op.hotroll_strain_profile, soft.retained_strain, rtol=1e-9)
    # the pass keeps its state and hands on the grain it entered with (softening follows)
    np.testing.assert_allclose(p1.hotroll_pass_state.strain, ps.strain, rtol=1e-12)
    assert p1.out_profile.grain_size == D0 and p1.out_profile.recrystallized_fraction == 0.0
    # a distribution, not a uniform value: the surface is chilled and strained more
    assert soft.fraction[0] - soft.fraction[-1] > 0.03
    assert soft.half_time[-1] / soft.half_time[0] > 2.0
    rec = t1.hotroll_microstructure
    assert rec["grain_size_mean"] == pytest.approx(op.grain_size, rel=1e-12)


def test_the_next_pass_enters_with_the_retained_strain_profile(rolled):
    p1, t1, p2 = rolled.units
    import tomllib

    plate = tomllib.loads(hp.solve(p2)["case_toml"])["plate"]
    prof = np.asarray(plate["strain_profile"])
    np.testing.assert_allclose(prof[:, 0], t1.out_profile.hotroll_profile_eta, atol=1e-9)
    np.testing.assert_allclose(prof[:, 1], t1.out_profile.hotroll_strain_profile, atol=1e-6)
    assert p2.in_profile.strain == pytest.approx(_mean(prof[:, 0], prof[:, 1]), abs=1e-6)
    assert p2.in_profile.grain_size == pytest.approx(t1.out_profile.grain_size, rel=1e-12)
    # its kinetics add the pass strain on each streamline to that profile
    ps2 = p2.hotroll_pass_state
    pass_strain = np.asarray(hp.solve(p2)["exit_profile"]["pass_strain"])
    entry = np.interp(ps2.eta, prof[:, 0], prof[:, 1])
    np.testing.assert_allclose(ps2.strain, entry + pass_strain, rtol=1e-12)
    np.testing.assert_allclose(ps2.grain, np.interp(ps2.eta, t1.out_profile.hotroll_profile_eta,
                                                    t1.out_profile.hotroll_grain_size_profile))


def _means(p1, t1) -> dict:
    """The pass's section means (c) hands to (a) and (b): the kinetics strain, the strain rate
    exp(<ln edot>), and PyRolL's one temperature of the transport, (T_in + T_out) / 2."""
    ps = p1.hotroll_pass_state
    return {"strain": _mean(ps.eta, ps.strain), "rate": math.exp(_mean(ps.eta, np.log(ps.rate))),
            "T": 0.5 * (t1.in_profile.temperature + t1.out_profile.temperature),
            "d0": D0, "duration": DURATION, "h0": 0.02, "h1": 0.016}


def _jmak(args: dict) -> dict:
    # not imported here: its hooks would stay registered for the other PyRolL tests
    if importlib.util.find_spec("pyroll.jmak_recrystallization") is None:
        pytest.skip("pip install pyroll-jmak-recrystallization==3.0.0 (the [pyroll] extra)")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(Path(hp.__file__).resolve().parents[1]), os.environ.get("PYTHONPATH", "")]))
    run = subprocess.run([sys.executable, "-c", JMAK_RUN], input=json.dumps(args), check=True,
                         capture_output=True, text=True, env=env)
    return json.loads(run.stdout)


KEYS = ("recrystallized_fraction", "grain_size", "strain")


def _table(m, a, b, c, rec) -> None:
    """The table of docs/validation/microstructure-pyroll.md (shown with pytest -s)."""
    print(f"\nmeans: strain {m['strain']:.5f}, rate {m['rate']:.4f} 1/s, T {m['T']:.2f} K, "
          f"d0 {1e6 * m['d0']:g} um, hold {m['duration']:g} s")
    print("| quantity | (a) hotroll, means | (b) PyRolL JMAK | (c) hotroll FE: section mean "
          "(centre .. surface) |")
    print("|---|---|---|---|")
    for key, unit, f in (("critical_strain", "", 1.0), ("half_time", " s", 1.0),
                         ("recrystallized_fraction", "", 1.0),
                         ("recrystallized_grain_size", " um", 1e6), ("grain_size", " um", 1e6),
                         ("strain", "", 1.0)):
        own = {"recrystallized_fraction": "recrystallised_fraction",
               "recrystallized_grain_size": "recrystallised_grain_size",
               "strain": "retained_strain"}.get(key, key)
        print(f"| {key}{unit} | {f * a[key]:.10g} | {f * b[key]:.10g} | {f * c[key]:.6g} "
              f"({f * rec[own][0]:.4g} .. {f * rec[own][-1]:.4g}) |")


def test_three_way_on_mean_values(rolled):
    """(a) hotroll's kinetics on the means and (b) PyRolL's plugin with the same constants
    agree to 1e-8 (the gas constant's last digits) where the formulas are the same, and on the
    grain size to PyRolL's growth of the unrecrystallised grains during the hold, computed
    here; (c) the FE section's means are within 0.03 of (a) in X and 3 % in d and the retained
    strain (the through-thickness distribution and the cooling history against one mean)."""
    p1, t1, _ = rolled.units
    kin = get_set(SET)
    m = _means(p1, t1)
    a = hm.mean_kinetics(kin, m["strain"], D0, m["rate"], m["T"], DURATION)
    b = _jmak({**m, "params": hm.jmak_parameters(kin)})["b"]
    assert b["temperatures"] == pytest.approx([m["T"], m["T"]], rel=1e-12)
    assert b["strain_in"] == pytest.approx(m["strain"], rel=1e-12)
    assert b["strain_rate"] == pytest.approx(m["rate"], rel=1e-12)
    assert a["mechanism"] == b["mechanism"] == "static" and b["pass_mechanism"] == "none"
    for key in ("critical_strain", "half_time", "recrystallized_fraction",
                "recrystallized_grain_size", "strain"):
        assert a[key] == pytest.approx(b[key], rel=1e-8), key
    # PyRolL grows the unrecrystallised grains over the whole hold ((1 - X)^2 d0 grown),
    # hotroll keeps d0: that, and only that, is the difference (8.7e-5 of d here)
    X = a["recrystallized_fraction"]
    grown = float(kin.grown(D0, DURATION * kin.growth.rate(m["T"])))
    assert b["grain_size"] == pytest.approx(a["grain_size"] + (1 - X) ** 2 * (grown - D0),
                                            rel=1e-8)
    assert b["grain_size"] == pytest.approx(a["grain_size"], rel=2e-4)
    c = {k: float(getattr(t1.out_profile, k)) for k in KEYS}
    rec = t1.hotroll_microstructure
    for key, own in (("critical_strain", "critical_strain"), ("half_time", "half_time"),
                     ("recrystallized_grain_size", "recrystallised_grain_size")):
        c[key] = _mean(rec["eta"], rec[own])
    _table(m, a, b, c, rec)
    assert c["recrystallized_fraction"] == pytest.approx(a["recrystallized_fraction"], abs=0.03)
    assert c["grain_size"] == pytest.approx(a["grain_size"], rel=0.03)
    assert c["strain"] == pytest.approx(a["strain"], rel=0.03)
    assert "pyroll.jmak_recrystallization" not in sys.modules      # (b) ran apart


def test_with_pyrolls_plugin_loaded_hotrolls_values_win():
    """pyroll-jmak-recrystallization imported first, then hotroll.pyroll with MICROSTRUCTURE
    on (own process, one FE pass): the transport's out profile holds hotroll's means, not the
    value PyRolL's hook computes (its S355J2 set, which the material also names)."""
    kin = get_set(SET)
    args = {"strain": 0.28, "rate": 10.0, "T": 1313.15, "d0": D0, "duration": DURATION,
            "h0": 0.02, "h1": 0.016, "params": hm.jmak_parameters(kin),
            "fe": {"mesh": MESH, "set": SET, "h0": 0.02, "h1": 0.016, "R": R, "speed": SPEED,
                   "duration": DURATION, "T0": T0, "d0": D0, "props": PROPS}}
    both = _jmak(args)["both"]
    own = both["hotroll"]
    assert both["grain_size"] == pytest.approx(own["grain_size"], rel=1e-12)
    assert both["strain"] == pytest.approx(own["retained_strain"], rel=1e-12)
    assert both["recrystallized_fraction"] == pytest.approx(own["recrystallised_fraction"],
                                                            rel=1e-12)
    assert abs(both["jmak_grain_size"] / both["grain_size"] - 1.0) > 0.05
    assert both["pass_grain_size"] == D0


def test_a_pass_without_a_grain_size_is_refused_by_name():
    """... before the FE solve."""
    saved = hp.Config.MICROSTRUCTURE
    hp.Config.MICROSTRUCTURE = SET
    solves = hp.STATS["fe_solves"]
    try:
        seq = pr.PassSequence([_flat("P1", 0.016)])
        with pytest.raises(Exception) as info:
            seq.solve(_strip())
        chain, err = [], info.value
        while err is not None:
            chain.append(str(err))
            err = err.__cause__
        assert any("in_profile.grain_size" in msg for msg in chain), chain
        assert hp.STATS["fe_solves"] == solves
    finally:
        hp.Config.MICROSTRUCTURE = saved


def test_the_sequence_leaves_with_its_last_passs_values(rolled):
    """The sequence's out profile (issue 51) carries what its last pass's out profile got: the
    grain size, recrystallised fraction and arrays hotroll computed and the FE exit
    temperature (PyRolL copies only root hooks such as the strain onto a sequence's)."""
    p2 = rolled.units[-1]
    want = {**hm.pass_values(p2), "temperature": hp.solve(p2)["outlet_temperature_mean"]}
    for key, value in want.items():
        assert getattr(rolled.out_profile, key) == value == getattr(p2.out_profile, key), key
    assert rolled.out_profile.temperature < rolled.in_profile.temperature - 10.0


def test_off_changes_nothing(rolled):
    """MICROSTRUCTURE None (the default; tests/workflows/test_pyroll_*.py run with it): no
    values, no entry profile."""
    p1, t1, p2 = rolled.units
    saved = hp.Config.MICROSTRUCTURE
    hp.Config.MICROSTRUCTURE = None
    try:
        assert hm.transport_values(t1) is None and hm.pass_values(p1) is None
        assert hm.entry_plate(p2) == {}
        assert hm._transport_values(t1) is None and hm._pass_values(p1) is None
    finally:
        hp.Config.MICROSTRUCTURE = saved
