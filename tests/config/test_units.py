"""Quantities with units in the input files (issue 51, item 2; hotroll/config/units.py): every
field with a unit takes its units and refuses another dimension naming the field; a case
written in engineers' units is the same case, bit for bit, as the one written in SI."""
from __future__ import annotations

import copy
import json
import math
import re
import tomllib
from decimal import Decimal
from pathlib import Path

import pytest
from casebuild import EXAMPLE1_COARSE

from hotroll.config.base import Section, _number_field
from hotroll.config.case import CaseError, case_from_dict
from hotroll.config.units import UnitError, takes_units, to_si
from hotroll.examples import example_path

#: (SI unit, text, value) worked by hand: 1 in = 25.4 mm, 1 rpm = 2 pi/60 rad/s, degF =
#: (F - 32) 5/9 + 273.15 K, 1 GiB = 2^30 B
BY_HAND = [
    ("m", "6 mm", 0.006), ("m", "6mm", 0.006), ("m", "2 in", 0.0508), ("m", "0.35 m", 0.35),
    ("m", "64.938 mm", 0.064938),
    ("K", "1000 degC", 1273.15), ("K", "1000 °C", 1273.15), ("K", "1832 degF", 1273.15),
    ("K", "1273.15 K", 1273.15),
    ("Pa", "120 MPa", 120e6), ("Pa", "12 kN/cm^2", 120e6), ("Pa", "210 GPa", 210e9),
    ("m/s", "300 m/min", 5.0), ("m/s", "18 km/h", 5.0),
    ("rad/s", "60 rpm", 2 * math.pi), ("rad/s", "1.5 rad/s", 1.5),
    ("s", "2 min", 120.0), ("s", "250 ms", 0.25),
    ("N/m", "5 kN/mm", 5e6), ("N/m", "5 MN/m", 5e6),
    ("1/s", "10 /s", 10.0), ("1/s", "10 1/s", 10.0),
    ("kg/m^3", "7.85 g/cm^3", 7850.0), ("J/(kg K)", "0.65 kJ/(kg K)", 650.0),
    ("W/(m K)", "0.28 W/(cm K)", 28.0), ("W/(m^2 K)", "20 kW/(m^2 K)", 2e4),
    ("1/degC", "-0.0025 1/K", -0.0025), ("1/degC", "-0.0025 1/degC", -0.0025),
    ("B", "2 GiB", 2.0**31),
]


@pytest.mark.parametrize("unit, text, value", BY_HAND)
def test_a_quantity_is_its_si_value(unit, text, value):
    assert to_si(text, unit) == pytest.approx(value, rel=1e-15)


def _schema_units() -> set[str]:
    def walk(c):
        for s in c.__subclasses__():
            yield s
            yield from walk(s)

    import hotroll.config.case  # noqa: F401  (every section defined)
    import hotroll.config.schedule  # noqa: F401
    import hotroll.config.study  # noqa: F401

    units = set()
    for cls in walk(Section):
        for f in cls.model_fields.values():
            unit = (f.json_schema_extra or {}).get("unit") if isinstance(f.json_schema_extra,
                                                                          dict) else None
            if unit and _number_field(f.annotation)[0]:
                units.add(unit)
    return units


def test_every_unit_of_the_schema_is_read_or_said_to_be_a_number_only():
    """Each unit a number field of the case, schedule or study files has: pint reads it (and a
    text of it was checked by hand above), or it is a law's own unit (Pa s^m), numbers only."""
    units = _schema_units()
    assert "m" in units and "K" in units                 # the walk sees the schema
    checked = {u for u, _, _ in BY_HAND}
    assert {u for u in units if takes_units(u)} <= checked
    for u in units - checked:
        with pytest.raises(UnitError, match="a number"):
            to_si("1 Pa", u)


