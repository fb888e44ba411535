"""A study file (issue 18): a base case and the parameters to vary, validated before any run.

    name = "m_and_speed"
    [base]
    file = "case.toml"            # relative to the study file; or example = "hot_strip_finishing"
    set = { "solver.method" = "steady" }      # dotted keys set on the base case
    [vary]                        # dotted case keys -> values; their product is run
    "material.m" = [0.15, 0.2, 0.25]                           # a list
    "pass.roll_angular_velocity" = { start = 1.0, stop = 3.0, num = 5 }   # a range (ends in)
    "material.K" = { start = 1e3, stop = 1e6, num = 4, scale = "log" }
    [[cases]]                     # and/or a table of cases: each row's keys set together
    "pass.exit_thickness" = 0.4
    "friction.law" = "coulomb"
    [run]
    combine = "product"           # or "zip": the [vary] lists side by side (equal lengths)
    warm_start = true             # a worker starts each case from its neighbour (workflows/sweep.py)
    [plot]                        # study.png drawn from the table (results/study_plot.py)
    x = "material.m"
    y = ["roll_force", "forward_slip"]
    lines = "pass.roll_angular_velocity"     # one line per value (optional)

The combinations: each row of ``[[cases]]`` (or ``cases_file``, a CSV whose header names the
dotted keys) times every combination of ``[vary]``. Every combination becomes a case
(``StudyCase``); a combination the case schema refuses is not an error of the study: it is a
row with status "bad_input" and the reason.
"""
from __future__ import annotations

import copy
import itertools
import math
import re
import tomllib
import typing
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

from pydantic import Field, ValidationError, field_validator, model_validator

from hotroll.config.base import Problems, Section, field, fields_of, problem_lines, with_units
from hotroll.config.case import Case, CaseError, case_from_dict, set_dotted
from hotroll.config.schedule import PassEntry, Schedule, schedule_from_dict
from hotroll.examples import example_path, schedule_path


class BaseConfig(Section):
    file: str | None = field(None, "the base case file, relative to the study file", "",
                              "a path")
    example: str | None = field(None, "or a bundled example case by name", "",
                                 "a name of hotroll/examples/cases")
    schedule: str | None = field(None, "or a pass schedule: its file (relative to the study "
                                  "file) or a bundled schedule's name", "",
                                  "a path or finishing_mill")
    set: dict[str, Any] = field({}, "dotted case keys set on the base case", "",
                                 'e.g. { "solver.method" = "steady" }')

    @model_validator(mode="after")
    def _one(self) -> BaseConfig:
        if sum(x is not None for x in (self.file, self.example, self.schedule)) != 1:
            raise Problems(["base: give exactly one of file, example and schedule"])
        return self


class Range(Section):
    """Evenly spaced values from start to stop, both included: ``num`` of them, or every
    ``step``; ``scale = "log"``: evenly spaced logarithms (``num`` only)."""

    start: float = field(..., "first value", "", "a number")
    stop: float = field(..., "last value (included)", "", "a number")
    num: int | None = field(None, "how many values", "", "2..100000", ge=2, le=100_000)
    step: float | None = field(None, "or the spacing", "", "> 0", gt=0)
    scale: Literal["linear", "log"] = field("linear", "spacing", "", '"linear" or "log"')

    @model_validator(mode="after")
    def _one(self) -> Range:
        if (self.num is None) == (self.step is None):
            raise Problems(["give exactly one of num and step"])
        if self.scale == "log" and (self.step is not None or self.start <= 0 or self.stop <= 0):
            raise Problems(['scale = "log" needs num and start, stop > 0'])
        if self.step is not None and not 1 <= (self.stop - self.start) / self.step + 1 <= 100_000:
            raise Problems([f"step: from {self.start:g} to {self.stop:g} by {self.step:g} is "
                             "not 1..100000 values (stop must not be below start)"])
        return self

    def values(self) -> list[float]:
        import numpy as np

        if self.scale == "log":
            v = np.geomspace(self.start, self.stop, self.num)
        elif self.num is not None:
            v = np.linspace(self.start, self.stop, self.num)
        else:
            n = int(math.floor((self.stop - self.start) / self.step * (1 + 1e-12))) + 1
            v = self.start + self.step * np.arange(n)
        return [float(f"{x:.12g}") for x in v]


