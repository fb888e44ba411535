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
row with status "bad_input" and the reason. The sections' schema is ``config/study_schema.py``;
this module reads a study file and expands it into cases.
"""
from __future__ import annotations

import copy
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from hotroll.config.base import Problems, problem_lines, with_units
from hotroll.config.case import Case, CaseError, case_from_dict, set_dotted
from hotroll.config.schedule import schedule_from_dict
from hotroll.config.study_schema import PlotConfig, Study, key_unit  # noqa: F401 (re-exported)
from hotroll.examples import example_path, schedule_path


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
