"""The out profiles the PyRolL plugin leaves (issue 51 item 5; hotroll/pyroll_out_profile.py,
hotroll/pyroll_flow_stress.py): PyRolL's documented flat example (tests/data/pyroll_flat_example.py:
the Freiberg notebook's first two passes and the transport between them) rolled without the
plugin (pyroll-core alone, in its own process) and with it (here). Every out-profile property
both set is checked: the plugin's against the FE summary of the pass (the temperature as the
section average of the FE exit profile, to 1e-6 K), PyRolL's geometry and bookkeeping against
their definitions on hotroll's width, the rest equal between the runs; the sequence's out
profile is its last unit's. The profile's constant ``flow_stress`` is the one rolled (the force
doubles with it). With pyroll-integral-thermal loaded (two more processes; skipped where it is
not installed) PyRolL's own cooling between the passes is left as it is. A pass hotroll leaves
to PyRolL says why at WARNING."""
from __future__ import annotations

import importlib.util
import json
import logging
import math
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest
from casebuild import shared_scope

pr = pytest.importorskip("pyroll.core", reason="the [pyroll] extra (scripts/setup.sh installs it)")

import hotroll.pyroll as hp  # noqa: E402
from hotroll.model.flow_stress.norton_hoff import NortonHoffStress  # noqa: E402
from hotroll.model.interpass import cool  # noqa: E402
from hotroll.model.thermal_properties import ThermalProperties  # noqa: E402

EXAMPLE = Path(__file__).resolve().parents[1] / "data" / "pyroll_flat_example.py"
_spec = importlib.util.spec_from_file_location("pyroll_flat_example", EXAMPLE)
ex = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ex)

THERMAL = importlib.util.find_spec("pyroll.integral_thermal") is not None
NO_THERMAL = ("pyroll-integral-thermal is not installed: it is in the [pyroll-compare] extra, "
              "not yet in [test]")


def _process(*flags) -> dict:
    """The example in a fresh process (tests/data/pyroll_flat_example.py) with ``flags``."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(Path(hp.__file__).resolve().parents[1]), os.environ.get("PYTHONPATH", "")]))
    run = subprocess.run([sys.executable, str(EXAMPLE), *flags], check=True,
                         capture_output=True, text=True, env=env)
    return json.loads(run.stdout)


@pytest.fixture(scope=shared_scope)
def rolled():
    """(pyroll-core alone, with the plugin): the example's out profiles."""
    hp.Config.MESH = dict(ex.MESH)
    hp.Config.SOLVER = {"threads": 1}
    hp.reset_stats()
    return _process(), ex.run(plugin=True)


def _section_mean(values, eta) -> float:
    """The average over the half thickness of a profile linear between its eta points."""
    values, eta = np.asarray(values, float), np.asarray(eta, float)
    return float(np.sum(0.5 * (values[1:] + values[:-1]) * np.diff(eta)) / (eta[-1] - eta[0]))


def _fe_means(row) -> tuple[float, float]:
    """(temperature K, strain) the pass's FE exit: the exit profile's section averages; the
    strain homogeneous, e0 + 2/sqrt3 ln(h0/h1), for a law without strain (no strain field)."""
    prof = row["hotroll"]["exit_profile"]
    if prof["strain"] is None:
        case = tomllib.loads(row["hotroll"]["case_toml"])
        h0, h1 = case["pass"]["entry_thickness"], case["pass"]["exit_thickness"]
        strain = row["in"]["strain"] + 2.0 / math.sqrt(3.0) * math.log(h0 / h1)
    else:
        strain = _section_mean(prof["strain"], prof["eta"])
    return _section_mean(prof["temperature"], prof["eta"]), strain


def _approx(x, rel=1e-12, abs=0.0):
    return pytest.approx(x, rel=rel, abs=abs)