class PlotConfig(Section):
    x: str = field(..., "the table's column on the x axis (a varied key or a summary field)",
                    "", "a column of study.csv")
    y: list[str] = field(["roll_force"], "summary fields, one panel each", "",
                          "columns of study.csv")
    lines: str | None = field(None, "a varied key: one line per value", "",
                               "a column of study.csv")
    xscale: Literal["linear", "log"] = field("linear", "x axis", "", '"linear" or "log"')
    profiles: bool = field(False, "also the contact profiles of the finished cases overlaid "
                            "(study_profiles.png)", "", "true or false")


class RunConfig(Section):
    combine: Literal["product", "zip"] = field(
        "product", "how the [vary] lists combine: every combination, or side by side", "",
        '"product" or "zip"')
    warm_start: bool = field(True, "start each case from the nearest case its worker solved",
                              "", "true or false")


def _difference(step: Any) -> Any:
    """A range's step is a difference: "50 degC" is 50 K, not 323.15 K (pint's delta units)."""
    if not isinstance(step, str):
        return step
    for offset, delta in (("°C", "delta_degC"), ("degC", "delta_degC"), ("°F", "delta_degF"),
                          ("degF", "delta_degF")):
        if offset in step and "delta_" not in step:
            return step.replace(offset, delta)
    return step


class Study(Section):
    name: str = Field("study", description="study name")
    base: BaseConfig
    vary: dict[str, list[Any] | Range] = Field({}, description="dotted case keys -> values")
    cases: list[dict[str, Any]] = Field([], description="a table of cases: dotted keys -> value")
    cases_file: str | None = Field(None, description="or a CSV of cases (header: dotted keys)")
    run: RunConfig = Field(default_factory=RunConfig)
    plot: PlotConfig | None = None

    @field_validator("vary", mode="before")
    @classmethod
    def _vary_units(cls, v: Any) -> Any:
        """Values with units ("5 mm", a range's start, stop and step) in the key's SI unit."""
        if not isinstance(v, dict):
            return v
        out = {}
        for key, values in v.items():
            unit = key_unit(key) if isinstance(key, str) else "-"
            if isinstance(values, dict):
                values = {k: with_units(_difference(x) if k == "step" else x, unit)
                          if k in ("start", "stop", "step") else x for k, x in values.items()}
            elif isinstance(values, list):
                values = [with_units(x, unit) for x in values]
            out[key] = values
        return out

    @field_validator("vary")
    @classmethod
    def _vary(cls, v: dict) -> dict:
        for key, values in v.items():
            _dotted(key)
            if isinstance(values, list) and not values:
                raise ValueError(f"{key!r}: an empty list of values")
        return {k: x.values() if isinstance(x, Range) else x for k, x in v.items()}

    @field_validator("cases")
    @classmethod
    def _cases(cls, v: list) -> list:
        for row in v:
            if not row:
                raise ValueError("an empty row of [[cases]]")
            for key in row:
                _dotted(key)
        return [{k: with_units(x, key_unit(k)) for k, x in row.items()} for row in v]

    @model_validator(mode="after")
    def _lengths(self) -> Study:
        if not self.vary and not self.cases and self.cases_file is None:
            raise Problems(["vary: give [vary] (dotted case keys with lists or ranges of "
                             "values), [[cases]] or cases_file"])
        if self.run.combine == "zip" and len({len(x) for x in self.vary.values()}) > 1:
            raise Problems(["vary: with run.combine = \"zip\" every list needs the same length, "
                             f"got {[len(x) for x in self.vary.values()]}"])
        self.check_keys()
        return self

    def check_keys(self) -> None:
        """A key in both [[cases]] and [vary] is refused; ``plot.lines`` must be varied (after
        ``cases_file`` is read: ``load_study`` calls this again)."""
        both = sorted({k for r in self.cases for k in r} & set(self.vary))
        if both:
            raise Problems([f"vary: {', '.join(both)} also in [[cases]]/cases_file: give each "
                             "key in one of them"])
        varied = set(self.vary) | {k for r in self.cases for k in r}
        if self.plot is not None and self.plot.lines is not None and \
                self.plot.lines not in varied and (self.cases_file is None or self.cases):
            raise Problems([f"plot.lines: {self.plot.lines!r} is not a varied key "
                             f"({', '.join(sorted(varied)) or 'none'})"])

    def combinations(self) -> list[dict[str, Any]]:
        """Each row of the cases table (one empty row without one) times the [vary] grid."""
        keys = list(self.vary)
        lists = [self.vary[k] for k in keys]
        grid = itertools.product(*lists) if self.run.combine == "product" or not keys \
            else zip(*lists)
        grid = [dict(zip(keys, r)) for r in grid]
        return [{**row, **g} for row in (self.cases or [{}]) for g in grid]


