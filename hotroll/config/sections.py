"""The geometry and numerics sections of a case: ``[pass]``, ``[plate]``, ``[mesh]``,
``[solver]``, ``[output]`` (``config.py`` assembles the case; the laws are in
``config_laws.py``, the temperature in ``config_thermal.py``)."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import Field, PrivateAttr, StrictBool, field_validator, model_validator

from hotroll.config.base import (
    MAX_LENGTH,
    MESH_TABLE,
    MeshName,
    PosFloat,
    Problems,
    Section,
    field,
    with_units,
)
from hotroll.config.roll_sides import (
    RollModelSide,
    RollSideConfig,
    own_radius,
    roll_values,
    side_problems,
)
from hotroll.model.geometry import RollPass
from hotroll.model.profile import ProfileError, ThicknessProfile
from hotroll.model.roll_gap import LOWER, UPPER, Roll, RollGap

#: pass.roll_gap's allowed range, as its field says
_GAP_ALLOWED = "> 0 and < entry_thickness [m]"


def preloaded_gap(v: Any, key: str, allowed: str = "> 0 [m]") -> Any:
    """``v`` unless it is a number <= 0: a no-load gap that does not open is a preloaded stand
    (the rolls pressed into each other at no load, as the negative gap to set a run reports
    means: results/engineering.negative_gap_warning); refused saying so."""
    if isinstance(v, str):
        v = with_units(v, "m")
    if isinstance(v, (int, float)) and not isinstance(v, bool) and v <= 0:
        raise Problems([f"{key}: {v:g} m: a no-load gap <= 0 is a preloaded stand (the rolls "
                        f"pressed into each other at no load); the exit thickness is found from "
                        f"a gap that opens: give this pass by its exit_thickness, whose report "
                        f"then says the (negative) gap to set; must be {allowed}"])
    return v


class PassConfig(Section):
    """Roll and pass geometry (roll centre at x = roll_axis_x, y = exit/2 + R)."""

    roll_radius: float = field(..., "roll radius R", "m", f"> 0 and <= {MAX_LENGTH:g}", gt=0,
                                le=MAX_LENGTH)
    entry_thickness: float = field(..., "full plate thickness at entry", "m",
                                    f"> 0 and <= {MAX_LENGTH:g}", gt=0, le=MAX_LENGTH)
    exit_thickness: float = field(
        ..., "full plate thickness at exit (the roll gap of rigid rolls and a rigid mill); "
        "with roll_gap: the first guess of it (omit: roll_gap)", "m",
        "> 0 and < entry_thickness", gt=0)
    roll_angular_velocity: float = field(..., "roll angular velocity omega", "rad/s", "> 0", gt=0)
    roll_axis_x: float = field(1.0, "x of the roll centre (initial plate head position)", "m",
                                f"in [-{MAX_LENGTH:g}, {MAX_LENGTH:g}]", ge=-MAX_LENGTH,
                                le=MAX_LENGTH)
    back_tension: float = field(0.0, "back tension: mean tensile stress on the entry strip",
                                 "Pa", ">= 0", ge=0)
    front_tension: float = field(0.0, "front tension: mean tensile stress on the exit strip",
                                  "Pa", ">= 0", ge=0)
    width: PosFloat | None = field(None, "strip width (omit: results per unit width only)", "m",
                                    "> 0")
    mill_modulus: PosFloat | None = field(
        None, "the stand's modulus M: its whole force per metre the roll gap opens (hot strip "
        "finishing stands about 4e9-7e9 N/m); reports the mill stretch F/M and the no-load gap "
        "to set, exit thickness - F/M (needs width)", "N/m", "> 0")
    roll_gap: PosFloat | None = field(
        None, "the no-load roll gap S set on the stand: the exit thickness is then found with "
        "the force, h1 = S + F/M (gaugemeter; needs mill_modulus, steady solver)", "m",
        "> 0 and < entry_thickness")
    speed_ratio: PosFloat | None = field(
        None, "asymmetric rolling: the upper roll's surface speed over the lower's; the upper "
        "roll keeps its speed (pass.roll_angular_velocity, or [pass.upper]'s) and the lower "
        "turns at the upper's surface speed / speed_ratio (omit: each roll at its own angular "
        "velocity, pass.roll_angular_velocity unless its table gives one; at <= 0 the lower "
        "roll would stand or drive the strip backwards)", "", "> 0")
    upper: RollSideConfig | None = field(
        None, "the upper roll's own radius and speed, [pass.upper] (omit: [pass]'s)", "",
        "a table of roll_radius, roll_angular_velocity or roll_surface_speed")
    lower: RollSideConfig | None = field(
        None, "the lower roll's own radius and speed, [pass.lower] (omit: [pass]'s, the speed "
        "from speed_ratio when given)", "",
        "a table of roll_radius, roll_angular_velocity or roll_surface_speed")

    @model_validator(mode="before")
    @classmethod
    def _gap_guess(cls, data: Any) -> Any:
        """With a roll gap and no exit thickness, the first guess is the gap (the geometry
        the case is checked with: the largest draft the stand can give)."""
        if isinstance(data, dict) and data.get("roll_gap") is not None \
                and data.get("exit_thickness") is None:
            gap = preloaded_gap(data["roll_gap"], "pass.roll_gap", _GAP_ALLOWED)
            if isinstance(gap, (int, float)) and not isinstance(gap, bool):
                data = {**data, "exit_thickness": gap}
        return data

    @field_validator("roll_gap", mode="before")
    @classmethod
    def _gap_opens(cls, v: Any) -> Any:
        """A gap <= 0 is refused with what it means (``preloaded_gap``)."""
        return preloaded_gap(v, "pass.roll_gap", _GAP_ALLOWED)

    @model_validator(mode="after")
    def _check_geometry(self) -> PassConfig:
        problems = []
        if self.exit_thickness >= self.entry_thickness:
            problems.append(
                f"pass.exit_thickness: must be smaller than pass.entry_thickness "
                f"({self.entry_thickness:g} m), got {self.exit_thickness:g} m")
        elif not own_radius(self) and self.draft >= self.roll_radius:
            problems.append(
                f"pass.roll_radius: must exceed the draft per side (entry - exit)/2 = "
                f"{self.draft:g} m, otherwise the roll cannot bite the plate; allowed: "
                f"roll_radius > {self.draft:g} m, got {self.roll_radius:g} m")
        if self.roll_gap is not None:
            if self.roll_gap >= self.entry_thickness:
                problems.append(f"pass.roll_gap: must be smaller than pass.entry_thickness "
                                f"({self.entry_thickness:g} m), got {self.roll_gap:g} m")
            if self.mill_modulus is None:
                problems.append("pass.roll_gap: needs pass.mill_modulus (N/m) and pass.width "
                                "(m): the exit thickness is the gap plus the stretch F/M")
        if self.mill_modulus is not None and self.width is None:
            problems.append("pass.mill_modulus: needs pass.width (the stand carries the whole "
                            "width's force)")
        problems += side_problems(self)
        if problems:
            raise Problems(problems)
        return self

    @property
    def draft(self) -> float:
        """Thickness reduction per side (m)."""
        return 0.5 * (self.entry_thickness - self.exit_thickness)

    @property
    def per_roll(self) -> bool:
        """Whether the pass gives per-roll values ([pass.upper], [pass.lower], speed_ratio)."""
        return self.upper is not None or self.lower is not None or self.speed_ratio is not None

    def roll_pass(self) -> RollPass:
        """The geometry object the solver uses (all derived quantities live there); with
        per-roll values the upper roll's arc (``RollGap.arc``), the same object when the
        rolls are equal."""
        if self.per_roll:
            return self.two_rolls().arc(UPPER)
        return RollPass(self.roll_radius, 0.5 * self.entry_thickness, 0.5 * self.exit_thickness,
                        self.roll_angular_velocity, self.roll_axis_x)

    def two_rolls(self) -> RollGap:
        """The two rolls of the pass, their radii and speeds (rigid, the case's friction:
        ``Case.roll_gap`` adds the rest)."""
        (R1, w1), (R2, w2) = roll_values(self, UPPER), roll_values(self, LOWER)
        return RollGap(Roll(R1, w1, side=UPPER), Roll(R2, w2, side=LOWER),
                       self.entry_thickness, self.exit_thickness, self.roll_axis_x)

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


class PlateConfig(Section):
    length: float = field(
        ..., "initial plate length, at least 3 x the projected contact length", "m",
        f"> 0 and <= {MAX_LENGTH:g}", gt=0, le=MAX_LENGTH)
    temperature: float = field(
        1373.15, "plate temperature: uniform (isothermal run) or at the entry (with [thermal])",
        "K", "> 0", gt=0)
    entry_strain: float = field(0.0, "equivalent plastic strain the plate enters with", "",
                                 ">= 0", ge=0)
    free_surface: Literal["traced", "constrained"] = field(
        "traced", "free tops before and after the bite: traction-free streamlines (traced) or "
        "held flat by the penalty (3.2d) (constrained)", "", '"traced" or "constrained"')
    temperature_profile: list[tuple[float, float]] | None = field(
        None, "entry temperature through the half thickness, [[eta, T], ...] with eta = "
        "y / half thickness from 0 (centre) to 1 (surface), linear between (omit: uniform "
        "plate.temperature; needs [thermal] and the steady method)", "K",
        "pairs with eta increasing strictly from 0 to 1 and T > 0", columns=("", "K"))
    strain_profile: list[tuple[float, float]] | None = field(
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
        return tuple(None if p is None else ThicknessProfile.from_pairs(p)
                     for p in (self.temperature_profile, self.strain_profile))


class MeshConfig(Section):
    h_contact: Literal["auto"] | MeshName | PosFloat = field(
        "auto", "mesh size along the contact (auto: the coarsest size whose roll force is within "
        "1 % of the mesh-converged one, docs/theory.md 4e)", "m",
        '"auto", one of C1, C2, M1, M2, F1, F2 or a number > 0')
    h_far: PosFloat | None = field(None, "coarse mesh size far from the roll (omit: automatic)",
                                    "m", "> 0 and >= h_contact")
    grading: float = field(0.3, "mesh grading (size growth rate)", "", "in (0, 1]", gt=0, le=1)
    corner_refinement: float = field(
        16.0, "the steady strip's mesh at the contact's start, where the flow turns onto the "
        "roll, this many times finer than h_contact, graded back to it: 16 takes the traced top's "
        "mass leak from 5-10e-4 of the inflow (1: none) to below 1e-4 (docs/theory.md 4e)", "",
        "in [1, 64]", ge=1, le=64)

    _auto_h: float = PrivateAttr(default=float("nan"))   # set by Case from the pass geometry

    @field_validator("h_contact", mode="before")
    @classmethod
    def _upper_name(cls, v: Any) -> Any:
        if isinstance(v, str):
            v = v.strip()
            if v.lower() == "auto":
                return "auto"
            return v.upper() if v.upper() in MESH_TABLE else v     # "c2"; "20 mm" a length
        return v

    @property
    def h(self) -> float:
        """Contact mesh size in m (Table 2 names and "auto" resolved)."""
        if self.h_contact == "auto":
            return self._auto_h
        return MESH_TABLE[self.h_contact] if isinstance(self.h_contact, str) else self.h_contact


class SolverConfig(Section):
    method: Literal["steady", "transient"] = field(
        "steady", "solution method: direct steady state or the report's time stepping", "",
        '"steady" or "transient"')
    nonlinear: Literal["newton", "picard"] = field("newton", "nonlinear solver", "",
                                                    '"newton" or "picard"')
    tolerance: float = field(1e-5, "nonlinear tolerance (Newton update / roll speed)", "",
                              "in (0, 0.1]", gt=0, le=0.1)
    max_iterations: int | None = field(
        None, "nonlinear iterations per step (transient) or per continuation stage (steady); "
        "omit: 20 transient, 30 steady", "", "an integer >= 1", ge=1)
    end_time: PosFloat | None = field(None, "simulated time (omit: automatic)", "s", "> 0")
    time_step: Literal["h/6"] | PosFloat = field(
        "h/6", 'time step ("h/6": dt = h_contact/6)', "s", '"h/6" or a number > 0')
    steady_tolerance: float = field(2e-3, "steady-state detection tolerance (relative change)",
                                     "", "in (0, 0.1]", gt=0, le=0.1)
    max_steps: int = field(100000, "maximum number of time steps", "", "an integer >= 1", ge=1)
    wall_time_limit: PosFloat | None = field(None, "wall-clock limit (omit: none)", "s", "> 0")
    checkpoint_every: int = field(25, "steps between checkpoints", "", "an integer >= 1", ge=1)
    threads: Literal["auto"] | Annotated[int, Field(ge=1, le=1024)] = field(
        "auto", "threads of each Newton step, the meshing and the measures: at most this many, "
        "and never a core another running process wants (sampled at each step, "
        "fem/reproducible.py); auto: up to 4", "", '"auto" or an integer in [1, 1024]')
    memory_limit: PosFloat | None = field(
        None, "refuse a mesh whose estimated memory is above this (omit: the machine's free "
        "memory; workflows/estimate.py)", "B", "> 0")
    force: bool = field(False, "run even when the memory estimate is above the limit or the "
                         "case looks like a unit slip (config/plausibility.py: a roll surface "
                         "speed above 60 m/s, R above 2 m, h0 above 1 m, a grade below 500 K)",
                         "", "true or false")
    steady_entry_length: PosFloat | None = field(
        None, "steady strip: flat length before the touching point (omit: automatic)", "m", "> 0")
    steady_exit_length: PosFloat | None = field(
        None, "steady strip: flat length after the roll gap (omit: automatic)", "m", "> 0")
    exit_pressure_correction: bool = field(True, "correct the exit pressure", "", "true or false")


class ContactConfig(Section):
    method: Literal["auto", "multiplier", "penalty"] = field(
        "auto", "roll contact: exact (the pressure a Lagrange multiplier on the arc) or the "
        "report's penalty (Table 1); auto: multiplier for the steady solver, penalty for the "
        "report's scheme", "", '"auto", "multiplier" (steady only) or "penalty"')
    unilateral: Literal["auto"] | StrictBool = field(
        "auto", "the strip leaves the roll where the contact pressure falls to zero (before "
        "the gap or at it); false: bilateral, the strip held to the roll up to the gap whatever "
        "the pressure; auto: true for the steady solver with traced tops, false otherwise (the "
        "report's scheme: its (2.28a))", "", '"auto", true (steady solver, traced tops) or false')

    strip_youngs_modulus: Literal["auto", "off"] | PosFloat = field(
        "auto", "the strip's Young's modulus at the pass temperature: its elastic thickness "
        "strain in the contact (elastic entry and exit zones, the strip recovering past the "
        "gap; steady solver, exact contact); auto: the grade's E(T) at plate.temperature "
        "(model/strip_elasticity.py: steels Ghosh and Olson 2002, aluminium Frost and Ashby "
        "1982) where the run has a grade and exact contact with traced tops, else off; off: "
        "rigid-plastic", "Pa", '"auto", "off" or a number > 0')
    strip_poissons_ratio: Literal["auto"] | Annotated[float, Field(ge=0.0, lt=0.5)] = field(
        "auto", "the strip's Poisson's ratio (with its elasticity); auto: the grade family's "
        "(steel 0.3, aluminium 0.35), 0.3 without a grade", "",
        '"auto" or a number >= 0 and < 0.5')

    def resolved(self, solver_method: str) -> str:
        """The method a run uses: "auto" resolved by the solver."""
        if self.method != "auto":
            return self.method
        return "multiplier" if solver_method == "steady" else "penalty"

    def resolved_unilateral(self, solver_method: str) -> bool:
        """Whether the strip may leave the roll: "auto" resolved by the solver."""
        if self.unilateral != "auto":
            return bool(self.unilateral)
        return solver_method == "steady"     # (constrained tops: held, ``SteadyRun``)


class RollConfig(Section):
    """The work roll's elasticity (docs/theory.md 1f)."""

    model: Literal["rigid", "hitchcock", "elastic"] = field(
        "rigid", "the work roll: rigid; flattened by Hitchcock's formula (a circle of radius R' "
        "through the gap); or elastic (the plane-strain disc under the computed contact "
        "pressure and shear, its surface iterated with the strip); flattening rolls need the "
        "steady solver", "",
        '"rigid", "hitchcock" or "elastic"')
    youngs_modulus: PosFloat = field(210e9, "the roll's Young's modulus (steel 210e9)", "Pa",
                                     "> 0", gt=0)
    poissons_ratio: float = field(0.3, "the roll's Poisson's ratio (steel 0.3)", "",
                                  ">= 0 and < 0.5", ge=0.0, lt=0.5)
    relaxation: float = field(1.0, "the share of each surface update taken (under-relaxation)",
                              "", "> 0 and <= 1", gt=0.0, le=1.0)
    tolerance: float = field(1e-5, "the roll has settled when its surface moves less than this "
                             "x the exit half-thickness per update", "", "> 0 and < 1",
                             gt=0.0, lt=1.0)
    upper: RollModelSide | None = field(
        None, "the upper roll's own model, [roll.upper] (omit: roll.model)", "",
        "a table of model")
    lower: RollModelSide | None = field(
        None, "the lower roll's own model, [roll.lower] (omit: roll.model)", "",
        "a table of model")

    def model_of(self, side: int) -> str:
        """The model of the roll on ``side`` (+1 upper, -1 lower): its table's, else [roll]'s."""
        own = self.upper if side == UPPER else self.lower
        return self.model if own is None or own.model is None else own.model


class OutputConfig(Section):
    figures: bool = field(True, "write figures", "", "true or false")
    vtk: bool = field(True, "write VTK files", "", "true or false")
