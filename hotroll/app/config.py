"""Validated case description (TOML -> pydantic models), SI units throughout.

A case file has the sections ``[pass]``, ``[plate]``, ``[material]`` (required)
and ``[friction]``, ``[mesh]``, ``[solver]``, ``[output]``, ``[thermal]`` (optional).  Every
problem is reported as ``<section.key>: <what is wrong; allowed range>`` in a
single :class:`CaseError`. The shared helpers are in ``config_base.py``, the law sections
(``[material]``, ``[friction]``) in ``config_laws.py``.
"""

from __future__ import annotations

import json
import tomllib
import typing
from pathlib import Path
from typing import Any, Literal

from pydantic import (BaseModel, ConfigDict, Field, PrivateAttr, ValidationError, field_validator,
                      model_validator)
from pydantic.fields import FieldInfo

from ..process.geometry import RollPass
from .config_base import (MESH_TABLE, CaseError, MeshName, PosFloat, _field, _fields, _Problems,
                          _Section)
from .config_laws import FrictionConfig, MaterialConfig
from .config_thermal import ThermalConfig

#: Largest length of a case (m): roll radius, thicknesses, plate length, |roll_axis_x|. Beyond
#: it the geometry's squares overflow (R = 1e300 m) or the roll position swamps the contact
#: length in double precision (roll_axis_x = 1e300 m: l_c = 0); mills are metres in size.
MAX_LENGTH = 1e3

__all__ = ["MESH_TABLE", "Case", "CaseError", "FrictionConfig", "MaterialConfig", "case_from_dict",
           "case_from_toml", "load_case", "flat"]


class PassConfig(_Section):
    """Roll and pass geometry (roll centre at x = roll_axis_x, y = exit/2 + R)."""

    roll_radius: float = _field(..., "roll radius R", "m", f"> 0 and <= {MAX_LENGTH:g}", gt=0,
                                le=MAX_LENGTH)
    entry_thickness: float = _field(..., "full plate thickness at entry", "m",
                                    f"> 0 and <= {MAX_LENGTH:g}", gt=0, le=MAX_LENGTH)
    exit_thickness: float = _field(..., "full plate thickness at exit (roll gap)", "m",
                                   "> 0 and < entry_thickness", gt=0)
    roll_angular_velocity: float = _field(..., "roll angular velocity omega", "rad/s", "> 0", gt=0)
    roll_axis_x: float = _field(1.0, "x of the roll centre (initial plate head position)", "m",
                                f"in [-{MAX_LENGTH:g}, {MAX_LENGTH:g}]", ge=-MAX_LENGTH,
                                le=MAX_LENGTH)
    back_tension: float = _field(0.0, "back tension: mean tensile stress on the entry strip",
                                 "Pa", ">= 0", ge=0)
    front_tension: float = _field(0.0, "front tension: mean tensile stress on the exit strip",
                                  "Pa", ">= 0", ge=0)
    width: PosFloat | None = _field(None, "strip width (omit: results per unit width only)", "m",
                                    "> 0")

    @model_validator(mode="after")
    def _check_geometry(self) -> PassConfig:
        problems = []
        if self.exit_thickness >= self.entry_thickness:
            problems.append(
                f"pass.exit_thickness: must be smaller than pass.entry_thickness "
                f"({self.entry_thickness:g} m), got {self.exit_thickness:g} m")
        elif self.draft >= self.roll_radius:
            problems.append(
                f"pass.roll_radius: must exceed the draft per side (entry - exit)/2 = "
                f"{self.draft:g} m, otherwise the roll cannot bite the plate; allowed: "
                f"roll_radius > {self.draft:g} m, got {self.roll_radius:g} m")
        if problems:
            raise _Problems(problems)
        return self

    @property
    def draft(self) -> float:
        """Thickness reduction per side (m)."""
        return 0.5 * (self.entry_thickness - self.exit_thickness)

    def roll_pass(self) -> RollPass:
        """The geometry object the solver uses (all derived quantities live there)."""
        return RollPass(self.roll_radius, 0.5 * self.entry_thickness, 0.5 * self.exit_thickness,
                        self.roll_angular_velocity, self.roll_axis_x)

    @property
    def half_entry(self) -> float:
        return self.roll_pass().half_entry

    @property
    def half_exit(self) -> float:
        return self.roll_pass().half_exit

    @property
    def roll_centre(self) -> tuple[float, float]:
        return self.roll_pass().centre

    @property
    def roll_surface_speed(self) -> float:
        return self.roll_pass().u_roll

    @property
    def contact_length(self) -> float:
        """Projected contact length (m)."""
        return self.roll_pass().contact_length

    @property
    def bite_angle(self) -> float:
        """Bite angle acos(1 - draft/R) (rad)."""
        return self.roll_pass().bite_angle