def _check_pass(key, a, b, row):
    """A roll pass's out-profile property ``key``: ``a`` PyRolL's, ``b`` with the plugin."""
    out, inp = row["out"], row["in"]
    width, gap = inp["computed width"], ex.GAPS[0 if row["label"].endswith(" I") else 1]
    T, strain = _fe_means(row)
    area = width * gap                   # the strip leaves the flat gap as a rectangle
    checks = {
        "temperature": lambda: b == _approx(T, rel=0.0, abs=1e-6),          # K
        "strain": lambda: b == _approx(strain, rel=1e-9),
        "velocity": lambda: b == _approx(row["hotroll"]["exit_velocity"]),  # m/s
        "computed width": lambda: b == width,                                # plane strain
        "computed height": lambda: b == _approx(gap),
        "cross_section": lambda: (b["area"] == _approx(area)
                                  and b["bounds"] == _approx([-width / 2, -gap / 2,
                                                              width / 2, gap / 2])),
        "technologically_orientated_cross_section": lambda: b == out["cross_section"],
        "filling_ratio": lambda: b == _approx(width / row["usable_width"]),
        "filling_error": lambda: b == _approx(width / row["usable_width"] - 1.0),
        "cross_section_filling_ratio": lambda: b == _approx(area / (row["usable_width"] * gap)),
        "cross_section_error": lambda: b == _approx(area / (row["usable_width"] * gap) - 1.0),
        "t": lambda: b == _approx(inp["t"] + row["duration"]),               # s
        "length": lambda: b * out["cross_section"]["area"] == _approx(
            inp["length"] * inp["cross_section"]["area"]),                   # volume kept
    }
    if key in checks:
        return checks[key]()
    return b == a            # classifiers, material, density, specific heat, flow stress


def test_every_out_profile_value_both_set(rolled):
    """Per unit: the plugin sets every property PyRolL sets; those hotroll computes equal the
    FE summary (temperature: the exit profile's section average), PyRolL's geometry and times
    follow from them by their definitions, the rest equal PyRolL's own."""
    alone, plugin = rolled
    for a_row, b_row in zip(alone["units"], plugin["units"], strict=True):
        a, b = a_row["out"], b_row["out"]
        assert set(a) <= set(b), (b_row["label"], set(a) - set(b))
        for key in sorted(set(a) & set(b)):
            if b_row["type"] == "Transport":
                ok = _check_transport(key, a[key], b[key], b_row)
            else:
                ok = _check_pass(key, a[key], b[key], b_row)
            assert ok, (b_row["label"], key, a[key], b[key])
    # the FE's exit thickness is the gap within 1e-4: PyRolL's height (the gap) is kept
    for row in plugin["units"][::2]:
        gap = ex.GAPS[0 if row["label"].endswith(" I") else 1]
        assert abs(row["hotroll"]["exit_thickness"] / gap - 1.0) < 1e-4


def _check_transport(key, a, b, row):
    """A plain transport after a hotroll pass: hands on what the pass set, cooled by hotroll's
    interpass model (pyroll-core alone has no transport cooling)."""
    inp = row["in"]
    if key == "temperature":
        want = cool([0.0], [inp["temperature"]], 0.5 * inp["computed height"], ex.DURATION,
                    ThermalProperties(7.5e3, 690.0, hp.Config.PROPERTIES["conductivity"]),
                    hp.Config.THERMAL["htc_air"], hp.Config.THERMAL["emissivity"],
                    pr.Transport(duration=1.0).environment_temperature).mean  # PyRolL's 293 K
        return b == _approx(want) and 5.0 < inp["temperature"] - b < 30.0
    if key == "t":
        return b == _approx(inp["t"] + ex.DURATION)
    if key == "strain":
        return b == a == 0          # PyRolL's transport recrystallises fully
    if key in inp:
        return b == inp[key]        # the pass's out profile handed on
    return b == a


def test_the_sequence_leaves_with_its_last_units_out_profile(rolled):
    """The bug of issue 51: the sequence's out temperature was the entry temperature. Now every
    value of the sequence's out profile is its last unit's, the temperature the last pass's FE
    exit mean (section average) to 1e-6 K, 80 K below the entry."""
    _, plugin = rolled
    last, seq = plugin["units"][-1], plugin["sequence"]
    assert seq == {k: last["out"][k] for k in seq}
    assert set(seq) >= {"temperature", "strain", "cross_section", "t"}
    T, strain = _fe_means(last)
    assert seq["temperature"] == pytest.approx(T, rel=0.0, abs=1e-6)
    assert seq["strain"] == pytest.approx(strain, rel=1e-9)
    assert 40.0 < ex.profile().temperature - seq["temperature"] < 150.0


