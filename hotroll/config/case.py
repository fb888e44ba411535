"""Validated case description (TOML -> pydantic models), SI units throughout.

A case file has the sections ``[pass]``, ``[plate]``, ``[material]`` (required)
and ``[friction]``, ``[mesh]``, ``[solver]``, ``[output]``, ``[thermal]`` (optional).  Every
problem is reported as ``<section.key>: <what is wrong; allowed range>`` in a
single :class:`CaseError`. The shared helpers are in ``config_base.py``, the law sections
(``[material]``, ``[friction]``) in ``config_laws.py``, the geometry and numerics sections in
``config_sections.py``, ``[thermal]`` in ``config_thermal.py``.
"""

from __future__ import annotations

import json
import tomllib
import typing
from dataclasses import replace
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator
from pydantic.fields import FieldInfo

from hotroll.config import plausibility
from hotroll.config.base import MESH_TABLE, CaseError, Problems, Section, fields_of
from hotroll.config.friction import FrictionConfig
from hotroll.config.material import MaterialConfig
from hotroll.config.roll_sides import SIDES
from hotroll.config.sections import (  # noqa: F401 (re-exported)
    MAX_LENGTH,
    ContactConfig,
    MeshConfig,
    OutputConfig,
    PassConfig,
    PlateConfig,
    RollConfig,
    SolverConfig,
    check_profile,
)
from hotroll.config.spread import SpreadConfig
from hotroll.config.spread import problems as spread_problems
from hotroll.config.thermal import ThermalConfig
from hotroll.config.units import ENGINEERING, UnitError, shown
from hotroll.model.geometry import auto_contact_size
from hotroll.model.grades import get_grade
from hotroll.model.roll_gap import RollFriction, RollGap
from hotroll.model.strip_elasticity import family_modulus

__all__ = ["MESH_TABLE", "Case", "CaseError", "FrictionConfig", "MaterialConfig", "case_from_dict",
           "case_from_toml", "load_case", "flat"]


