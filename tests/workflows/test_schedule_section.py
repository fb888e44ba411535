"""A [spread] schedule's temperature across the width (issue 53): the transport cools the
cross-section (model/interpass_section.py, the edges from the side too) and the next pass
enters with it (``spread.temperature_section``), its 3D pass carrying the difference from
mid-width's through the bite. tests/data/bar_spread_schedule.toml made thermal with C45's
Hensel-Spittel law and a 3 s transport (two passes of a 10 x 10 mm bar, one width layer).

Labels: [plumb] the hand-off recomputed from the files; [hand] signs; [estimate] the
streamlines' carrying, with its measured accuracy."""
from __future__ import annotations

import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

from hotroll.config.schedule import schedule_from_dict
from hotroll.model.interpass_section import cool_section
from hotroll.model.profile import ThicknessProfile
from hotroll.model.section import SectionProfile
from hotroll.workflows.schedule import pass_case, run_schedule
from hotroll.workflows.strip_state import StripState

DATA = Path(__file__).resolve().parents[1] / "data" / "bar_spread_schedule.toml"


def thermal_bar(**spread) -> dict:
    """The bar schedule, thermal, C45, a 3 s transport after pass 1 (``spread``: keys added
    to its [spread])."""
    d = tomllib.loads(DATA.read_text())
    d["material"] = {"law": "hensel-spittel", "grade": "C45", "density": 7800.0,
                     "specific_heat": 650.0, "conductivity": 30.0}
    for p in d["pass"]:
        p.pop("isothermal", None)
    d["pass"][0]["transport"] = {"duration": 3.0}
    d["spread"].update(spread)
    return d


@pytest.fixture(scope="module")
def rolled(tmp_path_factory):
    out = tmp_path_factory.mktemp("bar_section")
    sch = schedule_from_dict(thermal_bar())
    rows = run_schedule(sch, out, figure=False)
    return sch, rows, out


def _case(out: Path, row: dict) -> dict:
    return tomllib.loads((out / row["case"] / "case.toml").read_text())


def _summary(out: Path, row: dict) -> dict:
    return json.loads((out / row["case"] / "summary.json").read_text())


def test_the_next_pass_enters_with_the_section_its_transport_cooled(rolled):
    """[plumb] pass 2's ``spread.temperature_section`` is pass 1's outlet (its plane-strain
    exit profile at every width: pass 1 entered uniform) cooled for 3 s across its exit
    thickness and width (1e-9), the row's heat lost its own per m^2 of the cooled surface;
    its mid-width column is pass 2's plate profile. [hand] the
    edge colder than mid-width at every height; the row's edge temperature below its mean."""
    sch, rows, out = rolled
    first = _summary(out, rows[0])
    assert first["exit_temperature_offset"] is None            # entered uniform
    prof = first["exit_profile"]
    start = SectionProfile.across(ThicknessProfile(tuple(prof["eta"]),
                                                   tuple(prof["temperature"])))
    th = sch.thermal
    expect = cool_section(start, 0.5 * rows[0]["exit_thickness"], 0.5 * rows[0]["exit_width"],
                          3.0, sch.material.thermal_properties(),
                          th.law("surface", htc_air=th.htc_air, emissivity=th.emissivity),
                          th.ambient_temperature)
    case2 = _case(out, rows[1])
    got = SectionProfile.from_dict(case2["spread"]["temperature_section"])
    # the row's heat lost per m^2 of the quarter's cooled surface (half width + half height)
    assert rows[0]["transport_heat_lost"] == pytest.approx(
        expect.heat_lost / (0.5 * rows[0]["exit_width"] + 0.5 * rows[0]["exit_thickness"]),
        rel=1e-9)
    expect = expect.section
    assert got.eta == expect.eta and got.zeta == expect.zeta
    assert np.max(np.abs(got.array - expect.array)) <= 1e-9 * got.array.max()
    plate = np.asarray(case2["plate"]["temperature_profile"])
    assert np.max(np.abs(got.mid_width()(plate[:, 0]) - plate[:, 1])) <= 1e-9 * plate.max()
    assert np.all(got.array[:, -1] < got.array[:, 0] - 1.0)
    assert rows[0]["next_entry_temperature_edge"] < rows[0]["next_entry_temperature_mean"]
    # the next pass's entry mean is mid-width's (its plate temperature), the section's below
    assert rows[1]["entry_temperature_mean"] == pytest.approx(
        rows[0]["next_entry_temperature_mean"], rel=1e-9)
    assert rows[0]["next_entry_temperature_section_mean"] < rows[0]["next_entry_temperature_mean"]
    units = json.loads((out / "schedule.json").read_text())["units"]
    assert units["next_entry_temperature_edge"] == "K"