def test_the_given_flow_stress_is_rolled(rolled, tmp_path):
    """The profile's flow_stress = 100 MPa (and its material C45, a hotroll grade): each pass is
    rolled as Norton-Hoff's law with m = Config.FLOW_STRESS_RATE_EXPONENT whose stress at the
    pass's mean strain rate U/l_c 2/sqrt3 ln(h0/h1) is 100 MPa, not the grade's law; with
    200 MPa given, the rigid-plastic strip under a rigid roll needs twice the force and torque
    (Norton-Hoff's K scales the whole solution)."""
    _, plugin = rolled
    for row in plugin["units"][::2]:
        fit = row["hotroll"]["flow_stress_fit"]
        case = tomllib.loads(row["hotroll"]["case_toml"])
        p = case["pass"]
        U, h0, h1 = p["roll_angular_velocity"] * p["roll_radius"], p["entry_thickness"], \
            p["exit_thickness"]
        rate = U / math.sqrt(p["roll_radius"] * 0.5 * (h0 - h1)) * 2 / math.sqrt(3) * math.log(
            h0 / h1)
        assert fit["source"] == "in_profile.flow_stress" and fit["strain_rate"] == _approx(rate)
        mat = case["material"]
        assert mat["law"] == "norton-hoff" and "grade" not in mat
        assert mat["m"] == hp.Config.FLOW_STRESS_RATE_EXPONENT == 0.1
        assert NortonHoffStress(mat["K"], mat["m"]).sigma(0.0, rate) == _approx(100e6)

    def one_pass(sigma):
        rp = pr.RollPass(label=f"sigma {sigma:g}", gap=ex.GAPS[0], velocity=0.3, rotation=False,
                         roll=pr.Roll(groove=pr.FlatGroove(usable_width=ex.USABLE_WIDTH),
                                      nominal_radius=0.15))
        ip = ex.profile()
        ip.flow_stress = sigma
        rp.solve(ip)
        return rp

    low, high = one_pass(100e6), one_pass(200e6)
    assert high.roll_force / low.roll_force == pytest.approx(2.0, rel=1e-7)   # 1.3e-9 off
    assert high.roll.roll_torque / low.roll.roll_torque == pytest.approx(2.0, rel=1e-7)


def test_a_pass_left_to_pyroll_says_why_at_warning(caplog):
    """A flat pass hotroll cannot roll is left to PyRolL's models with the reason at WARNING,
    once: an unusable flow stress, no flow stress and no hotroll grade, a bar (not a strip)."""
    roll = pr.Roll(groove=pr.FlatGroove(usable_width=0.3), nominal_radius=0.15)
    cases = {
        "the profile's flow_stress -1.0 (Pa) is no finite positive number":
            pr.Profile.box(height=0.02, width=0.25, temperature=1373.15, material="C45",
                           flow_stress=-1.0),
        "no flow stress: neither a flow_stress (Pa) nor a flow_stress_function":
            pr.Profile.box(height=0.02, width=0.25, temperature=1373.15, material="AISI 304"),
        "fills 75% of its bounding box: no flat strip":
            pr.Profile.hexagon(height=0.03, temperature=1373.15, flow_stress=100e6),
    }
    for i, (why, ip) in enumerate(cases.items()):
        rp = pr.RollPass(label=f"left {i}", roll=roll, gap=0.015, velocity=1.0)
        rp.init_solve(ip)
        caplog.clear()
        with caplog.at_level(logging.INFO, logger="hotroll.pyroll"):
            assert not hp.handles(rp) and not hp.handles(rp)
        told = [r for r in caplog.records if r.name == "hotroll.pyroll"]
        assert len(told) == 1 and told[0].levelno == logging.WARNING, told
        assert why in told[0].getMessage() and f"'left {i}'" in told[0].getMessage()


@pytest.mark.skipif(not THERMAL, reason=NO_THERMAL)
def test_pyrolls_own_cooling_between_passes_is_untouched():
    """With pyroll-integral-thermal (PyRolL's lumped heat; it makes the out temperature a root
    hook) loaded beside the plugin, each in fresh processes: the passes leave at hotroll's FE
    exit mean, the transport cools by integral-thermal's own model (a lone PyRolL Transport
    from the same in state gives the same, to 1e-6 K), the sequence leaves with its last
    unit's temperature; without the plugin integral-thermal's numbers are PyRolL's alone."""
    alone, plugin = _process("--thermal"), _process("--thermal", "--plugin")
    for run in (alone, plugin):
        tr = run["units"][1]
        assert tr["out"]["temperature"] == pytest.approx(run["lone_transport_temperature"],
                                                         rel=0.0, abs=1e-6)
        assert 5.0 < tr["in"]["temperature"] - tr["out"]["temperature"] < 40.0
        assert run["sequence"]["temperature"] == run["units"][-1]["out"]["temperature"]
    for row in plugin["units"][::2]:
        T, _ = _fe_means(row)
        assert row["out"]["temperature"] == pytest.approx(T, rel=0.0, abs=1e-6)
    # hotroll's interpass model would have cooled differently (its 1D slab, faces only)
    tr = plugin["units"][1]
    mine = cool([0.0], [tr["in"]["temperature"]], 0.5 * tr["in"]["computed height"],
                ex.DURATION, ThermalProperties(7.5e3, 690.0, 28.0), 15.0, 0.8, 293.15).mean
    assert abs(mine - tr["out"]["temperature"]) > 1.0
