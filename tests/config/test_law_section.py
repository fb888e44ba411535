"""The law sections' fields built from a registry (hotroll/config/law_section.py:
parameter_fields), called at test time: the sections are built at import, which the mutation
run cannot see. Each field's type, text, unit, allowed range and limits written out by hand."""
from __future__ import annotations

import typing

import pytest
from pydantic import TypeAdapter, ValidationError

from hotroll.config.law_section import parameter_fields
from hotroll.model.friction import FRICTION_LAWS
from hotroll.model.heat_transfer import HEAT_TRANSFER_LAWS

pytestmark = pytest.mark.mutation


def test_friction_fields_by_hand():
    f = parameter_fields(FRICTION_LAWS)
    assert list(f) == ["a_f", "mu", "factor"]
    kind, info = f["mu"]
    assert kind == float | None and info.default is None
    assert info.description == ('Coulomb friction coefficient; law = "coulomb" only [-]; '
                                'allowed: in (0, 2]')
    assert info.json_schema_extra["allowed"] == "in (0, 2]"
    mu = TypeAdapter(typing.Annotated[kind, info])
    assert mu.validate_python(2.0) == 2.0 and mu.validate_python(None) is None
    for bad in (0.0, 2.0001):
        with pytest.raises(ValidationError):
            mu.validate_python(bad)
    kind, info = f["a_f"]                         # words besides numbers: "estimate"
    a_f = TypeAdapter(typing.Annotated[kind, info])
    assert a_f.validate_python("estimate") == "estimate" and a_f.validate_python(3.0) == 3.0
    for bad in ("guess", 0.0, -1.0):
        with pytest.raises(ValidationError):
            a_f.validate_python(bad)
    assert info.description.endswith('law = "viscoplastic" only [m^-m]; allowed: "estimate" '
                                     'or a number > 0')
    assert info.json_schema_extra["allowed"] == '"estimate" or a number > 0 [m^-m]'


def test_a_parameter_of_two_laws_is_one_field_naming_both():
    """htc_air belongs to one surface law; a parameter shared by two laws is declared once and
    says both (checked on a registry of two laws sharing a parameter)."""
    from dataclasses import replace

    spec = HEAT_TRANSFER_LAWS["convection_radiation"]
    twin = replace(spec, name="twin")
    f = parameter_fields({"convection_radiation": spec, "twin": twin})
    assert list(f) == ["htc_air", "emissivity"]
    assert 'law = "convection_radiation" or "twin" only' in f["htc_air"][1].description
    kind, info = f["emissivity"]
    e = TypeAdapter(typing.Annotated[kind, info])
    assert e.validate_python(1.0) == 1.0 and e.validate_python(0.0) == 0.0
    with pytest.raises(ValidationError):
        e.validate_python(1.01)


def test_a_field_carries_its_unit_and_range():
    """config/base.py: field, called at test time (the schema's classes call it at import)."""
    from hotroll.config.base import field

    f = field(0.5, "share of something", "W/m", "in [0, 1]", ge=0, le=1)
    assert f.default == 0.5
    assert f.description == "share of something [W/m]; allowed: in [0, 1]"
    assert f.json_schema_extra["allowed"] == "in [0, 1] [W/m]"
    g = TypeAdapter(typing.Annotated[float, f])
    assert g.validate_python(1.0) == 1.0
    with pytest.raises(ValidationError):
        g.validate_python(1.5)
    bare = field(None, "a count", "", "an integer")
    assert bare.description == "a count [-]; allowed: an integer"
    assert bare.json_schema_extra["allowed"] == "an integer"


def test_the_heat_transfer_law_choice():
    """config/thermal.py: _law_choice, the [thermal] contact_law/surface_law field."""
    from hotroll.config.thermal import _law_choice

    kind, info = _law_choice("surface")
    assert typing.get_args(kind) == ("convection_radiation",)
    assert info.default == "convection_radiation"
    assert info.description == (
        "heat-transfer law of the surface: convection_radiation (q = htc_air (T - T_ambient) "
        '+ emissivity sigma (T^4 - T_ambient^4)) [-]; allowed: "convection_radiation"')
    kind, info = _law_choice("contact")
    assert typing.get_args(kind) == ("constant",) and info.default == "constant"
    assert info.json_schema_extra["allowed"] == '"constant"'


def test_with_generated_replaces_only_between_the_marks():
    """config/reference.py: the text between the first BEGIN and the first END after it is
    the new body; what is before and after (another END in the tail too) stays."""
    from hotroll.config.reference import BEGIN, END, with_generated

    page = f"head\n{BEGIN}\nold\n{END}\ntail {END} more"
    assert with_generated(page, "BODY") == f"head\n{BEGIN}\n\nBODY\n{END}\ntail {END} more"
    again = with_generated(with_generated(page, "BODY"), "NEW")
    assert again == f"head\n{BEGIN}\n\nNEW\n{END}\ntail {END} more"
