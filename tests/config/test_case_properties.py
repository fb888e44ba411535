"""Property-based tests over the case schema (issue 18, hypothesis).

1. Every invalid case is refused with a ``CaseError`` naming its field, before anything is
   computed. The broken fields are drawn from the schema itself (every key of every section of
   ``Case``, with its words and type), so a key added later is covered without editing this
   file; a number goes outside the range its description states (the text the user reads,
   checked to be the range enforced). Values outside the range, NaN and infinities, text and
   booleans for numbers, unknown words, unknown keys and sections, missing required keys, a
   table where a number goes; then the rules between fields (exit >= entry thickness, the roll
   that cannot bite, a plate or mesh too coarse for the bite, a friction or flow-stress
   parameter of another law, a Hensel-Spittel law without rate sensitivity at the plate
   temperature, [thermal] without the strip's properties, ...). Through ``hotroll run`` on a
   TOML file the same cases end with exit code 2, the mesher never called.
2. Every valid case in a bounded range (R/h0 5-100, reductions 5-50 %, m 0.02-1, roll speeds
   0.1-30 rad/s, K 1-1e9 Pa s^m, each friction law with its parameter) solved by the steady
   solver on a coarse mesh either converges with its conservation checks closing (mass flux in
   = out, plastic + friction + penalty power = roll power, roll power = torque x omega, force
   > 0, forward slip and neutral angle in their physical ranges), or ends with a nonzero exit
   code and the reason it states - never with an exception. K x 1000 multiplies every force
   and power by 1000 and leaves the kinematics unchanged.

Examples are drawn reproducibly (``derandomize``; no shrinking of the solves, a case costs
seconds); corners of the range are run as well. The flux tolerance is 2 %: the coarse runs of
test_rolling.py and test_steady.py stay below 1 % (measured 0.6 % on h = 0.02 m), the meshes
here have 4 elements through the exit half-thickness; the power balance holds to the nonlinear
tolerance (measured <= 0.7 %), 2 % as in test_steady.py. Both are the runner's own
``CONSERVATION_TOL``, beyond which a run ends with exit code 7. What the tests found is in
docs/testing.md (the row of this file).
"""
from __future__ import annotations

import copy
import json
import math
import re
import tempfile
import types
import typing
from pathlib import Path
from unittest import mock

import annotated_types as at
import pytest
from hypothesis import HealthCheck, Phase, example, given, settings
from hypothesis import strategies as st

import hotroll
from hotroll.config import case as C
from hotroll.results.outcome import EXIT_CODES, exit_code
from hotroll.workflows.runner import CONSERVATION_TOL

# ------------------------------------------------------------------------------------------------
# 1. invalid cases
# ------------------------------------------------------------------------------------------------

#: A valid case with every section and nearly every key set (Norton-Hoff, Coulomb, [thermal],
#: entry profiles), so that breaking any one key leaves everything else valid.
BASE: dict = {
    "name": "properties",
    "pass": {"roll_radius": 0.6, "entry_thickness": 0.5, "exit_thickness": 0.4,
             "roll_angular_velocity": 1.0, "roll_axis_x": 1.0, "back_tension": 1e3,
             "front_tension": 2e3, "width": 1.5, "mill_modulus": 5e9},
    "plate": {"length": 1.0, "temperature": 1373.15, "entry_strain": 0.1,
              "free_surface": "traced", "temperature_profile": [[0.0, 1373.15], [1.0, 1300.0]],
              "strain_profile": [[0.0, 0.1], [1.0, 0.2]]},
    "material": {"law": "norton-hoff", "K": 1e6, "m": 0.2, "eps0": 1e-4, "density": 7800.0,
                 "specific_heat": [[300.0, 450.0], [1400.0, 650.0]], "conductivity": 30.0},
    "friction": {"law": "coulomb", "mu": 0.3, "v_reg": 1e-4, "a_f_max": 1e6},
    "mesh": {"h_contact": 0.02, "h_far": 0.05, "grading": 0.3},
    "solver": {"method": "steady", "nonlinear": "newton", "tolerance": 1e-5,
               "max_iterations": 20, "end_time": 1.0, "time_step": 1e-3,
               "steady_tolerance": 2e-3, "max_steps": 1000, "wall_time_limit": 60.0,
               "checkpoint_every": 25, "threads": 1, "steady_entry_length": 0.3,
               "steady_exit_length": 0.3, "exit_pressure_correction": True},
    "contact": {"method": "multiplier", "unilateral": False, "strip_youngs_modulus": 1.2e11,
                "strip_poissons_ratio": 0.3},
    "roll": {"model": "rigid", "youngs_modulus": 210e9, "poissons_ratio": 0.3,
             "relaxation": 1.0, "tolerance": 1e-4},
    "output": {"figures": False, "vtk": False},
    "thermal": {"taylor_quinney": 0.9, "friction_heat_to_strip": 0.5, "htc_contact": 2e4,
                "roll_temperature": 350.0, "htc_air": 20.0, "emissivity": 0.8,
                "ambient_temperature": 293.15, "mesh_refinement": 1.0},
}
#: the [spread] section, in the base of its own keys only (it refuses an asymmetric pass)
SPREAD = {"edge_layer": 0.02, "growth": 1.2, "largest_layer": 0.08, "max_rounds": 30}
#: an entry temperature over the cross-section whose mid-width column is BASE's plate profile
SECTION = {"eta": [0.0, 1.0], "zeta": [0.0, 0.5, 1.0],
           "values": [[1373.15, 1370.0, 1340.0], [1300.0, 1295.0, 1270.0]]}
