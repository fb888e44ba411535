"""The case's ``[material]`` section: the flow-stress law by name (``model/flow_stress``'s
registry), its parameters, the regularisation eps0 and the thermal properties.

The section is built from the registry: every registered law's parameters are fields (with
their unit and allowed range), a law takes only its own, and a Hensel-Spittel ``grade`` stands
for its coefficients. Adding a law touches its own module, not this one.
"""
from __future__ import annotations

import math
from typing import ClassVar, Literal

import numpy as np
from pydantic import create_model, field_validator, model_validator

from hotroll.config.base import Problems, field, fields_of
from hotroll.config.law_section import LawSection, parameter_fields
from hotroll.config.thermal import Property, check_property
from hotroll.model.flow_stress import LAWS, FlowStressLaw
from hotroll.model.grades import get_grade, list_grades
from hotroll.model.thermal_properties import ThermalProperties

#: The law whose parameter sets ``grade`` names (model/grades.py).
GRADE_LAW = "hensel-spittel"


class _MaterialSection(LawSection):
    """The checks and the law object of ``MaterialConfig`` (its fields come from the registry)."""

    registry: ClassVar[dict] = LAWS
    section: ClassVar[str] = "material"

    @field_validator("density", "specific_heat", "conductivity", mode="before", check_fields=False)
    @classmethod
    def _property(cls, v, info):
        return check_property(info.field_name, v)

    @model_validator(mode="after")
    def _check_law(self):
        spec, problems = LAWS[self.law], self.other_law_problems()
        if self.grade is not None:
            if self.law != GRADE_LAW:
                problems.append(f"material.grade: only for law = \"{GRADE_LAW}\" (a grade is a "
                                f"Hensel-Spittel set of model/grades.py)")
            else:
                try:
                    get_grade(self.grade)
                except (KeyError, ValueError):
                    problems.append(f"material.grade: unknown grade {self.grade!r} (allowed: "
                                    f"{', '.join(list_grades())})")
                problems += [f"material.{k}: not with material.grade (the grade sets it)"
                             for k in self.given()]
        elif not problems:
            problems += [f"material.{p.name}: missing required key for law = \"{self.law}\" "
                         f"({fields_of(type(self))[p.name].description})"
                         for p in spec.parameters if p.required and getattr(self, p.name) is None]
            if not problems and spec.check is not None:
                problems += [f"material.{k}: {msg}" for k, msg in spec.check(self.given())]
        if problems:
            raise Problems(problems)
        return self

    def flow_stress(self) -> FlowStressLaw:
        """The flow-stress law object (``model/flow_stress``), SI units, T in K."""
        if self.grade is not None:
            return get_grade(self.grade).law(eps0=self.eps0)
        return LAWS[self.law].build(self.given(), self.eps0)

    def problems_at(self, temperature: float, strain: float) -> list[str]:
        """What is wrong with the flow-stress law at the plate's entry state (temperature in K,
        strain): its rate exponent must be in (0, 1] and its consistency K finite and > 0 (the
        reference Norton-Hoff law of ``workflows.build.reference_material``)."""
        flow = self.flow_stress()
        m = float(flow.rate_exponent(temperature))
        if not 0.0 < m <= 1.0:
            lo, hi = flow.admissible_temperature_range()
            return [f"plate.temperature: the flow-stress law's rate exponent is {m:.4g} at "
                    f"{temperature:g} K; it must be in (0, 1] (allowed temperatures for this "
                    f"law: {lo:.6g} to {hi:.6g} K)"]
        with np.errstate(all="ignore"):
            K = float(flow.consistency(strain, temperature))
        if not (math.isfinite(K) and K > 0.0):
            return [f"plate.temperature: the flow-stress law's consistency K at {temperature:g} "
                    f"K and strain {strain:g} is {K:g} Pa s^m; it must be finite and > 0 (see "
                    f"plate.temperature, plate.entry_strain and the parameters of material.law)"]
        return []

    def thermal_properties(self) -> ThermalProperties:
        """The strip's ``ThermalProperties``; all three must be given (with [thermal])."""
        return ThermalProperties(density=self.density, specific_heat=self.specific_heat,
                                 conductivity=self.conductivity)

    def rate_exponent(self, temperature: float) -> float:
        """m of the law at the plate temperature (K)."""
        return float(self.flow_stress().rate_exponent(temperature))


MaterialConfig = create_model(
    "MaterialConfig", __base__=_MaterialSection, __module__=__name__,
    law=(Literal[tuple(LAWS)], field(
        "norton-hoff", "flow-stress law: " + "; ".join(
            f"{s.name} ({', '.join(p.name for p in s.parameters)})" for s in LAWS.values())
        + f"; {GRADE_LAW} also by grade", "", " or ".join(f'"{n}"' for n in LAWS))),
    grade=(str | None, field(None, "Hensel-Spittel parameter set by name (hotroll grades)", "",
                             "a name from model/grades.py")),
    **parameter_fields(LAWS),
    eps0=(float, field(1e-4, "strain-rate regularisation eps0", "1/s", "> 0", gt=0)),
    # thermal properties: used only with a [thermal] section (config/thermal.py)
    density=(Property | None, field(None, "density (with [thermal])", "kg/m^3",
                                    "> 0 or a table [[T (K), value], ...]")),
    specific_heat=(Property | None, field(None, "specific heat capacity (with [thermal])",
                                          "J/(kg K)", "> 0 or a table [[T (K), value], ...]")),
    conductivity=(Property | None, field(None, "thermal conductivity (with [thermal])",
                                         "W/(m K)", "> 0 or a table [[T (K), value], ...]")),
)
MaterialConfig.__doc__ = "The [material] section: a flow-stress law of the registry and its data."
