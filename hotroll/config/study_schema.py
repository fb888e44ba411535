"""The study file's schema (pydantic): its ``[base]``, ``[vary]`` (lists, or ``Range``s from
start to stop), ``[[cases]]``, ``[run]`` and ``[plot]`` sections validated in the SI units of the
case keys they vary (``key_unit``), and a study's combinations (``Study.combinations``). Reading
the file and expanding it into cases is ``config/study.py``."""
from __future__ import annotations

import itertools
import math
import re
import typing
from typing import Any, Literal

from pydantic import Field, field_validator, model_validator

from hotroll.config.base import Problems, Section, field, fields_of, with_units
from hotroll.config.case import Case
from hotroll.config.schedule import PassEntry, Schedule


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