HS_MATERIAL = {"law": "hensel-spittel", "A": 1e8, "m1": -0.003, "m2": 0.1, "m3": 0.15,
               "m4": -0.001, "m5": 1e-4, "m7": -0.1, "m8": 1e-5, "m9": 0.01}
#: Keys active only under another law: the base the key is broken in.
LAW_OF = {("friction", "a_f"): {"law": "viscoplastic", "a_f": 5.0},
          ("friction", "factor"): {"law": "tresca", "factor": 0.8}}


def base_for(section: str, key: str) -> dict:
    """A valid case in which ``section.key`` is in force."""
    d = copy.deepcopy(BASE)
    if section == "spread":
        d["spread"] = dict(SPREAD)
    if section == "spread.temperature_section":     # its mid-width column the plate's profile
        d["spread"] = {**SPREAD, "temperature_section": dict(SECTION)}
        d["material"] = {**HS_MATERIAL, **{k: d["material"][k] for k in (
            "density", "specific_heat", "conductivity")}, "eps0": 1e-4}
    if (section, key) in LAW_OF:
        d["friction"] = {**LAW_OF[section, key], "v_reg": 1e-4, "a_f_max": 1e6}
    if section.startswith("friction.") and ("friction", key) in LAW_OF:   # a roll's own
        table(d, section).update(LAW_OF["friction", key])
    if section == "material" and (key in HS_MATERIAL or key == "grade"):
        props = {k: d["material"][k] for k in ("density", "specific_heat", "conductivity")}
        hs = {"law": "hensel-spittel", "grade": "S355J2"} if key == "grade" else HS_MATERIAL
        d["material"] = {**hs, **props, "eps0": 1e-4}
    return d


def test_the_bases_are_valid():
    for section, model in SECTIONS.items():
        for key in C.fields_of(model):
            C.case_from_dict(base_for(section, key))


# --- the schema, read back ----------------------------------------------------------------------
def _sections(model, prefix: str = "") -> dict:
    """Every table of the case by dotted name, a section's own tables too (pass.upper)."""
    out = {}
    for name in C.fields_of(model):
        sub = C._model_of(model, name)
        if sub is not None:
            out[prefix + name] = sub
            out.update(_sections(sub, f"{prefix}{name}."))
    return out


SECTIONS = _sections(C.Case)


def table(d: dict, section: str) -> dict:
    """The table ``section`` (dotted) of the case dict ``d``, made empty where absent."""
    for part in section.split("."):
        d = d.setdefault(part, {})
    return d


def _parent(d: dict, section: str) -> tuple[dict, str]:
    """(the table holding ``section``, its last name)."""
    *head, last = section.split(".")
    return (table(d, ".".join(head)) if head else d), last


def _parts(annotation) -> list:
    """The members of a field's type: Optional/Union unpacked, Annotated kept."""
    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        return [p for a in typing.get_args(annotation) for p in _parts(a)]
    return [annotation]


def kind(info) -> dict:
    """What a field takes, from its annotation and constraints: numbers (float or int, with
    their bounds), words (Literal), booleans, text, tables of pairs."""
    out = {"number": None, "integer": False, "words": set(), "bool": False, "text": False,
           "pairs": False, "bounds": {}}
    metadata = list(info.metadata)
    for part in _parts(info.annotation):
        if typing.get_origin(part) is typing.Annotated:
            base, *extra = typing.get_args(part)
            metadata += [m for e in extra for m in getattr(e, "metadata", [e])]
            part = base
        if typing.get_origin(part) is typing.Literal:
            out["words"] |= set(typing.get_args(part))
        elif part is bool:
            out["bool"] = True
        elif part in (float, int):
            out["number"], out["integer"] = True, part is int
        elif part is str:
            out["text"] = True
        elif typing.get_origin(part) is list:
            out["pairs"] = True
    for m in metadata:
        for name in ("gt", "ge", "lt", "le"):
            if isinstance(m, getattr(at, name.capitalize())):
                out["bounds"][name] = getattr(m, name)
    return out


FIELDS = [(section, key, info) for section, model in SECTIONS.items()
          for key, info in C.fields_of(model).items()
          if C._model_of(model, key) is None]        # a section's own tables are sections
_NUM = r"-?\d+(?:\.\d+)?(?:e[+-]?\d+)?"
_OPS = {">": "gt", ">=": "ge", "<": "lt", "<=": "le"}