@pytest.mark.parametrize("unit, text, why", [
    ("m", "6 s", "is not a length"), ("K", "1000 m", "is not a temperature"),
    ("Pa", "5 m/s", "is not a pressure"), ("m", "6 mmm", "unknown unit 'mmm'"),
    ("m", "6", "a number, or a number with a unit"), ("m", "6 mm + 1 cm", "cannot read"),
    ("rad/s", "5 m/s", "is not a angular speed"),
])
def test_a_wrong_quantity_is_refused_saying_why(unit, text, why):
    with pytest.raises(UnitError, match=re.escape(why)):
        to_si(text, unit)


def test_a_wrong_dimension_is_refused_naming_the_field():
    d = tomllib.loads(example_path("thermal_pass").read_text())
    cases = {"pass.roll_radius": "350 s", "plate.temperature": "1000 mm",
             "pass.roll_angular_velocity": "5 m/s", "thermal.htc_contact": "2 MPa",
             "material.density": [["900 degC", "7.6 kg"], ["1200 degC", "7.5 g/cm^3"]]}
    for dotted, value in cases.items():
        bad = copy.deepcopy(d)
        sec, key = dotted.split(".")
        bad[sec][key] = value
        with pytest.raises(CaseError) as e:
            case_from_dict(bad)
        assert len(e.value.problems) == 1, e.value.problems
        assert e.value.problems[0].startswith(f"{dotted}: "), e.value.problems
        assert "is not a" in e.value.problems[0]


def test_a_range_error_quotes_the_text_given():
    d = tomllib.loads(example_path("hot_strip_finishing").read_text())
    d["plate"]["temperature"] = "-300 degC"
    with pytest.raises(CaseError) as e:
        case_from_dict(d)
    assert e.value.problems == ["plate.temperature: must be > 0 [K], got -26.85 (from "
                                "'-300 degC')"]


#: the engineer's unit of each SI unit, and its factor as a decimal (exact in Decimal)
ENGINEER = {"m": ("mm", Decimal(1000)), "Pa": ("MPa", Decimal("1e-6")),
            "m/s": ("mm/s", Decimal(1000)), "s": ("ms", Decimal(1000)),
            "N/m": ("kN/mm", Decimal("1e-6")), "kg/m^3": ("g/cm^3", Decimal("0.001")),
            "J/(kg K)": ("kJ/(kg K)", Decimal("0.001")),
            "W/(m K)": ("W/(cm K)", Decimal("0.01")),
            "W/(m^2 K)": ("kW/(m^2 K)", Decimal("0.001")), "rad/s": ("mrad/s", Decimal(1000))}


def _engineer(value, unit: str):
    """``value`` (SI, a TOML number) as an engineer writes it: the decimal digits moved, or
    degC; a table of pairs [T, value] column by column."""
    if isinstance(value, list):
        return [_engineer(v, unit) for v in value]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return value
    if unit == "K":
        return f"{Decimal(repr(float(value))) - Decimal('273.15')} degC"
    if unit in ENGINEER:
        name, factor = ENGINEER[unit]
        return f"{Decimal(repr(float(value))) * factor} {name}"
    return value


def _in_engineers_units(d: dict) -> tuple[dict, int]:
    """Every number of a case dict with a unit in ENGINEER or K rewritten as text."""
    from hotroll.config.base import fields_of
    from hotroll.config.case import Case

    out, n = copy.deepcopy(d), 0
    for sec, table in out.items():
        if not isinstance(table, dict) or sec not in fields_of(Case):
            continue
        model = fields_of(Case)[sec].annotation
        model = next((a for a in getattr(model, "__args__", (model,)) if a is not type(None)),
                     model)
        fields = fields_of(model)
        for key, value in table.items():
            extra = fields[key].json_schema_extra if key in fields else None
            if not isinstance(extra, dict):
                continue
            unit = extra.get("unit", "")
            columns = extra.get("columns")
            if key in ("density", "specific_heat", "conductivity") and isinstance(value, list):
                columns = ("K", unit)
            if columns and isinstance(value, list):
                table[key] = [[_engineer(x, u) for x, u in zip(row, columns)] for row in value]
            else:
                table[key] = _engineer(value, unit)
            n += table[key] != value
    return out, n