def check_profile(key: str, v: Any) -> Any:
    """A through-thickness profile [[eta, value], ...] (``process.profile``): eta from 0 to 1,
    temperatures > 0 K, strains >= 0; ValueError with what is wrong."""
    from ..process.profile import ProfileError, ThicknessProfile

    if v is None:
        return None
    try:
        prof = ThicknessProfile.from_pairs(v)
    except ProfileError as e:
        raise ValueError(str(e)) from None
    low = min(prof.values)
    if key == "temperature_profile" and low <= 0.0:
        raise ValueError(f"temperatures must be > 0 K, got {low:g} K")
    if key == "strain_profile" and low < 0.0:
        raise ValueError(f"strains must be >= 0, got {low:g}")
    return [tuple(p) for p in prof.pairs()]


class PlateConfig(_Section):
    length: float = _field(
        ..., "initial plate length, at least 3 x the projected contact length", "m",
        f"> 0 and <= {MAX_LENGTH:g}", gt=0, le=MAX_LENGTH)
    temperature: float = _field(
        1373.15, "plate temperature: uniform (isothermal run) or at the entry (with [thermal])",
        "K", "> 0", gt=0)
    entry_strain: float = _field(0.0, "equivalent plastic strain the plate enters with", "",
                                 ">= 0", ge=0)
    free_surface: Literal["traced", "constrained"] = _field(
        "traced", "free tops before and after the bite: traction-free streamlines (traced) or "
        "held flat by the penalty (3.2d) (constrained)", "", '"traced" or "constrained"')
    temperature_profile: list[tuple[float, float]] | None = _field(
        None, "entry temperature through the half thickness, [[eta, T], ...] with eta = "
        "y / half thickness from 0 (centre) to 1 (surface), linear between (omit: uniform "
        "plate.temperature; needs [thermal] and the steady method)", "K",
        "pairs with eta increasing strictly from 0 to 1 and T > 0")
    strain_profile: list[tuple[float, float]] | None = _field(
        None, "entry strain through the half thickness, [[eta, strain], ...] as "
        "temperature_profile (omit: uniform plate.entry_strain; steady method)", "",
        "pairs with eta increasing strictly from 0 to 1 and strain >= 0")

    @field_validator("temperature_profile", "strain_profile")
    @classmethod
    def _profile(cls, v: Any, info) -> Any:
        return check_profile(info.field_name, v)

    @property
    def mean_entry_strain(self) -> float:
        """The strain profile's section mean, or entry_strain."""
        prof = self.entry_profiles()[1]
        return self.entry_strain if prof is None else prof.mean()

    def entry_profiles(self):
        """(temperature, strain) ``ThicknessProfile`` or None each."""
        from ..process.profile import ThicknessProfile

        return tuple(None if p is None else ThicknessProfile.from_pairs(p)
                     for p in (self.temperature_profile, self.strain_profile))


