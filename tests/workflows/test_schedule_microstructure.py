"""Microstructure through a schedule (issue 33): the streamline histories of a pass against
slab theory and the temperatures' bounds, the retained-strain and grain-size profiles handed
on, the limits of a long hot and a short cold transport, the late pass's force against full
softening, the outputs with their units, and bad input.

The coarse two-pass schedule of tests/data/two_pass_schedule.toml (its own Hensel-Spittel
law, which hardens with strain), rolled with [microstructure] model = "hodgson_gibbs_cmn"."""
from __future__ import annotations

import copy
import csv
import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from casebuild import assert_schedule_refused, shared_scope

from hotroll.config.schedule import schedule_from_dict
from hotroll.model.microstructure import get_set
from hotroll.workflows.schedule import run_schedule

DATA = Path(__file__).resolve().parents[1] / "data" / "two_pass_schedule.toml"
HG = get_set("hodgson_gibbs_cmn")


def _schedule(model: bool = True, **transport) -> dict:
    d = tomllib.loads(DATA.read_text())
    tr = d["pass"][0]["transport"]
    del tr["strain_retained"]
    tr.update(transport)
    if model:
        d["microstructure"] = {"model": "hodgson_gibbs_cmn", "grain_size": 100e-6}
    return d


def _roll(d: dict, out: Path):
    rows = run_schedule(schedule_from_dict(d, "schedule.toml"), out, figure=False)
    return rows, json.loads((out / "schedule.json").read_text())


@pytest.fixture(scope=shared_scope)
def hot(tmp_path_factory):
    """A 20 s transport at 1100 degC: recrystallises fully."""
    out = tmp_path_factory.mktemp("ms_hot")
    return (*_roll(_schedule(), out), out)


@pytest.fixture(scope=shared_scope)
def cold(tmp_path_factory):
    """A 10 ms transport entering at 950 degC: keeps its strain; and the same schedule with
    full softening (strain_retained 0, no model)."""
    out = tmp_path_factory.mktemp("ms_cold")
    d = _schedule(duration=0.01)
    d["strip"]["temperature"] = 1223.15
    full = _schedule(False, duration=0.01, strain_retained=0.0)
    full["strip"]["temperature"] = 1223.15
    return _roll(d, out / "kinetics"), _roll(full, out / "full")


def test_streamline_histories_against_slab_theory(hot):
    """The centre streamline's pass strain is the homogeneous 2/sqrt(3) ln(h0/h1) (no shear
    on the symmetry line; within 2 %), the surface's larger (friction's shear); the strain-
    weighted mean temperature of the centre's streamline lies between the entry's 1373.15 K and
    its exit value (it only heats); every one between the roll's 350 K and the entry's plus
    the adiabatic heating's bound sigma eps / (rho c) < 10 K (sigma < 150 MPa, eps < 0.4)."""
    rows, js, out = hot
    rec = js["profiles"][0]["microstructure"]
    eps0 = 0.05
    homogeneous = 2.0 / math.sqrt(3.0) * math.log(0.1 / 0.08)
    strain = np.asarray(rec["strain"])
    assert strain[0] - eps0 == pytest.approx(homogeneous, rel=0.02)
    assert strain[-1] > strain[0]
    summary = json.loads((out / rows[0]["case"] / "summary.json").read_text())
    prof = summary["exit_profile"]
    T_mean = 1.0 / np.asarray(prof["inverse_temperature_mean"])
    T_exit = np.asarray(prof["temperature"])
    assert min(1373.15, T_exit[0]) - 0.5 < T_mean[0] < max(1373.15, T_exit[0]) + 0.5
    assert np.all(T_mean < 1373.15 + 10.0) and np.all(T_mean > 350.0)
    # Z on each streamline from its own means (the kinetics' input)
    Z = np.exp(np.asarray(prof["log_rate_mean"]) + HG.q_def / 8.314462618 * (1.0 / T_mean))
    assert np.allclose(rec["zener"], Z, rtol=1e-12)


def test_long_hot_transport_recrystallises_and_hands_on_grains(hot):
    """20 s at about 1100 degC: X = 1 everywhere, the next pass enters with zero strain (its
    case's strain profile) and the grain grown from the recrystallised size (finer than the
    100 um it entered with); the grain size profile reaches the second pass's record."""
    rows, js, out = hot
    rec = js["profiles"][0]["microstructure"]
    assert np.all(np.asarray(rec["recrystallised_fraction"]) > 1.0 - 1e-6)
    assert np.all(np.asarray(rec["retained_strain"]) < 1e-6) and all(rec["finished"])
    assert rows[0]["next_entry_strain_mean"] < 1e-6
    d = np.asarray(rec["grain_size"])
    assert np.all(d > np.asarray(rec["recrystallised_grain_size"])) and np.all(d < 100e-6)
    after = js["profiles"][0]["after_transport"]["grain_size_profile"]
    assert np.allclose([v for _, v in after], d)
    rec2 = js["profiles"][1]["microstructure"]
    assert np.allclose(rec2["grain_size_entry"], np.interp(rec2["eta"], rec["eta"], d))
    case2 = tomllib.loads((out / rows[1]["case"] / "case.toml").read_text())
    assert case2["plate"]["entry_strain"] < 1e-6