def key_unit(dotted: str) -> str:
    """The unit of a dotted case key from the case schema (``[m]`` of its description), or of
    a schedule's (``strip.temperature``, ``pass[2].exit_thickness``), else "-"."""
    section, _, key = dotted.partition(".")
    text = ""
    for schema in (Case, Schedule):
        try:
            model = PassEntry if section.startswith("pass[") else fields_of(schema)[section].annotation
            *tables, last = key.split(".")          # a roll's own table: pass.lower.roll_radius
            for name in tables:
                model = next(a for a in typing.get_args(fields_of(model)[name].annotation)
                             if isinstance(a, type))
            text = fields_of(model)[last].description or ""
            break
        except (KeyError, AttributeError, TypeError, StopIteration):
            continue
    found = re.search(r"\[([^\]]*)\]; allowed", text)      # field's "text [unit]; allowed"
    return found.group(1) if found else "-"


def _dotted(key: str) -> None:
    if "." not in key:
        raise ValueError(f"{key!r}: a dotted case key (section.key), e.g. material.m")


@dataclass
class StudyCase:
    """One combination: its label, the varied values, the validated case or the reason."""

    index: int
    label: str
    values: dict[str, Any]
    case: Case | None
    problem: str | None = None


def label(values: dict[str, Any]) -> str:
    """A directory name of the varied values: ``material.m=0.2,pass.roll_...=1``."""
    parts = [f"{k}={_short(v)}" for k, v in values.items()]
    text = re.sub(r"[^A-Za-z0-9_.=,+-]", "_", ",".join(parts)) or "base"
    if len(text) > 120:             # a file name has at most 255 bytes: cut, keep it unique
        import hashlib

        text = text[:100] + "-" + hashlib.sha1(text.encode()).hexdigest()[:12]
    return text


def _short(v: Any) -> str:
    return f"{v:.6g}" if isinstance(v, float) else str(v)


