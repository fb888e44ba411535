"""A pass schedule file (issue 17), validated before anything runs, SI units throughout.

    name = "finishing"
    [strip]            entry strip: thickness, width, temperature (or temperature_profile),
                       strain (or strain_profile)
    [mill]             speeds = "given" (each pass its roll speed) or "mass_flow" (tandem:
                       the first pass's speed, the others set so that every stand passes the
                       same mass flux)
    [material]         as in a case (the flow stress and the thermal data)
    [friction]         default of every pass (a pass may give its own table)
    [thermal]          as in a case: roll contact, air; required (a schedule carries T)
    [roll]             the work rolls of every stand: rigid, hitchcock or elastic (as a case)
    [contact]          the roll contact of every stand (as a case)
    [microstructure]   recrystallisation between the passes (config/microstructure.py)
    [mesh] [solver] [output]   defaults of every pass's case
    [[pass]]           roll_radius, exit_thickness (or roll_gap with mill_modulus),
                       roll_surface_speed or roll_angular_velocity, back_tension,
                       front_tension, mill_modulus, friction, name; an asymmetric pass:
                       speed_ratio, [pass.upper]/[pass.lower] (a roll's own radius and
                       speed, as a case's), [pass.friction.upper]/[pass.friction.lower],
                       isothermal (config/schedule_rolls.py)
    [pass.transport]   after the pass: duration (s) or distance (m, at the exit speed),
                       htc_air, emissivity (default [thermal]'s), strain_retained

Every pass becomes a ``Case`` (``Schedule.pass_case``) whose entry is the previous exit; the
errors name ``pass[k].key`` (k from 1) or the section.
"""
from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any, Literal

from pydantic import Field, StrictBool, ValidationError, field_validator, model_validator

from hotroll.config.base import PosFloat, Problems, Section, field, problem_lines
from hotroll.config.case import (
    Case,
    CaseError,
    ContactConfig,
    FrictionConfig,
    MaterialConfig,
    MeshConfig,
    OutputConfig,
    RollConfig,
    SolverConfig,
    case_from_dict,
    check_profile,
)
from hotroll.config.microstructure import MicrostructureConfig, check_schedule
from hotroll.config.roll_sides import RollSideConfig
from hotroll.config.schedule_rolls import asymmetric_problems, pass_rolls
from hotroll.config.sections import preloaded_gap
from hotroll.config.spread import SpreadConfig
from hotroll.config.thermal import ThermalConfig
from hotroll.model.profile import ThicknessProfile

#: The plate length of each pass's steady strip, in contact lengths.
PLATE_CONTACT_LENGTHS = 5.0


class StripConfig(Section):
    thickness: float = field(..., "full strip thickness entering the first pass", "m", "> 0",
                              gt=0)
    width: PosFloat | None = field(None, "strip width (omit: results per unit width only)",
                                    "m", "> 0")
    temperature: float = field(..., "entry temperature (uniform, or the reference with a "
                                "profile)", "K", "> 0", gt=0)
    temperature_profile: list[tuple[float, float]] | None = field(
        None, "entry temperature through the half thickness [[eta, T], ...]", "K",
        "pairs with eta increasing strictly from 0 to 1 and T > 0", columns=("", "K"))
    strain: float = field(0.0, "equivalent strain the strip enters with", "", ">= 0", ge=0)
    strain_profile: list[tuple[float, float]] | None = field(
        None, "entry strain through the half thickness [[eta, strain], ...]", "",
        "pairs with eta increasing strictly from 0 to 1 and strain >= 0")


    @field_validator("temperature_profile", "strain_profile")
    @classmethod
    def _profile(cls, v: Any, info) -> Any:
        return check_profile(info.field_name, v)


class MillConfig(Section):
    speeds: Literal["given", "mass_flow"] = field(
        "given", "roll speeds: each pass's own (given), or the first pass's and the others "
        "from the constant mass flux of a tandem mill (mass_flow)", "",
        '"given" or "mass_flow"')
    start_from_previous: bool = field(
        True, "start each pass's Newton from the previous pass mapped onto its mesh "
        "(solvers/transfer.py; false: from the slab guess, cold)", "", "true or false")
    tensions: Literal["given", "from_speeds"] = field(
        "given", "interstand tensions: each pass's own (given), or those that make every "
        "stand pass the same mass flux at the given roll speeds (from_speeds: a cold tandem, "
        "a mill log; the first pass's back and the last pass's front tension stay given)", "",
        '"given" or "from_speeds"')
    flux_tolerance: float = field(
        1e-4, "from_speeds: largest relative difference between stand k's exit mass flux and "
        "stand k+1's inlet flux", "",
        "in (0, 0.01]", gt=0, le=0.01)
    mass_flow_tolerance: float = field(
        1e-3, "mass_flow: relative flux difference between stands at which a stand's speed "
        "is accepted", "", "in (0, 0.1]", gt=0, le=0.1)


