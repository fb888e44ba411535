"""Quantities with units in the input files (issue 51): a number stays SI; a text such as
"6 mm", "1000 degC", "5 m/s", "120 MPa" or "60 rpm" is converted to the field's SI unit by
pint, the units library of the scientific Python ecosystem, and refused naming the field when
its dimension is not the field's.

Two choices, both measured with pint 0.25 (docs/notes/issue51-research.md, section 2):

- The number and the unit are split here and given to pint as ``Quantity(Decimal(number),
  unit)``: pint parses the text "1000 degC" as the product 1000 x degC, which an offset unit
  refuses (``OffsetUnitCalculusError``), and the split refuses expressions ("6 mm + 1 cm").
- A registry of ``Decimal`` magnitudes: "64.938 mm" is then exactly the float 0.064938 that
  the literal 0.064938 gives (with float magnitudes 23 % of random lengths in mm were off by
  an ulp), so "6 mm" and 0.006 give the same bits everywhere downstream.
"""
from __future__ import annotations

import re
from decimal import Decimal, InvalidOperation
from functools import lru_cache

#: a number, then its unit
_QUANTITY = re.compile(r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(\S.*?)\s*$")

#: hotroll's unit texts (config fields) as pint reads them; None: not a pint unit (a law's
#: own, such as Norton-Hoff's consistency in Pa s^m): numbers only
_PINT = {"1/degC": "1/delta_degC", "B": "byte", "m^-m": None, "Pa s^m": None, "wt %": None,
         "-": None, "": None}

#: the unit an engineer reads a SI unit in, and the SI value of one of it (an offset too):
#: (name, factor, offset), value = (si - offset) / factor (``hotroll validate``, case.toml);
#: plain arithmetic, so writing a case does not load pint (0.3 s)
ENGINEERING = {"m": ("mm", 1e-3, 0.0), "K": ("degC", 1.0, 273.15), "Pa": ("MPa", 1e6, 0.0),
               "rad/s": ("rpm", 2.0 * 3.141592653589793 / 60.0, 0.0),
               "N/m": ("kN/mm", 1e6, 0.0), "B": ("GiB", 2.0**30, 0.0),
               "1/degC": ("1/K", 1.0, 0.0)}


class UnitError(ValueError):
    """A text that is not a number with a unit of the field's dimension."""


@lru_cache(maxsize=1)
def registry():
    """pint's registry with Decimal magnitudes (made once, on the first text: 0.2 s)."""
    import pint

    return pint.UnitRegistry(non_int_type=Decimal)


def pint_unit(unit: str) -> str | None:
    """The pint text of hotroll's unit ``unit``, None where it has none."""
    return _PINT.get(unit, unit)


def takes_units(unit: str) -> bool:
    """Whether a field in ``unit`` takes quantities with units."""
    return pint_unit(unit) is not None


def dimension_name(unit: str) -> str:
    """'length', 'temperature', 'pressure' ... of a SI unit (pint's dimensionality otherwise)."""
    names = {"m": "length", "K": "temperature", "Pa": "pressure or stress", "s": "time",
             "m/s": "speed", "rad/s": "angular speed", "1/s": "strain rate",
             "N/m": "force per width", "kg/m^3": "density", "B": "memory size"}
    return names.get(unit) or str(registry().get_dimensionality(pint_unit(unit)))


def to_si(text: str, unit: str) -> float:
    """The value of ``text`` ("6 mm") in ``unit`` (hotroll's SI unit of the field), a float.
    ``UnitError`` names what is wrong: no unit, an unknown unit, another dimension."""
    import pint

    target = pint_unit(unit)
    if target is None:
        raise UnitError(f"a number (this field's unit {unit!r} has no unit texts), got {text!r}")
    m = _QUANTITY.match(text)
    if m is None:
        raise UnitError(f"a number, or a number with a unit such as '1 {unit}', got {text!r}")
    try:
        number = Decimal(m.group(1))
    except InvalidOperation:      # the pattern admits only numbers: never reached
        raise UnitError(f"a number with a unit, got {text!r}") from None
    text_unit = m.group(2)
    if text_unit.startswith("/"):             # "1 /s"
        text_unit = "1" + text_unit
    try:
        q = registry().Quantity(number, text_unit)
        return float(q.to(target).magnitude)
    except pint.UndefinedUnitError:
        raise UnitError(f"unknown unit {m.group(2)!r} in {text!r}") from None
    except pint.DimensionalityError:
        raise UnitError(f"{text!r} is not a {dimension_name(unit)} (a unit like {unit})") from None
    except (pint.errors.PintError, AttributeError, TypeError, ValueError) as e:
        raise UnitError(f"cannot read {text!r} as a quantity in {unit}: {e}") from None


def shown(value: float, unit: str) -> str:
    """``value`` (SI, in ``unit``) in the engineer's unit, e.g. '1000 degC', '6 mm'."""
    if unit not in ENGINEERING:
        return f"{value:.6g} {unit}".rstrip()
    name, factor, offset = ENGINEERING[unit]
    return f"{(value - offset) / factor:.6g} {name}"