class MeshConfig(_Section):
    h_contact: Literal["auto"] | MeshName | PosFloat = _field(
        "auto", "mesh size along the contact (auto: the coarsest size whose roll force is within "
        "1 % of the mesh-converged one, docs/theory.md 4e)", "m",
        '"auto", one of C1, C2, M1, M2, F1, F2 or a number > 0')
    h_far: PosFloat | None = _field(None, "coarse mesh size far from the roll (omit: automatic)",
                                    "m", "> 0 and >= h_contact")
    grading: float = _field(0.3, "mesh grading (size growth rate)", "", "in (0, 1]", gt=0, le=1)

    _auto_h: float = PrivateAttr(default=float("nan"))   # set by Case from the pass geometry

    @field_validator("h_contact", mode="before")
    @classmethod
    def _upper_name(cls, v: Any) -> Any:
        if isinstance(v, str):
            v = v.strip()
            return "auto" if v.lower() == "auto" else v.upper()
        return v

    @property
    def h(self) -> float:
        """Contact mesh size in m (Table 2 names and "auto" resolved)."""
        if self.h_contact == "auto":
            return self._auto_h
        return MESH_TABLE[self.h_contact] if isinstance(self.h_contact, str) else self.h_contact


class SolverConfig(_Section):
    method: Literal["steady", "transient"] = _field(
        "steady", "solution method: direct steady state or the report's time stepping", "",
        '"steady" or "transient"')
    nonlinear: Literal["newton", "picard"] = _field("newton", "nonlinear solver", "",
                                                    '"newton" or "picard"')
    tolerance: float = _field(1e-5, "nonlinear tolerance (Newton update / roll speed)", "",
                              "in (0, 0.1]", gt=0, le=0.1)
    max_iterations: int = _field(20, "nonlinear iterations per step", "", "an integer >= 1", ge=1)
    end_time: PosFloat | None = _field(None, "simulated time (omit: automatic)", "s", "> 0")
    time_step: Literal["h/6"] | PosFloat = _field(
        "h/6", 'time step ("h/6": dt = h_contact/6)', "s", '"h/6" or a number > 0')
    steady_tolerance: float = _field(2e-3, "steady-state detection tolerance (relative change)",
                                     "", "in (0, 0.1]", gt=0, le=0.1)
    max_steps: int = _field(100000, "maximum number of time steps", "", "an integer >= 1", ge=1)
    wall_time_limit: PosFloat | None = _field(None, "wall-clock limit (omit: none)", "s", "> 0")
    checkpoint_every: int = _field(25, "steps between checkpoints", "", "an integer >= 1", ge=1)
    threads: int = _field(2, "worker threads", "", "an integer in [1, 1024]", ge=1, le=1024)
    memory_limit: PosFloat | None = _field(
        None, "refuse a mesh whose estimated memory is above this (omit: the machine's free "
        "memory; app/estimate.py)", "B", "> 0")
    force: bool = _field(False, "run even when the memory estimate is above the limit", "",
                         "true or false")
    steady_entry_length: PosFloat | None = _field(
        None, "steady strip: flat length before the touching point (omit: automatic)", "m", "> 0")
    steady_exit_length: PosFloat | None = _field(
        None, "steady strip: flat length after the roll gap (omit: automatic)", "m", "> 0")
    exit_pressure_correction: bool = _field(True, "correct the exit pressure", "", "true or false")


class OutputConfig(_Section):
    figures: bool = _field(True, "write figures", "", "true or false")
    vtk: bool = _field(True, "write VTK files", "", "true or false")