def documented_bounds(info) -> dict | None:
    """The bounds the field's description states ("allowed: > 0 and <= 1000", "in (0, 1]",
    "an integer >= 1", '"auto", ... or a number > 0'), read from the text the user sees;
    None where the text states none in numbers (tables, names, symbolic bounds only)."""
    text = info.description.split("; allowed: ")[-1]
    text = re.sub(r"^.* or (a number|an integer) ", "", re.sub(r"^an integer ", "", text))
    m = re.fullmatch(rf"in ([\[(])({_NUM}), ({_NUM})([\])])", text)
    if m:
        return {"ge" if m[1] == "[" else "gt": float(m[2]),
                "le" if m[4] == "]" else "lt": float(m[3])}
    terms = [re.fullmatch(rf"(>=|>|<=|<) ({_NUM}|\w+)", t) for t in text.split(" and ")]
    if not all(terms):
        return None
    out = {_OPS[t[1]]: float(t[2]) for t in terms if re.fullmatch(_NUM, t[2])}
    return out or None


def _outside(bounds: dict, integer: bool) -> st.SearchStrategy:
    """Finite numbers outside the bounds, and the bounds themselves where they are excluded."""
    parts = []
    if "gt" in bounds:
        parts.append(st.floats(max_value=bounds["gt"], allow_infinity=False))
    if "ge" in bounds:
        parts.append(st.floats(max_value=bounds["ge"], exclude_max=True, allow_infinity=False)
                     .map(lambda v: int(math.floor(v)) if integer and abs(v) < 1e15 else v))
    if "le" in bounds:
        parts.append(st.floats(min_value=bounds["le"], exclude_min=True, allow_infinity=False))
    if "lt" in bounds:
        parts.append(st.floats(min_value=bounds["lt"], allow_infinity=False))
    return st.one_of(parts) if parts else st.nothing()


def _numeric_text(valid) -> st.SearchStrategy:
    return st.sampled_from([repr(valid), str(valid), f" {valid} ", "1", "0.5", "1e3"])


#: A property (density, ...) broken: a value <= 0 in its table, T not increasing, one pair
BAD_PROPERTY_TABLES = [[[300.0, -1.0], [1400.0, 2.0]], [[1400.0, 1.0], [300.0, 2.0]],
                       [[300.0, 1.0]], [[300.0, 1.0, 2.0], [1400.0, 2.0]],
                       [[-5.0, 1.0], [1.0, 2.0]],
                       [[300.0, math.nan], [1400.0, 2.0]], "warm"]
#: A through-thickness profile broken: eta not from 0 to 1, not increasing, values out of
#: range, a single pair, a pair of three, NaN
BAD_PROFILES = [[[0.1, 1000.0], [1.0, 900.0]], [[0.0, 1000.0], [0.9, 900.0]],
                [[0.0, 1000.0], [0.5, 900.0], [0.4, 950.0], [1.0, 800.0]],
                [[0.0, -5.0], [1.0, 900.0]], [[0.0, 1.0, 2.0], [1.0, 2.0]],
                [[0.0, math.nan], [1.0, 900.0]], [[0.0, 1000.0]], "warm", 900.0]


def bad_values(info, valid) -> st.SearchStrategy:
    """Values the field must refuse (``valid`` is the base case's value)."""
    k = kind(info)
    opts = [st.just({"value": valid})]
    if k["pairs"]:
        opts.append(st.sampled_from(BAD_PROPERTY_TABLES if k["number"] else BAD_PROFILES))
        opts.append(st.just([[0.0, "1000"], [1.0, 900.0]] if not k["number"]
                            else [[300.0, "450"], [1400.0, True]]))
    else:
        opts.append(st.just([valid] if valid is not None else [1.0]))
    if k["number"]:
        # out of the range the user reads (the description), not the one the code enforces
        opts += [_outside(documented_bounds(info) or k["bounds"], k["integer"]),
                 st.sampled_from([math.nan, math.inf, -math.inf]),
                 st.booleans(), _numeric_text(valid)]
        if k["integer"]:
            opts.append(st.floats(1.01, 1e6).filter(lambda v: not v.is_integer()))
        if k["words"]:
            opts.append(st.text(max_size=8).filter(
                lambda s: s.strip().upper() not in {w.upper() for w in k["words"]}
                and s.strip().lower() != "auto"))
    elif k["words"] and not k["text"]:
        opts += [st.text(max_size=12).filter(lambda s: s not in k["words"]),
                 st.integers(), st.floats(allow_nan=False)]
    elif k["bool"]:
        opts += [st.sampled_from(["maybe", "2", 2, -1, 0.5, "truth"])]
    elif k["text"]:
        opts += [st.integers(), st.floats(allow_nan=False)]
    return st.one_of(opts)


@st.composite
def one_field_broken(draw, field=None):
    """(case dict, dotted field) with one field of the schema (``field``: this one) given a
    bad value."""
    section, key, info = field or draw(st.sampled_from(FIELDS))
    d = base_for(section, key)
    valid = table(d, section).get(key, info.default if info.default is not None else 1.0)
    table(d, section)[key] = draw(bad_values(info, valid))
    return d, f"{section}.{key}"


LINE = re.compile(r"^[a-z_][a-z0-9_]*(\.[A-Za-z0-9_]+)*: \S")


def refused(d: dict) -> list[str]:
    """The problem lines of the CaseError ``d`` is refused with (the mesher, if reached,
    raises: the case must be refused before anything is computed)."""
    with mock.patch("hotroll.fem.mesh._graded_mesh", side_effect=AssertionError(
            "meshed a refused case")), pytest.raises(hotroll.CaseError) as info:
        hotroll.case_from_dict(d)
    problems = info.value.problems
    assert problems and all(LINE.match(p) for p in problems), problems
    return problems