def load_study(path: str | Path, overrides: dict[str, Any] | None = None) -> tuple[Study, dict]:
    """The validated study and its base case as a dict (TOML names), ``overrides`` (dotted
    keys) set on the base after the file's ``base.set``; CaseError naming the field."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise CaseError(f"cannot read study file: {e.strerror or e}", str(path), "study") from None
    except tomllib.TOMLDecodeError as e:
        raise CaseError(f"TOML syntax error: {e}", str(path), "study") from None
    data.setdefault("name", path.stem)
    try:
        study = Study.model_validate(data)
    except ValidationError as e:
        raise CaseError(problem_lines(e), str(path), "study") from None
    if study.cases_file is not None:
        study.cases = study.cases + _read_cases(path.parent / study.cases_file, str(path))
        try:
            study.check_keys()
        except Problems as e:
            raise CaseError(e.problems, str(path), "study") from None
    if overrides:
        study.base.set = {**study.base.set, **overrides}
    return study, _base_dict(study, path.parent)


def _read_cases(csv_path: Path, source: str) -> list[dict[str, Any]]:
    """The rows of a CSV of cases; a cell that reads as a number is one, a number with a unit
    ("6 mm") the key's SI value."""
    import csv

    try:
        with open(csv_path, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise CaseError(f"cases_file: cannot read {csv_path}: {e.strerror or e}", source,
                        "study") from None
    if not rows:
        raise CaseError(f"cases_file: {csv_path} has no rows under its header", source, "study")
    bad = [k for k in rows[0] if k is None or "." not in k]
    if bad:
        raise CaseError(f"cases_file: header {bad!r}: dotted case keys (section.key)", source,
                        "study")
    for n, r in enumerate(rows, 2):
        if None in r:
            raise CaseError(f"cases_file: {csv_path} line {n} has more cells than the header",
                            source, "study")
    return [{k: with_units(parse_value(v), key_unit(k)) for k, v in r.items() if v not in ("", None)}
            for r in rows]


def parse_value(text: str) -> Any:
    """A value written as text (a CSV cell, ``--set key=VALUE``): what TOML reads it as
    (number, boolean, list, quoted text), true/false in any case, else the text itself."""
    text = text.strip()
    if text.lower() in ("true", "false"):
        return text.lower() == "true"
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def _base_dict(study: Study, root: Path) -> dict:
    data = _read_base(study, root)
    try:
        _set(study, data, study.base.set)
        _validate(study, data)
    except CaseError as e:
        raise CaseError([f"base case: {p}" for p in e.problems], None, "study") from None
    return data


def _read_base(study: Study, root: Path) -> dict:
    if study.base.schedule is not None:
        src = root / study.base.schedule
        if not src.is_file():
            try:
                src = schedule_path(study.base.schedule)
            except FileNotFoundError as e:
                raise CaseError(f"base.schedule: neither a file nor {e}", None,
                                "study") from None
    elif study.base.file is not None:
        src = (root / study.base.file)
    else:
        try:
            src = example_path(study.base.example)
        except FileNotFoundError as e:
            raise CaseError(f"base.example: {e}", None, "study") from None
    try:
        data = tomllib.loads(src.read_text(encoding="utf-8"))
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise CaseError(f"base.file: cannot read the base case {src}: {e}", None,
                        "study") from None
    data.setdefault("name", src.stem)
    return data


def expand(study: Study, base: dict) -> list[StudyCase]:
    """Every combination as a case, or a schedule (``StudyCase.case`` a ``Schedule``); an
    invalid one keeps its reason. The threads stay the case's: a worker's assembly takes a
    second core only while no other worker wants it (``fem/reproducible.threads_now``)."""
    out, seen = [], set()
    for i, values in enumerate(study.combinations()):
        name = label(values)
        if name in seen:                 # values equal to 6 digits, or a repeated row
            name = f"{name}-{i}"
        seen.add(name)
        try:
            data = _set(study, copy.deepcopy(base), values)
            data["name"] = f"{base.get('name', 'case')} {name}"
            out.append(StudyCase(i, name, values, _validate(study, data)))
        except CaseError as e:
            out.append(StudyCase(i, name, values, None, "; ".join(e.problems)))
    return out


def _validate(study: Study, data: dict):
    if study.base.schedule is None:
        return case_from_dict(data)

    return schedule_from_dict(data)


def _set(study: Study, data: dict, dotted: dict[str, Any]) -> dict:
    """``set_dotted`` for a case; for a schedule also ``pass[k].key`` (pass k, from 1) and
    ``pass[*].key`` (every pass), e.g. ``pass[2].exit_thickness``, ``pass[*].roll_radius``."""
    if study.base.schedule is None:
        return set_dotted(data, dotted)
    plain = {}
    for key, value in dotted.items():
        found = re.match(r"^pass\[(\d+|\*)\]\.(.+)$", key)
        if not found:
            plain[key] = value
            continue
        passes = data.get("pass") or []
        which = range(len(passes)) if found.group(1) == "*" else [int(found.group(1)) - 1]
        for k in which:
            if not 0 <= k < len(passes):
                raise CaseError(f"{key}: the schedule has passes 1..{len(passes)}")
            set_dotted(passes[k], {found.group(2): value})
    return set_dotted(data, plain)