class TransportConfig(Section):
    duration: PosFloat | None = field(None, "time between the two passes", "s", "> 0")
    distance: PosFloat | None = field(
        None, "distance to the next pass (the duration is this over the strip's exit speed)",
        "m", "> 0")
    htc_air: float | None = field(None, "convection coefficient (omit: thermal.htc_air)",
                                   "W/(m^2 K)", ">= 0", ge=0)
    emissivity: float | None = field(None, "emissivity (omit: thermal.emissivity)", "",
                                      "in [0, 1]", ge=0, le=1)
    strain_retained: float = field(
        1.0, "share of the strain the strip keeps (1: no softening; 0: fully recrystallised)",
        "", "in [0, 1]", ge=0, le=1)

    @model_validator(mode="after")
    def _one_time(self) -> TransportConfig:
        if (self.duration is None) == (self.distance is None):
            raise Problems(["transport: give exactly one of duration (s) and distance (m)"])
        return self


class PassEntry(Section):
    name: str | None = Field(None, description="pass name (default P1, P2, ...)")
    roll_radius: float = field(..., "roll radius", "m", "> 0", gt=0)
    exit_thickness: PosFloat | None = field(
        None, "full exit thickness (the roll gap of rigid rolls and a rigid mill); with "
        "roll_gap: omit, it is found with the force", "m", "> 0 and < the entry thickness")
    roll_gap: PosFloat | None = field(
        None, "the no-load roll gap S set on the stand (instead of exit_thickness): the exit "
        "thickness is S + F/M (needs mill_modulus and strip.width)", "m", "> 0")
    mill_modulus: PosFloat | None = field(
        None, "the stand's modulus M (reports the stretch F/M and the gap to set; needs "
        "strip.width)", "N/m", "> 0")
    roll_surface_speed: PosFloat | None = field(None, "roll surface speed", "m/s", "> 0")

    @field_validator("roll_gap", mode="before")
    @classmethod
    def _gap_opens(cls, v: Any) -> Any:
        """A gap <= 0 is refused with what it means (``sections.preloaded_gap``)."""
        return preloaded_gap(v, "roll_gap")

    roll_angular_velocity: PosFloat | None = field(None, "roll angular velocity", "rad/s",
                                                    "> 0")
    back_tension: float = field(0.0, "back tension", "Pa", ">= 0", ge=0)
    front_tension: float = field(0.0, "front tension", "Pa", ">= 0", ge=0)
    friction: FrictionConfig | None = Field(None, description="this pass's friction (omit: "
                                            "the schedule's [friction]); its upper and lower "
                                            "tables as a case's")
    speed_ratio: PosFloat | None = field(
        None, "an asymmetric pass: the upper roll's surface speed over the lower's, as a "
        "case's pass.speed_ratio (omit: each roll at its own speed)", "", "> 0")
    upper: RollSideConfig | None = field(
        None, "the upper roll's own radius and speed, [pass.upper] after this [[pass]] (as a "
        "case's; omit: the pass's)", "",
        "a table of roll_radius, roll_angular_velocity or roll_surface_speed")
    lower: RollSideConfig | None = field(
        None, "the lower roll's own radius and speed, [pass.lower] (as [pass.upper])", "",
        "a table of roll_radius, roll_angular_velocity or roll_surface_speed")
    isothermal: StrictBool = field(
        False, "solve this pass without the temperature field: the strip leaves with the "
        "temperature profile it enters with, the transport after it still cools",
        "", "true or false")
    transport: TransportConfig | None = Field(None, description="the transport after the pass")

    @property
    def nominal_exit(self) -> float:
        """The exit thickness, or the roll gap (m): the pass's thinnest exit, which the
        checks before a run use."""
        return self.exit_thickness if self.roll_gap is None else self.roll_gap

    def angular_velocity(self) -> float | None:
        if self.roll_angular_velocity is not None:
            return self.roll_angular_velocity
        if self.roll_surface_speed is not None:
            return self.roll_surface_speed / self.roll_radius
        return None