@pytest.mark.parametrize("name", sorted(p.stem for p in Path(example_path("example1")).parent
                                        .glob("*.toml")))
def test_a_bundled_case_in_engineers_units_is_the_same_case_bit_for_bit(name):
    d = tomllib.loads(example_path(name).read_text())
    eng, changed = _in_engineers_units(d)
    assert changed >= 4, name                     # lengths at least
    assert case_from_dict(eng).model_dump() == case_from_dict(d).model_dump()


def test_six_mm_and_0_006_give_the_same_summary_bit_for_bit(tmp_path):
    """Example 1's coarse pass written in mm (and mrad/s) solves to the same summary, every
    figure equal (the wall times aside)."""
    from hotroll.workflows.runner import run_case

    eng, changed = _in_engineers_units(EXAMPLE1_COARSE)
    assert changed >= 5
    assert eng["pass"]["roll_radius"] == "600.0 mm"
    summaries = []
    for k, d in enumerate((EXAMPLE1_COARSE, eng)):
        run_case(case_from_dict(d), tmp_path / str(k), resume=False)
        s = json.loads((tmp_path / str(k) / "summary.json").read_text())
        summaries.append({k: v for k, v in s.items()
                          if "wall_time" not in k and not k.startswith("estimated_")
                          and k != "solver_threads"})
    assert summaries[0]["converged"]
    assert summaries[1] == summaries[0]


def test_the_readmes_first_case_is_the_bundled_pass():
    """The README's first case, written with units, is the bundled hot_strip_finishing to the
    last bit (the README's own words)."""
    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    block = readme.split("## A first case", 1)[1].split("```toml", 1)[1].split("```", 1)[0]
    written = tomllib.loads(block)
    assert written["pass"]["roll_radius"] == "350 mm"
    bundled = tomllib.loads(example_path("hot_strip_finishing").read_text())
    for sec in written:
        for key, value in written[sec].items():
            if isinstance(value, str) and key not in ("law", "grade"):
                assert bundled[sec][key] != value                # the file says it in SI
    keep = {k: bundled[k] for k in written}
    assert case_from_dict(written).model_dump() == case_from_dict(keep).model_dump()


@pytest.mark.parametrize("unit", ["m", "K", "Pa", "rad/s", "N/m", "B", "1/degC"])
def test_the_engineers_unit_shown_is_pints_conversion(unit):
    """``shown`` (plain factors, no pint on a run's path) against pint's own conversion of
    the same value back to SI."""
    from hotroll.config.units import ENGINEERING, shown

    value = 1234.5678
    text = shown(value, unit)
    assert text.endswith(" " + ENGINEERING[unit][0])
    assert to_si(text, unit) == pytest.approx(value, rel=1e-5)


def test_a_study_range_in_degc_steps_by_a_temperature_difference():
    """[vary] plate.temperature = {start = "900 degC", stop = "1100 degC", step = "50 degC"}:
    five temperatures 50 K apart (a step is a difference, not 323.15 K), and a list in degC
    the same values."""
    from hotroll.config.study import Study
    from hotroll.examples import study_path

    d = tomllib.loads(study_path("af_study").read_text())
    d["vary"] = {"plate.temperature": {"start": "900 degC", "stop": "1100 degC",
                                       "step": "50 degC"}}
    values = Study.model_validate(d).vary["plate.temperature"]
    assert values == pytest.approx([1173.15, 1223.15, 1273.15, 1323.15, 1373.15], abs=1e-9)
    d["vary"] = {"plate.temperature": ["900 degC", "950 degC"]}
    assert Study.model_validate(d).vary["plate.temperature"] == [1173.15, 1223.15]