def test_the_second_pass_carries_the_edges_cooling_to_its_outlet(rolled):
    """[estimate] pass 2's outlet holds at the edge, at each height, the entry's difference
    from mid-width there (a streamline keeps its share of the flux below it), within 2 % of
    the entry's largest difference (measured 0.3 %: 0.04 K of 13.8 K); at mid-width 0 within
    the same; the next state's section is the exit profile plus it (schedule.json)."""
    sch, rows, out = rolled
    entry = SectionProfile.from_dict(_case(out, rows[1])["spread"]["temperature_section"])
    off = _summary(out, rows[1])["exit_temperature_offset"]
    eta, v = np.asarray(off["eta"]), np.asarray(off["values"])
    span = np.max(np.abs(entry.offset(entry.eta, np.ones(len(entry.eta)))))
    assert span > 5.0
    assert np.max(np.abs(v[:, -1] - entry.offset(eta, np.ones_like(eta)))) <= 0.02 * span
    assert np.max(np.abs(v[:, 0])) <= 0.02 * span
    handed = json.loads((out / "schedule.json").read_text())["profiles"][1]["exit"]
    sec = SectionProfile.from_dict(handed["temperature_section"])
    assert np.asarray(sec.zeta) == pytest.approx(off["zeta"])
    prof = _summary(out, rows[1])["exit_profile"]
    assert set(prof["eta"]) <= set(sec.eta)            # the exit profile's grading kept
    plane = np.interp(sec.eta, prof["eta"], prof["temperature"])
    add = np.stack([np.interp(sec.eta, eta, v[:, j]) for j in range(v.shape[1])], axis=1)
    assert np.max(np.abs(sec.array - plane[:, None] - add)) <= 1e-9 * plane.max()


def _state(sch) -> StripState:
    """A state whose edges are 60 K colder than mid-width (linear across the width)."""
    T = ThicknessProfile((0.0, 1.0), (1300.0, 1250.0))
    sec = SectionProfile((0.0, 1.0), (0.0, 0.5, 1.0),
                         ((1300.0, 1290.0, 1240.0), (1250.0, 1240.0, 1190.0)))
    return StripState(0.009, T, ThicknessProfile.uniform(0.1), width=0.0104, section=sec)


def test_what_a_pass_is_handed_depends_on_what_feels_it():
    """[plumb] the section is handed to a thermal pass whose law depends on the temperature;
    not to an isothermal pass nor under a law without temperature (nothing would change);
    an edge zone's interior takes mid-width's column (its cut is plane strain)."""
    sch = schedule_from_dict(thermal_bar())
    state = _state(sch)
    case = pass_case(sch, 1, state)
    assert SectionProfile.from_dict(
        case.spread.temperature_section.model_dump()) == state.section
    iso = thermal_bar()
    iso["pass"][1]["isothermal"] = True
    assert pass_case(schedule_from_dict(iso), 1, state).spread.temperature_section is None
    nh = thermal_bar()
    nh["material"] = {**nh["material"], "law": "norton-hoff", "K": 1.5e8, "m": 0.05}
    nh["material"].pop("grade")
    assert pass_case(schedule_from_dict(nh), 1, state).spread.temperature_section is None
    zone = pass_case(schedule_from_dict(thermal_bar(edge_zone=0.003, edge_layer=0.001)), 1,
                     state)
    sec = SectionProfile.from_dict(zone.spread.temperature_section.model_dump())
    cut = 1.0 - 0.003 / 0.0052
    assert sec.is_uniform_across(cut) and not sec.is_uniform_across()
    assert sec(np.array([0.0, 1.0]), np.array([1.0, 1.0])) == pytest.approx([1240.0, 1190.0])


def _exit(case, offset) -> dict:
    """A pass's summary as exit_state reads it: a chilled exit profile, graded to the
    surface, and the 3D outlet's offset (or None)."""
    eta = [0.0, 0.5, 0.8, 0.9, 0.95, 1.0]
    return {"exit_profile": {"eta": eta, "temperature": [1300.0, 1298.0, 1290.0, 1275.0,
                                                          1255.0, 1200.0],
                             "strain": [0.2] * 6},
            "exit_width": 0.0106, "exit_thickness": 0.008, "homogeneous_exit_strain": 0.2,
            "exit_temperature_offset": offset}