class Schedule(Section):
    name: str = Field("schedule", description="schedule name")
    strip: StripConfig
    mill: MillConfig = Field(default_factory=MillConfig)
    material: MaterialConfig
    friction: FrictionConfig = Field(default_factory=FrictionConfig)
    thermal: ThermalConfig
    roll: RollConfig = Field(default_factory=RollConfig)
    contact: ContactConfig = Field(default_factory=ContactConfig)
    mesh: MeshConfig = Field(default_factory=MeshConfig)
    solver: SolverConfig = Field(default_factory=SolverConfig)
    output: OutputConfig = Field(default_factory=OutputConfig)
    microstructure: MicrostructureConfig = Field(default_factory=MicrostructureConfig)
    spread: SpreadConfig | None = Field(
        None, description="each pass also on the 3D strip across its width (needs "
        "strip.width): the spread per pass, each pass's exit width the next one's entry width")
    passes: list[PassEntry] = Field(..., alias="pass", min_length=1)

    @model_validator(mode="after")
    def _check(self) -> Schedule:
        problems = []
        h = self.strip.thickness
        # a tandem's flux is per unit width: with [spread] the width changes from stand to
        # stand and the next stand's flux per width with it (not carried yet)
        for key, tandem in (("speeds", "mass_flow"), ("tensions", "from_speeds")):
            if self.spread is not None and getattr(self.mill, key) == tandem:
                problems.append(f'mill.{key}: "{tandem}" not with [spread] (the stands\' mass '
                                f"flux is matched per unit width, and the spread changes the "
                                f'width from stand to stand); "given" with [spread]')
        for key in ("temperature_profile", "temperature_section"):
            if self.spread is not None and getattr(self.spread, key) is not None:
                problems.append(f"spread.{key}: not in a schedule (each pass enters with the "
                                "temperature the last pass and its transport left across the "
                                "width); a single pass's case takes it")
        for k, p in enumerate(self.passes, 1):
            if (p.exit_thickness is None) == (p.roll_gap is None):
                problems.append(f"pass[{k}]: give exactly one of exit_thickness (m) and "
                                f"roll_gap (m, with mill_modulus)")
                continue
            key = "exit_thickness" if p.roll_gap is None else "roll_gap"
            h1 = getattr(p, key)
            if h1 >= h:
                problems.append(f"pass[{k}].{key}: must be < the entry thickness "
                                f"{h:g} m (the previous {'exit' if k > 1 else 'strip'}"
                                f"{' or gap' if k > 1 else ''}), got {h1:g} m")
            h = h1
            if p.roll_gap is not None and p.mill_modulus is None:
                problems.append(f"pass[{k}].roll_gap: needs pass[{k}].mill_modulus (N/m)")
            if p.mill_modulus is not None and self.strip.width is None:
                problems.append(f"pass[{k}].mill_modulus: needs strip.width (the stand "
                                f"carries the whole width's force)")
            speed = [x for x in (p.roll_surface_speed, p.roll_angular_velocity) if x is not None]
            if self.mill.speeds == "given" or k == 1:
                if len(speed) != 1:
                    problems.append(f"pass[{k}]: give exactly one of roll_surface_speed (m/s) "
                                    f"and roll_angular_velocity (rad/s)")
            elif speed:
                problems.append(f"pass[{k}]: no roll speed with mill.speeds = \"mass_flow\" "
                                f"(it follows from the first pass's mass flux)")
            if k < len(self.passes) and p.transport is None:
                problems.append(f"pass[{k}].transport: missing; the time (or distance) to the "
                                f"next pass is needed ([pass.transport] duration or distance)")
        if self.mill.tensions == "from_speeds":
            if self.mill.speeds != "given":
                problems.append('mill.tensions: "from_speeds" needs mill.speeds = "given" '
                                f'(every stand\'s roll speed), got "{self.mill.speeds}"')
            if len(self.passes) < 2:
                problems.append('mill.tensions: "from_speeds" needs at least two passes')
        temps = [self.strip.temperature] + [T for _, T in self.strip.temperature_profile or []]
        problems += check_schedule(self.microstructure, self.material.grade, temps,
                                   [(k, p.transport) for k, p in enumerate(self.passes, 1)])
        if self.solver.method != "steady":
            problems.append("solver.method: a schedule runs the steady solver, got "
                            f"\"{self.solver.method}\"")
        if problems:
            raise Problems(problems)
        return self

    def pass_name(self, k: int) -> str:
        """The k-th pass's name (k from 0)."""
        return self.passes[k].name or f"P{k + 1}"

    def pass_case(self, k: int, entry_thickness: float, temperature: float,
                  temperature_profile=None, strain: float = 0.0, strain_profile=None,
                  angular_velocity: float | None = None,
                  tensions: tuple[float, float] | None = None,
                  width: float | None = None, temperature_section=None) -> Case:
        """The k-th pass (from 0) as a validated case entering with this state (profiles:
        ``process.profile.ThicknessProfile`` or None); ``tensions``: (back, front) in Pa
        (None: the pass's own); ``width`` (m): the strip's entering this pass (None:
        strip.width; with [spread] the last pass's exit width); ``temperature_section``: its
        entry temperature over the cross-section (``model/section.SectionProfile``, with
        [spread]; None: the same at every width)."""
        p = self.passes[k]
        back, front = tensions if tensions is not None else (p.back_tension, p.front_tension)
        omega = angular_velocity if angular_velocity is not None else p.angular_velocity()
        lc = (p.roll_radius * 0.5 * (entry_thickness - p.nominal_exit)) ** 0.5
        d = {
            "name": f"{k + 1:02d}_{self.pass_name(k)}",
            "pass": {"roll_radius": p.roll_radius, "entry_thickness": entry_thickness,
                     "roll_angular_velocity": omega,
                     "back_tension": back, "front_tension": front},
            "plate": {"length": PLATE_CONTACT_LENGTHS * lc, "temperature": temperature,
                      "entry_strain": strain},
            "material": self.material.model_dump(exclude_none=True),
            "friction": (p.friction or self.friction).model_dump(exclude_none=True),
            "mesh": self.mesh.model_dump(exclude_none=True),
            "solver": self.solver.model_dump(exclude_none=True),
            "output": self.output.model_dump(exclude_none=True),
            "roll": self.roll.model_dump(exclude_none=True),
            "contact": self.contact.model_dump(exclude_none=True),
        }
        for key in ("exit_thickness", "roll_gap", "mill_modulus"):
            if getattr(p, key) is not None:
                d["pass"][key] = getattr(p, key)
        width = self.strip.width if width is None else width
        if width is not None:
            d["pass"]["width"] = width
        if self.spread is not None:          # each pass's 3D pass across the width
            d["spread"] = self.spread.model_dump(exclude_none=True)
            if temperature_section is not None:
                d["spread"]["temperature_section"] = temperature_section.to_dict()
        d["pass"].update(pass_rolls(p))
        if not p.isothermal:
            d["thermal"] = self.thermal.model_dump(exclude_none=True)
        if temperature_profile is not None and not p.isothermal:
            d["plate"]["temperature_profile"] = temperature_profile.pairs()
        if strain_profile is not None:
            d["plate"]["strain_profile"] = strain_profile.pairs()
        try:
            return case_from_dict(d)
        except CaseError as e:
            raise CaseError([_pass_problem(k, q) for q in e.problems]) from None

    def entry_profiles(self):
        """The entry strip's (temperature, strain) profiles or None each."""
        return tuple(None if p is None else ThicknessProfile.from_pairs(p)
                     for p in (self.strip.temperature_profile, self.strip.strain_profile))

    def check_cases(self) -> list[Case]:
        """Every pass as a case at the nominal entry state (the geometry, laws, meshes checked
        before any computation); raises one CaseError with all problems."""
        cases, problems, h = [], [], self.strip.thickness
        omega1 = self.passes[0].angular_velocity()
        for k, p in enumerate(self.passes):
            omega = p.angular_velocity()
            if omega is None:      # mass_flow: a volume-constant guess (checks only)
                omega = omega1 * self.passes[0].roll_radius / p.roll_radius * \
                    self.passes[0].nominal_exit / p.nominal_exit
            try:
                cases.append(self.pass_case(k, h, self.strip.temperature, None,
                                            self.strip.strain, None, omega))
                problems += asymmetric_problems(self, k, cases[-1])
            except CaseError as e:
                problems += [q for q in e.problems if q not in problems]
            h = p.nominal_exit
        if problems:
            raise CaseError(problems, "schedule")
        return cases