class Case(_Section):
    """A complete rolling case."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, populate_by_name=True)

    name: str = Field("case", description="case name (used for output folders)")
    pass_: PassConfig = Field(..., alias="pass", description="roll and pass geometry")
    plate: PlateConfig = Field(..., description="plate")
    material: MaterialConfig = Field(..., description="Norton-Hoff material")
    friction: FrictionConfig = Field(default_factory=FrictionConfig, description="friction law")
    mesh: MeshConfig = Field(default_factory=MeshConfig, description="mesh sizes")
    solver: SolverConfig = Field(default_factory=SolverConfig, description="solver settings")
    output: OutputConfig = Field(default_factory=OutputConfig, description="output switches")
    thermal: ThermalConfig | None = Field(
        None, description="heat sources and losses; present: the coupled thermo-mechanical "
        "problem, absent: isothermal at plate.temperature")

    @model_validator(mode="after")
    def _check_sizes(self) -> Case:
        lc, problems = self.pass_.contact_length, []
        if self.mesh.h_contact == "auto":
            from ..discretisation.mesh import auto_contact_size

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
                         f"({_fields(MaterialConfig)[key].description})"
                         for key in ("density", "specific_heat", "conductivity")
                         if getattr(self.material, key) is None]
        for key in ("temperature_profile", "strain_profile"):
            if getattr(self.plate, key) is not None and self.solver.method != "steady":
                problems.append(f"plate.{key}: needs solver.method = \"steady\" (the report's "
                                f"scheme starts from a uniform plate), got "
                                f"\"{self.solver.method}\"")
        if self.plate.temperature_profile is not None and self.thermal is None:
            problems.append("plate.temperature_profile: needs a [thermal] section (an isothermal "
                            "run has one temperature, plate.temperature)")
        if problems:
            raise _Problems(problems)
        return self

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
        """TOML text that round-trips through :func:`case_from_toml`."""
        data = self.to_dict()
        lines = [f"name = {_toml_value(data.pop('name'))}"]
        for section, values in data.items():
            model = _model_of(Case, section)
            lines += ["", f"[{section}]"]
            for key, value in values.items():
                info = _fields(model)[key]
                lines.append(f"{key} = {_toml_value(value)}".ljust(36) + f"  # {info.description}")
        return "\n".join(lines) + "\n"


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
        raise CaseError(_problems(e), source) from None


def case_from_toml(text: str, source: str | None = None) -> Case:
    """Parse and validate TOML text; raises CaseError."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise CaseError(f"TOML syntax error: {e}", source) from None
    return case_from_dict(data, source)


def load_case(path: str | Path) -> Case:
    """Read a TOML case file; ``name`` defaults to the file stem."""
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
    return case_from_dict(data, str(path))


# ------------------------------------------------------------------ error text


def _model_of(model: type[BaseModel], key: str) -> type[BaseModel] | None:
    """The section model of ``key`` (an optional section: the model inside ``X | None``)."""
    ann = _fields(model)[key].annotation
    for a in (ann, *typing.get_args(ann)):
        if isinstance(a, type) and issubclass(a, BaseModel):
            return a
    return None


def _problems(err: ValidationError) -> list[str]:
    """Turn pydantic errors into ``section.key: message`` lines (one per field)."""
    out: dict[str, str] = {}
    for e in err.errors():
        exc = (e.get("ctx") or {}).get("error")
        if isinstance(exc, _Problems):
            out.update({p: p for p in exc.problems})
            continue
        path, parent, info = [], Case, None
        for item in e["loc"]:
            fields = _fields(parent) if parent else {}
            path.append(str(item))
            if item not in fields:
                break
            info, parent = fields[item], _model_of(parent, item)
            if parent is None:
                break
        dotted = ".".join(path)
        out.setdefault(dotted, f"{dotted}: {_message(e, path, parent, info)}")
    return list(out.values())


def _message(e: dict, path: list[str], parent: type[BaseModel] | None, info: FieldInfo | None) -> str:
    kind, got = e["type"], e.get("input")
    if kind == "extra_forbidden":
        what = "unknown section or key" if len(path) == 1 else "unknown key"
        return f"{what} (allowed: {', '.join(_fields(parent))})"
    is_section = info is not None and parent is not None and len(path) == 1
    if kind == "missing":
        if is_section or info is None:
            return "missing required section" if is_section else "missing"
        return f"missing required key ({info.description})"
    if is_section:
        return f"must be a table [{path[0]}], got {got!r}"
    allowed = (info.json_schema_extra or {}).get("allowed") if info else None
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
