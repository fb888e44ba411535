"""A study file (issue 18): a base case and the parameters to vary, validated before any run.

    name = "m_and_speed"
    [base]
    file = "case.toml"            # relative to the study file; or example = "hot_strip_finishing"
    [vary]                        # dotted case keys -> lists of values; their product is run
    "material.m" = [0.15, 0.2, 0.25]
    "pass.roll_angular_velocity" = [1.0, 2.0]
    [run]
    combine = "product"           # or "zip": the lists side by side (equal lengths)
    warm_start = true             # a worker starts each case from its neighbour (app/sweep.py)

Every combination becomes a case (``StudyCase``); a combination the case schema refuses is
not an error of the study: it is a row with status "bad_input" and the reason.
"""
from __future__ import annotations

import copy
import itertools
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

from pydantic import Field, ValidationError, field_validator, model_validator

from ..app.config import Case, CaseError, case_from_dict, set_dotted
from ..app.config_base import _field, _Problems, _Section, problem_lines


class BaseConfig(_Section):
    file: str | None = _field(None, "the base case file, relative to the study file", "",
                              "a path")
    example: str | None = _field(None, "or a bundled example case by name", "",
                                 "a name of hotroll/app/examples")

    @model_validator(mode="after")
    def _one(self) -> BaseConfig:
        if (self.file is None) == (self.example is None):
            raise _Problems(["base: give exactly one of file and example"])
        return self


class RunConfig(_Section):
    combine: Literal["product", "zip"] = _field(
        "product", "how the [vary] lists combine: every combination, or side by side", "",
        '"product" or "zip"')
    warm_start: bool = _field(True, "start each case from the nearest case its worker solved",
                              "", "true or false")


class Study(_Section):
    name: str = Field("study", description="study name")
    base: BaseConfig
    vary: dict[str, list[Any]] = Field(..., description="dotted case keys -> values")
    run: RunConfig = Field(default_factory=RunConfig)

    @field_validator("vary")
    @classmethod
    def _vary(cls, v: dict) -> dict:
        if not v:
            raise ValueError("give at least one dotted case key with a list of values")
        for key, values in v.items():
            if "." not in key:
                raise ValueError(f"{key!r}: a dotted case key (section.key), e.g. material.m")
            if not values:
                raise ValueError(f"{key!r}: an empty list of values")
        return v

    @model_validator(mode="after")
    def _lengths(self) -> Study:
        if self.run.combine == "zip" and len({len(x) for x in self.vary.values()}) > 1:
            raise _Problems(["vary: with run.combine = \"zip\" every list needs the same length, "
                             f"got {[len(x) for x in self.vary.values()]}"])
        return self

    def combinations(self) -> list[dict[str, Any]]:
        keys = list(self.vary)
        lists = [self.vary[k] for k in keys]
        rows = itertools.product(*lists) if self.run.combine == "product" else zip(*lists)
        return [dict(zip(keys, r)) for r in rows]


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
    return re.sub(r"[^A-Za-z0-9_.=,+-]", "_", ",".join(parts))


def _short(v: Any) -> str:
    return f"{v:.6g}" if isinstance(v, float) else str(v)


def load_study(path: str | Path) -> tuple[Study, dict]:
    """The validated study and its base case as a dict (TOML names); CaseError naming the
    field."""
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
    return study, _base_dict(study, path.parent)


def _base_dict(study: Study, root: Path) -> dict:
    from ..app.examples import example_path

    if study.base.file is not None:
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
    try:
        case_from_dict(data, str(src))
    except CaseError as e:
        raise CaseError([f"base case: {p}" for p in e.problems], str(src), "study") from None
    return data


def expand(study: Study, base: dict) -> list[StudyCase]:
    """Every combination as a case (one thread each: a worker is one core); an invalid one
    keeps its reason."""
    out = []
    for i, values in enumerate(study.combinations()):
        name = label(values)
        try:
            data = set_dotted(copy.deepcopy(base), {**values, "solver.threads": 1})
            data["name"] = f"{base.get('name', 'case')} {name}"
            out.append(StudyCase(i, name, values, case_from_dict(data)))
        except CaseError as e:
            out.append(StudyCase(i, name, values, None, "; ".join(e.problems)))
    return out