def test_the_exit_state_keeps_the_chill_and_carries_a_section_the_pass_did_not_take():
    """[plumb] the next section is the exit profile on its own grading (the chill's fine
    rows) plus the outlet's offset interpolated in eta; a thermal pass not handed the
    section (a law without T) carries the entry's difference from mid-width's unchanged, an
    isothermal pass the entry's section itself."""
    from hotroll.workflows.strip_state import exit_state

    sch = schedule_from_dict(thermal_bar())
    state = _state(sch)
    case = pass_case(sch, 1, state)
    offset = {"eta": [0.0, 1.0], "zeta": [0.0, 1.0], "values": [[0.0, -10.0], [0.0, -30.0]]}
    sec = exit_state(sch, case, _exit(case, offset), entry=state).section
    assert sec.eta == (0.0, 0.5, 0.8, 0.9, 0.95, 1.0)
    assert sec.array[:, 0] == pytest.approx([1300.0, 1298.0, 1290.0, 1275.0, 1255.0, 1200.0])
    assert sec.array[:, 1] - sec.array[:, 0] == pytest.approx(
        [-10.0, -20.0, -26.0, -28.0, -29.0, -30.0])
    nh = thermal_bar()
    nh["material"] = {**nh["material"], "law": "norton-hoff", "K": 1.5e8, "m": 0.05}
    nh["material"].pop("grade")
    nh_sch = schedule_from_dict(nh)
    carried = exit_state(nh_sch, pass_case(nh_sch, 1, state), _exit(case, None),
                         entry=state).section
    assert carried.offset(np.array([0.0, 1.0]), np.array([1.0, 1.0])) == pytest.approx(
        [-60.0, -60.0])
    iso = thermal_bar()
    iso["pass"][1]["isothermal"] = True
    iso_sch = schedule_from_dict(iso)
    assert exit_state(iso_sch, pass_case(iso_sch, 1, state), _exit(case, None),
                      entry=state).section is state.section


def _spy(monkeypatch, cls, name: str, keep) -> list:
    """The positional arguments of every call of ``cls.name`` whose keywords ``keep`` accepts
    (the call itself goes on)."""
    seen, original = [], getattr(cls, name)

    def spy(self, *args, **kw):
        if keep(kw):
            seen.append(args)
        return original(self, *args, **kw)

    monkeypatch.setattr(cls, name, spy)
    return seen


def test_the_exit_section_figure_draws_the_carried_offset(rolled, monkeypatch, tmp_path):
    """[plumb] fig_spread.png's exit section of pass 2: the outlet's offset (summary key
    exit_temperature_offset) drawn in the four quadrants as it is, over the outlet's heights
    (eta x the exit half thickness) and across to the exit half width (zeta 0 at mid-width)."""
    from matplotlib.axes import Axes

    from hotroll.results.figures.run_files import RunFiles
    from hotroll.results.figures.spread import fig_spread

    _, rows, out = rolled
    seen = _spy(monkeypatch, Axes, "pcolormesh", lambda kw: kw.get("cmap") == "RdBu_r")
    assert fig_spread(RunFiles(out / rows[1]["case"]), tmp_path / "f.png") is not None
    off = _summary(out, rows[1])["exit_temperature_offset"]
    v = np.asarray(off["values"])
    assert len(seen) == 4
    half = 0.5 * rows[1]["exit_width"]
    for Z, Y, drawn in seen:
        assert np.array_equal(np.asarray(drawn), v)
        assert np.all(np.asarray(Z)[:, 0] == 0.0)
        assert np.abs(np.asarray(Z)[:, -1]).mean() == pytest.approx(1e3 * half, rel=0.01)
        assert np.abs(np.asarray(Y)).max() == pytest.approx(0.5e3 * rows[1]["exit_thickness"],
                                                            rel=0.05)


def test_the_schedule_figure_draws_the_entry_edge_temperature(rolled, monkeypatch, tmp_path):
    """[plumb] schedule.png's temperature panel: the entry edge's temperature of pass 2 is
    the transport's row value (next_entry_temperature_edge, in degC) drawn at pass 2."""
    from matplotlib.axes import Axes

    from hotroll.results.schedule_plot import plot_schedule

    _, rows, _ = rolled
    seen = _spy(monkeypatch, Axes, "plot",
                lambda kw: kw.get("label") == "entry edge (thickness mean)")
    plot_schedule(rows, tmp_path / "s.png", width=rows[0]["entry_width"])
    assert len(seen) == 1
    x, y = seen[0][0], seen[0][1]
    assert list(x) == [2]
    assert y[0] == pytest.approx(rows[0]["next_entry_temperature_edge"] - 273.15, rel=1e-12)
