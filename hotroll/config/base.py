"""Shared pieces of the case description (``config.py``, ``config_laws.py``): the error type,
the field helper that puts unit and allowed range into every message, the base section."""

from __future__ import annotations

import types
import typing
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator
from pydantic.fields import FieldInfo

#: Contact mesh sizes of the report's Table 2 (m).
MESH_TABLE: dict[str, float] = {
    "C1": 5.02e-3, "C2": 4.2e-3, "M1": 3.7e-3, "M2": 3.01e-3, "F1": 2.7e-3, "F2": 2.02e-3,
}
MeshName = Literal["C1", "C2", "M1", "M2", "F1", "F2"]
#: Largest length of a case (m): roll radius, thicknesses, plate length, |roll_axis_x|. Beyond
#: it the geometry's squares overflow (R = 1e300 m) or the roll position swamps the contact
#: length in double precision (roll_axis_x = 1e300 m: l_c = 0); mills are metres in size.
MAX_LENGTH = 1e3
PosFloat = Annotated[float, Field(gt=0)]


class CaseError(ValueError):
    """Invalid case description; ``problems`` holds one ``section.key: ...`` line each."""

    def __init__(self, problems: list[str] | str, source: str | None = None,
                 what: str = "case description"):
        self.problems = [problems] if isinstance(problems, str) else list(problems)
        self.source = source
        n = len(self.problems)
        head = f"{source or 'case'}: invalid {what} ({n} problem{'s' * (n != 1)})"
        super().__init__("\n".join([head] + [f"  {p}" for p in self.problems]))


class Problems(ValueError):
    """Raised inside model validators; carries ready-made ``section.key: ...`` lines."""

    def __init__(self, problems: list[str]):
        self.problems = problems
        super().__init__("; ".join(problems))


def field(default: Any, text: str, unit: str, allowed: str, *,
          columns: tuple[str, ...] | None = None, **constraints: Any) -> Any:
    """Field whose description and error messages carry unit and allowed range. A number field
    in a unit pint knows also takes text with a unit ("6 mm", config/units.py); ``columns``:
    a table of pairs' unit per column (``unit`` is then the one the text names)."""
    allowed_u = f"{allowed} [{unit}]" if unit else allowed
    desc = f"{text} [{unit or '-'}]; allowed: {allowed}"
    extra: dict[str, Any] = {"allowed": allowed_u, "unit": unit}
    if columns is not None:
        extra["columns"] = list(columns)
    return Field(default, description=desc, json_schema_extra=extra, **constraints)


def with_units(value: Any, unit: str, words=(), columns=None) -> Any:
    """``value`` with every text that carries a unit ("6 mm") converted to the SI ``unit``
    (config/units.py), inside lists too, a table's pairs by ``columns``; the field's words
    ("auto") and the rest as they are (refused after, by ``has_text``)."""
    from hotroll.config.units import takes_units, to_si

    if isinstance(value, str) and value not in words and value.strip()[:1] in "+-.0123456789":
        if takes_units(unit):
            return to_si(value, unit)
        return value
    if isinstance(value, (list, tuple)):
        if columns is not None and all(isinstance(r, (list, tuple)) for r in value):
            return [[with_units(x, u) for x, u in zip(row, columns)] + list(row[len(columns):])
                    for row in value]
        return [with_units(x, unit, words) for x in value]
    return value


def _number_field(annotation: Any) -> tuple[bool, set]:
    """(a field of numbers, its allowed words): a field whose type is float or int, optionally
    with None, in lists or tuples (tables of pairs), and ``Literal`` words ("auto",
    "estimate"); not text, a switch or a table of sections."""
    number, words, other = False, set(), False
    todo = [annotation]
    while todo:
        a = todo.pop()
        origin = typing.get_origin(a)
        if origin is Annotated:
            todo.append(typing.get_args(a)[0])
        elif origin in (typing.Union, types.UnionType, list, tuple):
            todo += [x for x in typing.get_args(a) if x is not Ellipsis]
        elif origin is Literal:
            words.update(typing.get_args(a))
        elif a in (float, int):
            number = True
        elif a is not type(None):
            other = True
    return number and not other and all(isinstance(w, str) for w in words), words


def has_text(value: Any, words=()) -> bool:
    """Text (other than ``words``) or a boolean where numbers go, also inside lists."""
    if isinstance(value, bool) or (isinstance(value, str) and value not in words):
        return True
    return isinstance(value, (list, tuple)) and any(has_text(v) for v in value)


class Section(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    @field_validator("*", mode="before")
    @classmethod
    def _number_not_text(cls, v: Any, info) -> Any:
        """A number field takes numbers: not text ("0.5": pydantic would convert it) nor a
        boolean (true would be 1), also not inside a table of pairs; its words ("auto", ...)
        stay allowed; a number with a unit ("6 mm") is converted to the field's SI unit
        (``with_units``). The error carries the field's allowed range (config._message)."""
        info_f = cls.model_fields[info.field_name]
        number, words = _number_field(info_f.annotation)
        if number:
            extra = info_f.json_schema_extra if isinstance(info_f.json_schema_extra, dict) else {}
            v = with_units(v, extra.get("unit", ""), words, extra.get("columns"))
        if number and has_text(v, words):
            raise ValueError(f"numbers, got {v!r}")
        return v


def fields_of(model: type[BaseModel]) -> dict[str, FieldInfo]:
    return {(f.alias or n): f for n, f in model.model_fields.items()}


def problem_lines(err) -> list[str]:
    """pydantic's errors (a ``ValidationError``) as ``section.key: message`` lines, a model
    validator's own lines (``Problems``) as they are; an item k of a list of tables named
    ``pass`` (a schedule's passes) as ``pass[k+1]``. For the files besides the case
    (schedules, studies); the case has its own (``config._problems``)."""
    out = []
    for e in err.errors():
        exc = (e.get("ctx") or {}).get("error")
        if isinstance(exc, Problems):
            loc = e["loc"]
            if len(loc) >= 2 and loc[0] == "pass" and isinstance(loc[1], int):
                out += [f"pass[{loc[1] + 1}].{q}" for q in exc.problems]
            else:
                out += exc.problems
            continue
        loc = [str(x) for x in e["loc"]]
        if len(loc) >= 2 and loc[0] == "pass" and loc[1].isdigit():
            loc = [f"pass[{int(loc[1]) + 1}]"] + loc[2:]
        msg = e["msg"]
        if e["type"] == "extra_forbidden":
            msg = "unknown key"
        elif e["type"] == "missing":
            msg = "missing required key"
        elif e["type"] == "value_error" and exc is not None:
            msg = str(exc)            # a validator's own words, which name the value given
        else:
            msg = f"{msg[0].lower()}{msg[1:]}, got {e.get('input')!r}"
        out.append(f"{'.'.join(loc)}: {msg}")
    return out