def _pass_problem(k: int, problem: str) -> str:
    """A pass case's problem in the schedule's terms."""
    if problem.startswith("pass."):
        return f"pass[{k + 1}]." + problem[len("pass."):]
    if problem.startswith("plate."):
        return f"pass[{k + 1}] (its entry strip) " + problem
    if problem.startswith("mesh."):          # the mesh rules depend on the pass's size
        return f"{problem} (in pass[{k + 1}])"
    return problem


def schedule_from_dict(d: Any, source: str | None = None) -> Schedule:
    if not isinstance(d, dict):
        raise CaseError(f"schedule: must be a table of sections, got {type(d).__name__}", source,
                        "schedule")
    try:
        sch = Schedule.model_validate(d)
    except ValidationError as e:
        raise CaseError(problem_lines(e), source, "schedule") from None
    try:
        sch.check_cases()
    except CaseError as e:
        raise CaseError(e.problems, source, "schedule") from None
    return sch


def load_schedule(path: str | Path) -> Schedule:
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise CaseError(f"cannot read schedule file: {e.strerror or e}", str(path),
                        "schedule") from None
    except tomllib.TOMLDecodeError as e:
        raise CaseError(f"TOML syntax error: {e}", str(path), "schedule") from None
    data.setdefault("name", path.stem)
    return schedule_from_dict(data, str(path))