def test_short_cold_transport_keeps_the_strain_and_the_late_force_rises(cold):
    """10 ms at 950 degC: X < 1 % (t_0.5 of seconds, 65 ms where metadynamic), the retained strain
    lambda (1 - X) eps is the next pass's entry strain profile, and the second pass (whose law
    hardens with strain) needs more force than with full softening; the first pass, with the
    same input, the same force."""
    (rows, js), (rows_full, _) = cold
    rec = js["profiles"][0]["microstructure"]
    X = np.asarray(rec["recrystallised_fraction"])
    assert np.all(X < 0.01)
    assert np.allclose(rec["retained_strain"], (1.0 - X) * np.asarray(rec["strain"]),
                       rtol=1e-12)
    handed = js["profiles"][0]["after_transport"]["strain_profile"]
    assert np.allclose([v for _, v in handed], rec["retained_strain"])
    assert rows[0]["roll_force"] == pytest.approx(rows_full[0]["roll_force"], rel=1e-9)
    assert rows[1]["roll_force"] > 1.02 * rows_full[1]["roll_force"]


def test_outputs_and_units(hot):
    """microstructure.csv per pass; schedule.csv's columns; every new column's unit in
    schedule.json."""
    rows, js, out = hot
    table = list(csv.DictReader((out / rows[0]["case"] / "microstructure.csv").open()))
    assert len(table) == len(js["profiles"][0]["microstructure"]["eta"])
    assert {"eta", "recrystallised_fraction", "grain_size", "retained_strain", "zener",
            "critical_strain", "half_time"} <= set(table[0])
    for key in ("recrystallised_fraction_mean", "grain_size_surface", "retained_strain_mean",
                "drx_onset_share", "kinetics_temperature_min", "mechanism_centre"):
        assert key in rows[0] and key in js["units"]
    assert js["units"]["grain_size_mean"] == "m"
    assert (out / rows[1]["case"] / "microstructure.csv").is_file()     # the last pass too


def test_the_figure(hot, tmp_path):
    """microstructure.png from schedule.json's records (a PNG); none without a model."""
    from hotroll.results.figures.microstructure import plot_microstructure

    _, js, _ = hot
    assert plot_microstructure(js["profiles"], tmp_path / "m.png")
    assert (tmp_path / "m.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not plot_microstructure([{"pass": "P1"}], tmp_path / "none.png")
    assert not (tmp_path / "none.png").exists()


def test_table_columns_are_the_records_means(cold):
    """An identity of the bookkeeping: schedule.csv's means (over eta, trapezoids), surface and
    centre values are those of the per-eta record (microstructure.csv), for both the pass's
    and the transport's columns."""
    (rows, js), _ = cold
    rec = js["profiles"][0]["microstructure"]
    eta = np.asarray(rec["eta"])

    def mean(v):
        v = np.asarray(v, dtype=float)
        return float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(eta)))

    r = rows[0]
    for key in ("recrystallised_fraction", "grain_size", "retained_strain"):
        assert r[f"{key}_mean"] == pytest.approx(mean(rec[key]), rel=1e-12)
        assert r[f"{key}_surface"] == rec[key][-1] and r[f"{key}_centre"] == rec[key][0]
    assert r["drx_onset_share"] == pytest.approx(mean(rec["dynamic_onset"]), rel=1e-12)
    assert r["zener_log_mean"] == pytest.approx(mean(np.log(rec["zener"])), rel=1e-12)
    assert r["critical_strain_surface"] == rec["critical_strain"][-1]
    assert r["critical_strain_centre"] == rec["critical_strain"][0]
    assert r["kinetics_strain_centre"] == rec["strain"][0]
    assert r["kinetics_strain_surface"] == rec["strain"][-1]
    assert r["kinetics_extrapolated_share"] == pytest.approx(mean(rec["extrapolated"]),
                                                             rel=1e-12, abs=1e-15)
    assert r["kinetics_temperature_min"] == min(rec["coldest"])
    assert r["mechanism_surface"] == ("metadynamic" if rec["metadynamic"][-1] else "static")
    assert r["next_entry_strain_mean"] == pytest.approx(r["retained_strain_mean"], rel=1e-12)


def test_bad_input_named():
    d = _schedule()
    bad = copy.deepcopy(d)
    bad["microstructure"]["model"] = "sellars"
    assert_schedule_refused(bad, "microstructure.model: unknown set 'sellars'")
    bad = copy.deepcopy(d)
    del bad["microstructure"]["grain_size"]
    assert_schedule_refused(bad, "microstructure.grain_size: needed with a model")
    bad = copy.deepcopy(d)
    bad["microstructure"]["grain_size"] = 5e-3
    assert_schedule_refused(bad, "microstructure.grain_size: must be in")
    bad = copy.deepcopy(d)
    bad["pass"][0]["transport"]["strain_retained"] = 0.5
    assert_schedule_refused(bad, "pass[1].transport.strain_retained: not with microstructure")
    bad = copy.deepcopy(d)
    bad["strip"]["temperature"] = 1000.0
    assert_schedule_refused(bad, "strip.temperature: 1000.00..1000.00 K outside the set")
    bad = copy.deepcopy(d)
    bad["material"] = {"law": "hensel-spittel", "grade": "C45", "density": 7600.0,
                       "specific_heat": 650.0, "conductivity": 30.0}
    assert_schedule_refused(bad, "material.grade 'C45' has none")