FAST = settings(max_examples=300, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


@pytest.mark.parametrize("field", [f for f in FIELDS if kind(f[2])["number"]
                                   and not kind(f[2])["pairs"]], ids=lambda f: f"{f[0]}.{f[1]}")
def test_the_documented_range_is_the_enforced_range(field):
    """The bounds in a number field's description (what `hotroll validate` and the errors
    show) are the constraints pydantic enforces."""
    info = field[2]
    doc = documented_bounds(info)
    assert doc is not None or "finite number" in info.description, info.description
    assert (doc or {}) == kind(info)["bounds"], (info.description, kind(info)["bounds"])


@pytest.mark.parametrize("field", FIELDS, ids=lambda f: f"{f[0]}.{f[1]}")
@settings(max_examples=25, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(data=st.data())
def test_a_bad_value_is_refused_naming_its_field(field, data):
    """Every line blames the broken field, and a number field's line gives its allowed range."""
    d, dotted = data.draw(one_field_broken(field), label="broken")
    problems = refused(d)
    assert all(p.startswith(f"{dotted}:") for p in problems), (dotted, problems)
    section, key, info = field
    allowed = (info.json_schema_extra or {}).get("allowed", "")
    value = table(d, section)[key]
    if kind(info)["number"] and not kind(info)["pairs"] and not isinstance(value, (list, dict)):
        assert any(allowed in p for p in problems), (problems, allowed)


@FAST
@given(section=st.sampled_from(sorted(SECTIONS)),
       key=st.from_regex(r"[a-z][a-z0-9_]{0,14}", fullmatch=True), value=st.integers())
def test_an_unknown_key_is_refused_naming_it(section, key, value):
    d = base_for(section, key)
    if key in C.fields_of(SECTIONS[section]):
        return
    table(d, section)[key] = value
    assert refused(d) == [f"{section}.{key}: unknown key (allowed: "
                          f"{', '.join(C.fields_of(SECTIONS[section]))})"]


@FAST
@given(key=st.from_regex(r"[a-z][a-z0-9_]{0,14}", fullmatch=True),
       section=st.sampled_from(sorted(SECTIONS)),
       value=st.one_of(st.integers(), st.text(max_size=5), st.lists(st.integers(), max_size=2)))
def test_an_unknown_section_or_a_section_that_is_no_table_is_refused(key, section, value):
    if key not in C.fields_of(C.Case):
        d = copy.deepcopy(BASE)
        d[key] = {"x": 1}
        assert [p.split(" (")[0] for p in refused(d)] == [f"{key}: unknown section or key"]
    d = copy.deepcopy(BASE)
    parent, last = _parent(d, section)
    parent[last] = value
    if "." not in section:
        assert refused(d) == [f"{section}: must be a table [{section}], got {value!r}"]
    else:                  # a section's own table: pydantic's words, naming it
        assert [p.split(":")[0] for p in refused(d)] == [section]


REQUIRED = [(s, k) for s, k, info in FIELDS if info.is_required()] + [
    ("material", "K"), ("material", "m"), ("friction", "mu")]


@pytest.mark.parametrize("section,key", REQUIRED)
def test_a_missing_required_key_is_named(section, key):
    d = base_for(section, key)
    del table(d, section)[key]
    assert all(p.startswith(f"{section}.{key}: ") and ("missing" in p or "required" in p)
               for p in refused(d))
    if section in ("pass", "plate", "material"):
        d = copy.deepcopy(BASE)
        del d[section]
        assert refused(d) == [f"{section}: missing required section"]


def _lc(p: dict) -> float:
    """Projected contact length sqrt(R^2 - (R - draft)^2), written out here."""
    draft = (p["entry_thickness"] - p["exit_thickness"]) / 2
    return math.sqrt(p["roll_radius"] ** 2 - (p["roll_radius"] - draft) ** 2)


@st.composite
def rule_broken(draw):
    """(case dict, dotted field) breaking a rule between fields."""
    d = copy.deepcopy(BASE)
    p, rule = d["pass"], draw(st.integers(0, 15))
    frac = draw(st.floats(0.0, 1.0))
    if rule == 0:          # the exit no thinner than the entry
        p["exit_thickness"] = p["entry_thickness"] * (1 + 3 * frac)
        return d, "pass.exit_thickness"
    if rule == 1:          # a roll smaller than the draft cannot bite
        p["roll_radius"] = max(1e-6, frac) * (p["entry_thickness"] - p["exit_thickness"]) / 2
        return d, "pass.roll_radius"
    if rule == 2:          # the plate shorter than 3 contact lengths
        d["plate"]["length"] = max(1e-6, frac) * 3 * _lc(p) * (1 - 1e-9)
        return d, "plate.length"
    if rule == 3:          # the contact mesh no finer than a quarter of the contact
        d["pass"]["exit_thickness"] = 0.49   # a thin draft: the contact is the limit
        d["mesh"]["h_contact"] = _lc(p) / 4 * (1 + 1e-6 + 3 * frac)   # l_c rounded here
        d["mesh"]["h_far"] = 10.0
        return d, "mesh.h_contact"
    if rule == 4:          # fewer than 4 elements through the exit half-thickness
        d["mesh"]["h_contact"] = min(_lc(p) / 4.01, p["exit_thickness"] / 8 * (1.0001 + frac))
        d["mesh"]["h_far"] = 10.0
        return d, "mesh.h_contact"
    if rule == 5:          # the far mesh finer than the contact mesh
        d["mesh"]["h_far"] = d["mesh"]["h_contact"] * frac * 0.999
        return d, "mesh.h_far"
    if rule == 6:          # a friction parameter of another law
        key, law = draw(st.sampled_from([("mu", "tresca"), ("mu", "viscoplastic"),
                                         ("factor", "coulomb"), ("factor", "viscoplastic"),
                                         ("a_f", "coulomb"), ("a_f", "tresca")]))
        d["friction"] = {"law": law, {"coulomb": "mu", "tresca": "factor"}.get(law, "a_f"): 0.5,
                         key: 0.5}
        return d, f"friction.{key}"
    if rule == 7:          # Coulomb without mu, Tresca without a factor
        law, key = draw(st.sampled_from([("coulomb", "mu"), ("tresca", "factor")]))
        d["friction"] = {"law": law}
        return d, f"friction.{key}"
    if rule == 8:          # a Hensel-Spittel key with Norton-Hoff, K or m with Hensel-Spittel
        key = draw(st.sampled_from(sorted(HS_MATERIAL.keys() - {"law"}) + ["grade"]))
        d["material"][key] = "S355J2" if key == "grade" else 0.1
        return d, f"material.{key}"
    if rule == 9:
        key = draw(st.sampled_from(["K", "m"]))
        d["material"] = {**base_for("material", "A")["material"], key: 0.5}
        return d, f"material.{key}"
    if rule == 10:         # Hensel-Spittel without A or a grade; an unknown grade
        d["material"] = {k: v for k, v in base_for("material", "A")["material"].items()
                         if k != "A"}
        if draw(st.booleans()):
            d["material"] = {**base_for("material", "grade")["material"],
                             "grade": draw(st.sampled_from(["S999", "steel", ""]))}
            return d, "material.grade"
        return d, "material.A"
    if rule == 11:         # Hensel-Spittel without rate sensitivity: m3 outside (0, 1], m8 = 0
        d["material"] = {**base_for("material", "A")["material"], "m8": 0.0,
                         "m3": draw(st.sampled_from([0.0, -0.1, 1.5]))}
        if draw(st.booleans()):
            del d["material"]["m3"]           # omitted: 0
        return d, "material.m3"
    if rule == 12:         # a grade at a temperature where its rate exponent leaves (0, 1]
        d["material"] = base_for("material", "grade")["material"]
        d["plate"]["temperature"] = draw(st.sampled_from([1.0, 200.0, 273.15, 2e4]))
        del d["plate"]["temperature_profile"], d["thermal"]
        return d, "plate.temperature"
    if rule == 13:         # [thermal] without one of the strip's properties
        key = draw(st.sampled_from(["density", "specific_heat", "conductivity"]))
        del d["material"][key]
        return d, f"material.{key}"
    if rule == 14:         # an entry temperature profile in an isothermal run
        del d["thermal"]
        return d, "plate.temperature_profile"
    key = draw(st.sampled_from(["temperature_profile", "strain_profile"]))
    d["solver"]["method"] = "transient"       # profiles need the steady method
    return d, f"plate.{key}"


@FAST
@given(rule_broken())
def test_a_broken_rule_between_fields_is_refused_naming_the_field(broken):
    d, dotted = broken
    assert any(p.startswith(f"{dotted}:") for p in refused(d)), (dotted, refused(d))


NUMBER_FIELDS = [(s, k) for s, k, info in FIELDS if kind(info)["number"]]


@settings(max_examples=400, deadline=None, derandomize=True, database=None)
@given(field=st.sampled_from(NUMBER_FIELDS + [("material", k) for k in HS_MATERIAL if k != "law"]),
       value=st.floats(allow_nan=False, allow_infinity=False) | st.integers(-10**30, 10**30))
def test_any_finite_number_gives_a_case_or_a_case_error(field, value):
    """Huge, tiny and negative numbers in any number field: a Case or a CaseError, nothing
    else (R = 1e300 m overflowed in the contact length; roll_axis_x = 1e300 m blamed the mesh)."""
    section, key = field
    d = base_for(section, "A" if key in HS_MATERIAL else key)
    table(d, section)[key] = value
    try:
        case = hotroll.case_from_dict(d)
    except hotroll.CaseError as e:
        assert all(LINE.match(p) for p in e.problems), e.problems
        return
    p = case.pass_
    assert math.isfinite(p.contact_length) and p.contact_length > 0
    assert math.isfinite(case.mesh.h) and case.mesh.h < p.contact_length / 4


# --- through the command line: a TOML file, `hotroll run`, exit code 2 -------------------------
def _toml_key(k: str) -> str:
    return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else json.dumps(k)


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float) and not math.isfinite(v):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf")
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(type(v))


def to_toml(d: dict) -> str:
    """A case dict as TOML text (tables for the sections, anything else inline)."""
    lines = [f"{_toml_key(k)} = {_toml_value(v)}" for k, v in d.items() if not isinstance(v, dict)]
    for k, v in d.items():
        if isinstance(v, dict):
            lines += [f"[{_toml_key(k)}]"] + [f"{_toml_key(kk)} = {_toml_value(vv)}"
                                              for kk, vv in v.items()]
    return "\n".join(lines) + "\n"


@settings(max_examples=40, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(st.one_of(one_field_broken(), rule_broken()))
def test_hotroll_run_refuses_a_bad_case_file_with_exit_code_2(broken):
    from typer.testing import CliRunner

    from hotroll.cli import app

    d, dotted = broken
    with tempfile.TemporaryDirectory() as tmp, mock.patch(
            "hotroll.fem.mesh._graded_mesh",
            side_effect=AssertionError("meshed a refused case")):
        path = Path(tmp) / "case.toml"
        path.write_text(to_toml(d), encoding="utf-8")
        result = CliRunner().invoke(app, ["run", str(path), "--out", str(Path(tmp) / "out")])
        assert result.exit_code == 2, result.output
        assert f"{dotted}:" in result.output.replace("\n", "")
        assert not (Path(tmp) / "out").exists()


# ------------------------------------------------------------------------------------------------
# 2. valid cases in a bounded range: solved, conserved, or a stated reason
# ------------------------------------------------------------------------------------------------
R = 0.5                 # m: the ratio R/h0 is drawn; the roll is a hot mill's
MASS_TOL = 0.02         # |Q_out - Q_in| / Q_in of a converged run (module docstring)
POWER_TOL = 0.02        # power balance defect / roll power of a converged run


def pass_case(ratio: float, reduction: float, m: float, omega: float, K: float,
              friction: dict) -> dict:
    """The steady case: entry thickness R/ratio, the coarsest mesh the schema accepts (l_c/4.5,
    4 elements through the exit half-thickness), a plate of 4 contact lengths."""
    h0 = R / ratio
    h1 = h0 * (1.0 - reduction)
    lc = math.sqrt(R**2 - (R - (h0 - h1) / 2) ** 2)
    return {
        "name": "bounded",
        "pass": {"roll_radius": R, "entry_thickness": h0, "exit_thickness": h1,
                 "roll_angular_velocity": omega},
        "plate": {"length": 4.0 * lc},
        "material": {"K": K, "m": m},
        "friction": friction,
        "mesh": {"h_contact": 0.999 * min(lc / 4.5, h1 / 8.0)},
        "solver": {"method": "steady", "threads": 1},
        "output": {"figures": False, "vtk": False},
    }


FRICTION = {   # each law with its parameter over its range
    "viscoplastic": st.one_of(st.just({"law": "viscoplastic"}),        # a_f estimated (3.15)
                              st.floats(0.5, 100.0).map(lambda a: {"law": "viscoplastic",
                                                                   "a_f": a})),
    "coulomb": st.floats(0.05, 1.0).map(lambda mu: {"law": "coulomb", "mu": mu}),
    "tresca": st.floats(0.05, 1.0).map(lambda f: {"law": "tresca", "factor": f})}


def passes(friction: st.SearchStrategy) -> st.SearchStrategy:
    """Steady passes over the bounded range (module docstring); log-uniform where it spans
    decades."""
    return st.builds(pass_case,
                     ratio=st.floats(math.log10(5), 2).map(lambda e: 10**e),
                     reduction=st.floats(0.05, 0.5),
                     m=st.floats(math.log10(0.02), 0).map(lambda e: 10**e),
                     omega=st.floats(-1, math.log10(30)).map(lambda e: 10**e),
                     K=st.floats(0, 9).map(lambda e: 10**e),
                     friction=friction)


PASSES = passes(st.one_of(list(FRICTION.values())))


def solve(d: dict) -> tuple[C.Case, dict]:
    """The case through the Python API (hotroll.case_from_dict, hotroll.solve)."""
    case = hotroll.case_from_dict(d)
    with tempfile.TemporaryDirectory() as tmp:
        summary = hotroll.solve(case, Path(tmp) / "run").summary
    return case, summary


def check_outcome(case: C.Case, s: dict) -> None:
    """Converged with the conservation checks closing, or a nonzero exit code and its reason."""
    code = s["exit_code"]
    assert code == exit_code(s) and code in EXIT_CODES and code != 2   # 2: refused input
    assert isinstance(s["status"], str) and s["status"]
    if code != 0:
        # the reason stated: the code's meaning and what the summary says happened
        assert not s["converged"]
        if code in (3, 7):
            assert isinstance(s["failure"], str) and s["failure"]
        if code == 7:
            assert s["not_conserved"] and s["steady_state"] and not s["outlet_driven"]
            assert (s["mass_flux_error"] > MASS_TOL or s["power_balance_error"] > POWER_TOL
                    or s["leak_to_slip"] > CONSERVATION_TOL["leak_to_slip"]
                    or s["penalty_share"] > CONSERVATION_TOL["penalty_share"])
        if code == 6:
            assert s["outlet_driven"]
        if code == 5:
            assert s["status"] in ("unsettled", "end_time", "max_steps", "wall_time")
        if code == 4:     # the last Newton solve did not converge, or no finite figures
            assert s["status"] in ("failed", "steady") or not all(
                math.isfinite(s[k]) for k in ("roll_force", "roll_torque"))
        return
    p, omega = case.pass_, case.pass_.roll_angular_velocity
    U = omega * p.roll_radius
    assert s["converged"] and s["steady_state"] and not s["outlet_driven"]
    assert not s["not_conserved"] and s["failure"] is None
    # mass: the flux through the entry face = the flux through the exit face
    q_in, q_out = s["mass_flux_in"], s["mass_flux_out"]
    assert q_in > 0 and abs(q_out - q_in) / q_in <= MASS_TOL
    assert s["mass_flux_error"] == pytest.approx(abs(q_out - q_in) / q_in, rel=1e-9)
    # ... = entry velocity x entry half-thickness (the rigid inlet), exit velocity and slip
    assert q_in == pytest.approx(s["entry_velocity"] * p.entry_thickness / 2, rel=1e-6)
    assert s["forward_slip"] == pytest.approx(s["exit_velocity"] / U - 1.0, rel=1e-9, abs=1e-12)
    assert U * (1 + s["forward_slip"]) * p.exit_thickness / 2 == pytest.approx(q_in, rel=0.03)
    # power: what the roll puts in (and the tensions) is dissipated in the strip
    dissipated = s["plastic_power"] + s["friction_power"] + s["penalty_power"]
    supplied = s["roll_power"] + s["tension_power"]
    assert s["roll_power"] > 0 and s["plastic_power"] > 0 and s["friction_power"] >= 0
    assert abs(dissipated - supplied) <= POWER_TOL * s["roll_power"]
    assert s["roll_power"] == pytest.approx(s["roll_torque"] * omega, rel=1e-3)
    # the force presses the rolls apart; the kinematics in their physical ranges: the neutral
    # point on the contact arc, the exit no faster than the roll with the whole arc slipping
    # backwards (exit speed <= U h0/h1)
    assert s["roll_force"] > 0 and s["roll_torque"] > 0
    slip_max = (1 + MASS_TOL) * p.entry_thickness / p.exit_thickness - 1
    assert -MASS_TOL <= s["forward_slip"] <= slip_max
    cx, cy = s["roll_centre"]
    start = math.atan2(cx - s["contact_start"][0], cy - s["contact_start"][1])
    assert 0.0 < start <= 1.25 * p.bite_angle          # the traced entry top sags a little
    if s["neutral_angle"] is None:   # a sticking arc: the slip's sign is noise (theory 1e)
        zone = s["sticking_zone"]
        assert s["neutral_angle_in_sticking_zone"] and "sticking zone" in s["neutral_angle_reason"]
        assert s["neutral_point"] is None and 0.0 <= zone[1] < zone[0] <= start + 1e-12
    else:
        assert 0.0 <= s["neutral_angle"] <= start + 1e-12 and s["neutral_angle_reason"] is None


CORNERS = [  # (R/h0, reduction, m, omega, K, friction): the ranges' corners, cheap ones
    (5.0, 0.05, 1.0, 30.0, 1e9, {"law": "coulomb", "mu": 1.0}),
    (100.0, 0.05, 1.0, 30.0, 1e9, {"law": "tresca", "factor": 1.0}),
    (5.0, 0.5, 0.2, 1.0, 1.0, {"law": "viscoplastic"}),
    (100.0, 0.5, 0.2, 30.0, 1.0, {"law": "tresca", "factor": 0.05}),
    (5.0, 0.5, 1.0, 0.1, 1.0, {"law": "coulomb", "mu": 0.05}),
    (100.0, 0.05, 0.02, 1.0, 1e4, {"law": "viscoplastic", "a_f": 100.0}),
]
SOLVES = settings(max_examples=10, deadline=None, derandomize=True, database=None,
                  phases=[Phase.explicit, Phase.generate],    # a case costs seconds: no shrinking
                  suppress_health_check=[HealthCheck.too_slow])


@pytest.mark.parametrize("law", sorted(FRICTION))
@SOLVES
@given(data=st.data())
def test_a_bounded_valid_case_solves_or_states_why_not(law, data):
    check_outcome(*solve(data.draw(passes(FRICTION[law]), label="case")))


@pytest.mark.parametrize("args", CORNERS,
                         ids=lambda a: "-".join(map(str, a[:5])) + "-" + a[5]["law"])
def test_the_corners_of_the_range_solve_or_state_why_not(args):
    check_outcome(*solve(pass_case(*args)))


@pytest.mark.parametrize("args", [
    (20.0, 0.2, 0.2, 3.0, 1e6, {"law": "viscoplastic"}),
    (10.0, 0.3, 0.1, 10.0, 1e8, {"law": "coulomb", "mu": 0.4}),
    (50.0, 0.25, 0.5, 1.0, 1e3, {"law": "tresca", "factor": 0.7})],
    ids=["viscoplastic", "coulomb", "tresca"])
def test_mid_range_passes_converge(args):
    """Inside the range, away from skidding and from the slow speeds: each law converges (the
    property above would accept a stated failure; these must not fail)."""
    case, s = solve(pass_case(*args))
    assert s["exit_code"] == 0, (s["status"], s["failure"])
    check_outcome(case, s)


@settings(max_examples=4, deadline=None, derandomize=True, database=None,
          phases=[Phase.explicit, Phase.generate], suppress_health_check=[HealthCheck.too_slow])
@given(PASSES)
@example(pass_case(*CORNERS[1]))
def test_k_times_1000_multiplies_forces_and_powers_only(d):
    """Results do not depend on the unit of K: K x 1000 gives the same run (status, exit code,
    iterations, kinematics) with every force, torque and power x 1000."""
    case, s = solve(d)
    big = copy.deepcopy(d)
    big["material"]["K"] *= 1000.0
    _, t = solve(big)
    for key in ("status", "exit_code", "nonlinear_iterations", "converged"):
        assert t[key] == s[key], key
    for key in ("forward_slip", "neutral_angle", "mass_flux_in", "mass_flux_out",
                "power_balance_error", "a_f"):
        if s[key] is None:                      # no neutral point: none either
            assert t[key] is None, key
        elif math.isfinite(s[key]):
            assert t[key] == pytest.approx(s[key], rel=1e-9, abs=1e-12), key
    for key in ("roll_force", "roll_torque", "roll_power", "plastic_power", "friction_power"):
        assert t[key] == pytest.approx(1000.0 * s[key], rel=1e-9, abs=1e-12), key


def test_conservation_check_of_the_runner_by_hand():
    """runner.conservation_problem: each check over its tolerance named, none under it."""
    from hotroll.workflows.runner import conservation_problem

    ok = {"mass_flux_error": 0.0199, "power_balance_error": -0.0199, "roll_surface_speed": 0.05}
    assert conservation_problem(ok) is None
    assert conservation_problem({**ok, "mass_flux_error": math.nan}) is None
    text = conservation_problem({**ok, "mass_flux_error": 0.0301})
    assert "mass_flux_error = 0.0301 above 0.02" in text and "power" not in text
    text = conservation_problem({**ok, "power_balance_error": -0.05, "mass_flux_error": 0.03})
    assert "mass_flux_error = 0.03" in text and "power_balance_error = 0.05 above 0.02" in text


def test_forward_slip_does_not_depend_on_the_roll_speed():
    """Norton-Hoff is a power law in the rate: omega x 100 scales every stress by 100^m and
    leaves the flow pattern, hence the forward slip, exactly as it was, once eps0 scales with
    it (v_reg is a fraction of the roll speed). Issue 18's strict xfail (the penalties of
    Table 1 did not scale: the slip 13 % low at 0.1 rad/s); exact contact (issue 30): equal to
    1e-9 with the primal Newton tangent; the primal-dual tangent (issue 34) amplifies the
    rounding of the two runs' first step (7e-13) along the globalised path, and the slips end
    4.8e-7 apart, inside the Newton tolerance (1e-5), which is asked here (the rounding and
    its amplification differ between machines). With the friction's dual (session 6) both runs
    take the same 9 full steps and their slips agree to the last digit on this machine; the
    Newton tolerance is still what is asked. eps0 left unscaled (a hidden unit) moves the slip
    by 1.6e-4 (measured): caught."""
    runs = []
    for omega in (0.1, 10.0):
        d = pass_case(16.6, 0.33, 0.05, omega, 1e5, {"law": "tresca", "factor": 0.3})
        d["material"]["eps0"] = 1e-4 * omega
        runs.append(solve(d)[1])
    assert runs[0]["exit_code"] == runs[1]["exit_code"]
    assert runs[0]["forward_slip"] == pytest.approx(runs[1]["forward_slip"], rel=1e-5)


def test_a_failing_linear_solve_ends_a_steady_run_with_its_reason(monkeypatch):
    """A LinearSolveError in the steady solver's cold start (m = 0.02 at 15 m/s with Tresca's
    factor 1, R/h0 = 100, 50 %: no direct solver reached 1e-6) escaped the runner as a
    traceback; now the continuation in m is tried, and if that fails too the run ends with
    exit code 3 and the reason."""
    import hotroll.solvers.steady_solve as S  # the steady solve's loop calls newton
    from hotroll.fem.nonlinear import LinearSolveError

    real, calls = S.newton, {"n": 0, "fail": {1}}

    def newton(*args, **kw):
        calls["n"] += 1
        if calls["n"] in calls["fail"]:
            raise LinearSolveError("no direct solver (test)")
        return real(*args, **kw)

    monkeypatch.setattr(S, "newton", newton)
    d = pass_case(50.0, 0.25, 0.5, 1.0, 1e3, {"law": "tresca", "factor": 0.7})
    case, s = solve(d)                      # the direct solve fails, the continuation does not
    assert calls["n"] > 1 and s["exit_code"] == 0
    check_outcome(case, s)
    calls.update(n=0, fail=set(range(1, 100)))
    case, s = solve(d)                      # both fail
    assert s["exit_code"] == 3 and s["status"] == "failed"
    assert s["failure"] == "m = 1: no direct solver (test)"     # the continuation's first stage
    check_outcome(case, s)