class Case(Section):
    """A complete rolling case."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, populate_by_name=True)

    name: str = Field("case", description="case name (used for output folders)")
    pass_: PassConfig = Field(..., alias="pass", description="roll and pass geometry")
    plate: PlateConfig = Field(..., description="plate")
    material: MaterialConfig = Field(..., description="flow-stress law, its parameters and the strip's thermal data")
    friction: FrictionConfig = Field(default_factory=FrictionConfig, description="friction law")
    mesh: MeshConfig = Field(default_factory=MeshConfig, description="mesh sizes")
    solver: SolverConfig = Field(default_factory=SolverConfig, description="solver settings")
    contact: ContactConfig = Field(default_factory=ContactConfig,
                                   description="roll contact formulation")
    output: OutputConfig = Field(default_factory=OutputConfig, description="output switches")
    roll: RollConfig = Field(default_factory=RollConfig,
                             description="the work roll: rigid, Hitchcock's flattening or elastic")
    spread: SpreadConfig | None = Field(
        None, description="the 3D pass across the width (needs pass.width); present: the "
        "spread, the exit width and the whole width's force from it, absent: plane strain")
    thermal: ThermalConfig | None = Field(
        None, description="heat sources and losses; present: the coupled thermo-mechanical "
        "problem, absent: isothermal at plate.temperature")

    @model_validator(mode="after")
    def _check_sizes(self) -> Case:
        lc, problems = self.pass_.contact_length, []
        if self.mesh.h_contact == "auto":
            self.mesh._auto_h = auto_contact_size(self.pass_.roll_pass())
        if self.plate.length < 3 * lc:
            problems.append(f"plate.length: must be >= 3 x projected contact length = "
                            f"{3 * lc:.6g} m, got {self.plate.length:g} m")
        h = self.mesh.h
        if h >= lc / 4:
            shown = f"{self.mesh.h_contact} = {h:g}" if isinstance(self.mesh.h_contact, str) else f"{h:g}"
            problems.append(f"mesh.h_contact: must be < contact_length/4 = {lc / 4:.6g} m, "
                            f"got {shown} m")
        half_exit = self.pass_.exit_thickness / 2
        if h > half_exit / 4:
            problems.append(f"mesh.h_contact: must be <= exit half-thickness/4 = "
                            f"{half_exit / 4:.6g} m (4 elements through the exit half-"
                            f"thickness), got {h:g} m")
        if self.mesh.h_far is not None and self.mesh.h_far < h:
            problems.append(f"mesh.h_far: must be >= mesh.h_contact ({h:g} m), "
                            f"got {self.mesh.h_far:g} m")
        problems += self.material.problems_at(self.plate.temperature,
                                              self.plate.mean_entry_strain)
        if self.thermal is not None:
            problems += [f"material.{key}: missing, required with a [thermal] section "
                         f"({fields_of(MaterialConfig)[key].description})"
                         for key in ("density", "specific_heat", "conductivity")
                         if getattr(self.material, key) is None]
        for key in ("temperature_profile", "strain_profile"):
            if getattr(self.plate, key) is not None and self.solver.method != "steady":
                problems.append(f"plate.{key}: needs solver.method = \"steady\" (the report's "
                                f"scheme starts from a uniform plate), got "
                                f"\"{self.solver.method}\"")
        if self.contact.method == "multiplier" and self.solver.method != "steady":
            problems.append('contact.method: "multiplier" needs solver.method = "steady" (the '
                            'report\'s scheme has the penalty contact of Table 1), got '
                            f'"{self.solver.method}"')
        if self.contact.strip_youngs_modulus not in ("auto", "off") and not self._exact_steady:
            problems.append("contact.strip_youngs_modulus: a number needs solver.method = "
                            "\"steady\" with exact contact (the strip's elasticity enters the "
                            "multiplier's constraint); \"auto\" or \"off\" otherwise")
        if self.contact.strip_youngs_modulus == "auto" and self._auto_family is not None:
            try:
                family_modulus(self._auto_family).youngs_modulus(self.plate.temperature)
            except ValueError as e:
                problems.append(f"contact.strip_youngs_modulus: \"auto\": {e} (the "
                                f"plate.temperature); give the modulus in Pa or \"off\"")
        if self.contact.unilateral is True and self.plate.free_surface != "traced":
            problems.append("contact.unilateral: true needs plate.free_surface = \"traced\" "
                            "(the top after the contact's end is a traced free surface)")
        if self.contact.unilateral is True and self.solver.method != "steady":
            problems.append("contact.unilateral: true needs solver.method = \"steady\" (the "
                            "report's scheme holds the strip to the roll up to the exit point, "
                            "its (2.28a); set it to \"auto\" or false)")
        if self.roll.model != "rigid" and self.solver.method != "steady":
            problems.append(f'roll.model: "{self.roll.model}" needs solver.method = "steady" '
                            '(the report\'s scheme rolls with the rigid roll), got '
                            f'"{self.solver.method}"')
        for side in ("upper", "lower"):
            own = getattr(self.roll, side)
            if own is not None and own.model not in (None, "rigid") \
                    and self.solver.method != "steady":
                problems.append(f'roll.{side}.model: "{own.model}" needs solver.method = '
                                f'"steady" (the report\'s scheme rolls with the rigid roll), '
                                f'got "{self.solver.method}"')
        if self.pass_.roll_gap is not None and self.solver.method != "steady":
            problems.append('pass.roll_gap: needs solver.method = "steady" (the exit thickness '
                            f'is found by repeated steady solves), got "{self.solver.method}"')
        if self.plate.temperature_profile is not None and self.thermal is None:
            problems.append("plate.temperature_profile: needs a [thermal] section (an isothermal "
                            "run has one temperature, plate.temperature)")
        problems += spread_problems(self)
        if not problems and not self.solver.force:
            problems += [f"{line} (solver.force = true or --force runs it anyway)"
                         for line in plausibility.refusals(self)]
        if problems:
            raise Problems(problems)
        return self

    def roll_gap(self) -> RollGap:
        """The stand's two rolls: radius and speed ([pass], [pass.upper], [pass.lower],
        pass.speed_ratio), friction (None: [friction]'s; a side's table that changes nothing is
        [friction]'s) and model ([roll], [roll.upper], [roll.lower])."""
        gap = self.pass_.two_rolls()
        base = _friction_data(self.friction)
        rolls = []
        for roll in (gap.upper, gap.lower):
            name = SIDES[roll.side]
            own = getattr(self.friction, name)
            data = None if own is None else _friction_data(own)
            friction = None if data is None or data == base else RollFriction(
                data.pop("law"), tuple(sorted(data.items())))
            rolls.append(replace(roll, friction=friction, model=self.roll.model_of(roll.side)))
        return replace(gap, upper=rolls[0], lower=rolls[1])

    def warnings(self) -> list[str]:
        """What a run of this case reports and goes on with (``config/plausibility.py``): a
        pass outside its flow-stress fit's ranges, a steel below austenite, a nondimensional
        case; a 3D pass on a mesh not refined at the contact's start (its mass balance); each
        a ``section.key: ...`` line."""
        out = plausibility.warnings(self)
        if self.spread is not None and self.mesh.corner_refinement <= 1.0:
            out.append("mesh.corner_refinement: 1 (none) with [spread]: the 3D pass carries the "
                       "traced top's mass leak at the contact's start, 5-10e-4 of the inflow; "
                       "16 brings it below 1e-4 for 12-14 % more unknowns (docs/theory.md 4e)")
        return out

    @property
    def _exact_steady(self) -> bool:
        return (self.solver.method == "steady"
                and self.contact.resolved(self.solver.method) == "multiplier")

    @property
    def _auto_family(self) -> str | None:
        """The grade family whose E(T) ``strip_youngs_modulus = "auto"`` takes, or None (no
        grade, or not the steady solver's exact contact with traced tops: rigid-plastic)."""
        if not (self._exact_steady and self.plate.free_surface == "traced"
                and self.material.grade is not None):
            return None
        return get_grade(self.material.grade).family

    @property
    def strip_elasticity(self) -> tuple[float, float] | None:
        """(E_s Pa, nu_s) of the strip in the contact (docs/theory.md 1e), or None:
        rigid-plastic. ``strip_youngs_modulus = "auto"``: the grade family's E(T) at
        plate.temperature (model/strip_elasticity.py)."""
        c = self.contact
        if c.strip_youngs_modulus == "off":
            return None
        family = self._auto_family
        if c.strip_youngs_modulus == "auto":
            if family is None:
                return None
            law = family_modulus(family)
            nu = law.nu if c.strip_poissons_ratio == "auto" else c.strip_poissons_ratio
            return law.youngs_modulus(self.plate.temperature), nu
        nu = c.strip_poissons_ratio
        if nu == "auto":
            nu = family_modulus(family).nu if family is not None else 0.3
        return float(c.strip_youngs_modulus), nu

    @property
    def dt(self) -> float:
        """Time step in s (rule "h/6" resolved with the contact mesh size)."""
        ts = self.solver.time_step
        return self.mesh.h / 6.0 if ts == "h/6" else float(ts)

    def to_dict(self) -> dict[str, Any]:
        """Plain dict with TOML names (``pass``); unset optional keys left out."""
        return self.model_dump(by_alias=True, exclude_none=True)

    def with_overrides(self, **dotted: Any) -> Case:
        """New validated Case with ``{"section.key": value}`` replaced (None = automatic)."""
        return case_from_dict(set_dotted(self.to_dict(), dotted))

    def to_toml(self) -> str:
        """TOML text that round-trips through :func:`case_from_toml`: SI numbers, each line's
        comment the key's description, led by the value in an engineer's unit where it has one
        ("= 6 mm", "= 1000 degC": ``config/units.shown``)."""
        data = self.to_dict()
        lines = [f"name = {_toml_value(data.pop('name'))}"]
        tables = [(section, _model_of(Case, section), values)
                  for section, values in data.items()]
        for section, model, values in tables:
            lines += ["", f"[{section}]"]
            for key, value in values.items():
                if isinstance(value, dict):          # a roll's own table, after the section's
                    tables.append((f"{section}.{key}", _model_of(model, key), value))
                    continue
                info = fields_of(model)[key]
                unit = (info.json_schema_extra or {}).get("unit", "") \
                    if isinstance(info.json_schema_extra, dict) else ""
                eng = (f"= {shown(float(value), unit)}; "
                       if unit in ENGINEERING and isinstance(value, (int, float))
                       and not isinstance(value, bool) else "")
                lines.append(f"{key} = {_toml_value(value)}".ljust(36)
                             + f"  # {eng}{info.description}")
        return "\n".join(lines) + "\n"


def _friction_data(section) -> dict:
    """A friction table's keys as given or defaulted, without its per-roll tables."""
    return section.model_dump(exclude_none=True, exclude={"upper", "lower"})


# --------------------------------------------------------------------------- I/O


def set_dotted(data: dict, dotted: dict[str, Any]) -> dict:
    """``data`` (a case dict, TOML names) with ``{"section.key": value}`` set in place."""
    for key, value in dotted.items():
        parts = key.split(".")
        parts[0] = "pass" if parts[0] == "pass_" else parts[0]
        node = data
        for p in parts[:-1]:
            node = node.setdefault(p, {})
            if not isinstance(node, dict):
                raise CaseError(f"{key}: '{p}' is not a section")
        node[parts[-1]] = value
    return data


def case_from_dict(d: Any, source: str | None = None) -> Case:
    """Validate a plain dict (TOML names) into a Case; raises CaseError."""
    if not isinstance(d, dict):
        raise CaseError(f"case: must be a table of sections, got {type(d).__name__}", source)
    try:
        return Case.model_validate(d)
    except ValidationError as e:
        raise CaseError(_problems(e, d), source) from None


def case_from_toml(text: str, source: str | None = None) -> Case:
    """Parse and validate TOML text; raises CaseError."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise CaseError(f"TOML syntax error: {e}", source) from None
    return case_from_dict(data, source)


def load_case(path: str | Path, overrides: dict[str, Any] | None = None) -> Case:
    """Read a TOML case file; ``name`` defaults to the file stem; ``overrides`` (dotted keys,
    the command line's options) set before the one validation, so that ``solver.force`` can
    let a refused case run."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise CaseError(f"cannot read case file: {e.strerror or e}", str(path)) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise CaseError(f"TOML syntax error: {e}", str(path)) from None
    data.setdefault("name", path.stem)
    if overrides:
        return case_from_dict(set_dotted(data, overrides), f"{path} (with command-line options)")
    return case_from_dict(data, str(path))


# ------------------------------------------------------------------ error text


def _model_of(model: type[BaseModel], key: str) -> type[BaseModel] | None:
    """The section model of ``key`` (an optional section: the model inside ``X | None``)."""
    ann = fields_of(model)[key].annotation
    for a in (ann, *typing.get_args(ann)):
        if isinstance(a, type) and issubclass(a, BaseModel):
            return a
    return None


def _given(raw: Any, loc) -> Any:
    """What the file said at ``loc`` (None where it said nothing there)."""
    for item in loc:
        try:
            raw = raw[item]
        except (KeyError, IndexError, TypeError):
            return None
    return raw


def _problems(err: ValidationError, raw: Any = None) -> list[str]:
    """Turn pydantic errors into ``section.key: message`` lines (one per field); ``raw``: the
    input, whose text with a unit ("-300 degC") a range error quotes beside its SI value."""
    out: dict[str, str] = {}
    for e in err.errors():
        exc = (e.get("ctx") or {}).get("error")
        if isinstance(exc, Problems):
            out.update({p: p for p in exc.problems})
            continue
        path, parent, info = [], Case, None
        for item in e["loc"]:
            fields = fields_of(parent) if parent else {}
            path.append(str(item))
            if item not in fields:
                break
            info, parent = fields[item], _model_of(parent, item)
            if parent is None:
                break
        dotted = ".".join(path)
        message = _message(e, path, parent, info)
        given = _given(raw, e["loc"])
        if isinstance(given, str) and e["type"] != "value_error" and given != e.get("input"):
            message += f" (from {given!r})"
        out.setdefault(dotted, f"{dotted}: {message}")
    return list(out.values())


def _message(e: dict, path: list[str], parent: type[BaseModel] | None, info: FieldInfo | None) -> str:
    kind, got = e["type"], e.get("input")
    if kind == "extra_forbidden":
        what = "unknown section or key" if len(path) == 1 else "unknown key"
        return f"{what} (allowed: {', '.join(fields_of(parent))})"
    is_section = info is not None and parent is not None and len(path) == 1
    if kind == "missing":
        if is_section or info is None:
            return "missing required section" if is_section else "missing"
        return f"missing required key ({info.description})"
    if is_section:
        return f"must be a table [{path[0]}], got {got!r}"
    allowed = (info.json_schema_extra or {}).get("allowed") if info else None
    exc = (e.get("ctx") or {}).get("error")
    if isinstance(exc, UnitError):
        return f"{exc}; must be {allowed}" if allowed else str(exc)
    if allowed:
        return f"must be {allowed}, got {got!r}"
    return e["msg"][0].lower() + e["msg"][1:]


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def flat(d: dict, pre: str = "") -> dict:
    """Nested dict -> {"section.key": value}."""
    out = {}
    for k, v in d.items():
        out.update(flat(v, f"{pre}{k}.") if isinstance(v, dict) else {f"{pre}{k}": v})
    return out
