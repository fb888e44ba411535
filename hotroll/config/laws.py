"""The case sections that pick a law: ``[material]`` (flow stress) and ``[friction]``.

Part of the case description of :mod:`hotroll.config.case` (which re-exports them); each law's
parameters are checked against the law chosen, with ``section.key`` errors.
"""

from __future__ import annotations

import math
from typing import Literal

from pydantic import field_validator, model_validator

from hotroll.config.base import PosFloat, Problems, Section, field, fields_of
from hotroll.config.thermal import Property, check_property
from hotroll.model.flow_stress import HenselSpittel, NortonHoffStress
from hotroll.model.friction import CoulombFriction, TrescaFriction, ViscoplasticFriction
from hotroll.model.grades import get_grade, list_grades
from hotroll.model.thermal_properties import ThermalProperties


class MaterialConfig(Section):
    law: Literal["norton-hoff", "hensel-spittel"] = field(
        "norton-hoff", "flow-stress law: Norton-Hoff (K, m) or Hensel-Spittel (A, m1..m9, or a "
        "grade)", "", '"norton-hoff" or "hensel-spittel"')
    grade: str | None = field(None, "Hensel-Spittel parameter set by name (hotroll grades)",
                               "", "a name from model/grades.py")
    K: float | None = field(None, "Norton-Hoff consistency K", "Pa s^m", "> 0", gt=0)
    m: float | None = field(None, "strain-rate sensitivity m", "", "in (0, 1]", gt=0, le=1)
    A: float | None = field(None, "Hensel-Spittel A", "Pa", "> 0", gt=0)
    m1: float | None = field(None, "Hensel-Spittel m1 (temperature, e^(m1 T))", "1/degC",
                       "a finite number (omit: 0)")
    m2: float | None = field(None, "Hensel-Spittel m2 (strain, eps^m2)", "", "a finite number (omit: 0)")
    m3: float | None = field(None, "Hensel-Spittel m3 (rate, edot^m3)", "", "a finite number (omit: 0)")
    m4: float | None = field(None, "Hensel-Spittel m4 (e^(m4/eps))", "", "a finite number (omit: 0)")
    m5: float | None = field(None, "Hensel-Spittel m5 ((1+eps)^(m5 T))", "1/degC", "a finite number (omit: 0)")
    m7: float | None = field(None, "Hensel-Spittel m7 (e^(m7 eps))", "", "a finite number (omit: 0)")
    m8: float | None = field(None, "Hensel-Spittel m8 (edot^(m8 T))", "1/degC", "a finite number (omit: 0)")
    m9: float | None = field(None, "Hensel-Spittel m9 (T^m9)", "", "a finite number (omit: 0)")
    eps0: float = field(1e-4, "strain-rate regularisation eps0", "1/s", "> 0", gt=0)
    # thermal properties: used only with a [thermal] section (config_thermal.py)
    density: Property | None = field(None, "density (with [thermal])", "kg/m^3",
                                      "> 0 or a table [[T (K), value], ...]")
    specific_heat: Property | None = field(None, "specific heat capacity (with [thermal])",
                                            "J/(kg K)", "> 0 or a table [[T (K), value], ...]")
    conductivity: Property | None = field(None, "thermal conductivity (with [thermal])",
                                           "W/(m K)", "> 0 or a table [[T (K), value], ...]")

    @field_validator("density", "specific_heat", "conductivity", mode="before")
    @classmethod
    def _property(cls, v, info):
        return check_property(info.field_name, v)

    _HS = ("A", "m1", "m2", "m3", "m4", "m5", "m7", "m8", "m9")

    @model_validator(mode="after")
    def _check_law(self) -> MaterialConfig:
        problems = []
        if self.law == "norton-hoff":
            for key in ("K", "m"):
                if getattr(self, key) is None:
                    problems.append(f"material.{key}: missing required key for law = "
                                    f"\"norton-hoff\" ({fields_of(type(self))[key].description})")
            extra = [k for k in self._HS + ("grade",) if getattr(self, k) is not None]
            problems += [f"material.{k}: only for law = \"hensel-spittel\"" for k in extra]
        else:
            extra = [k for k in ("K", "m") if getattr(self, k) is not None]
            problems += [f"material.{k}: only for law = \"norton-hoff\" (Hensel-Spittel: A, "
                         f"m1..m9 or grade)" for k in extra]
            given = [k for k in self._HS if getattr(self, k) is not None]
            if self.grade is not None:
                try:
                    self._grade()
                except (KeyError, ValueError):
                    problems.append(f"material.grade: unknown grade {self.grade!r} (allowed: "
                                    f"{', '.join(list_grades())})")
                problems += [f"material.{k}: not with material.grade (the grade sets it)"
                             for k in given]
            elif self.A is None:
                problems.append("material.A: missing required key for law = \"hensel-spittel\""
                                " without a grade (Hensel-Spittel A [Pa]; allowed: > 0)")
            else:
                try:                    # the law's own checks (its rate exponent m3 + m8 T)
                    self.flow_stress()
                except ValueError as e:
                    problems.append(f"material.m3: {e}; allowed: m3 + m8 T_C (T in degC) in "
                                    f"(0, 1] at some T > 0 K (m3 omitted: 0)")
        if problems:
            raise Problems(problems)
        return self

    def problems_at(self, temperature: float, strain: float) -> list[str]:
        """What is wrong with the flow-stress law at the plate's entry state (temperature in K,
        strain): its rate exponent must be in (0, 1] and its consistency K finite and > 0 (the
        reference Norton-Hoff law of ``runner.reference_material``). Norton-Hoff: nothing
        (K and m are checked as fields)."""
        if self.law == "norton-hoff":
            return []
        import numpy as np

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
                    f"plate.temperature, plate.entry_strain and material.A, m1..m9)"]
        return []

    def _grade(self):
        return get_grade(self.grade)

    def flow_stress(self):
        """The flow-stress law object (``model/flow_stress.py``), SI units, T in K."""
        if self.law == "norton-hoff":
            return NortonHoffStress(self.K, self.m, self.eps0)
        if self.grade is not None:
            return self._grade().law(eps0=self.eps0)
        return HenselSpittel(**{k: getattr(self, k) or 0.0 for k in self._HS}, eps0=self.eps0)

    def thermal_properties(self):
        """The strip's ``ThermalProperties`` (``hotroll/thermal``); all three must be given."""
        return ThermalProperties(density=self.density, specific_heat=self.specific_heat,
                                 conductivity=self.conductivity)

    def rate_exponent(self, temperature: float) -> float:
        """m of the law at the plate temperature (K)."""
        return float(self.flow_stress().rate_exponent(temperature))


class FrictionConfig(Section):
    law: Literal["viscoplastic", "coulomb", "tresca"] = field(
        "viscoplastic", "friction law: viscoplastic (2.29a), Coulomb (mu p, capped at k = "
        "sigma_ef/sqrt3) or Tresca (factor k)", "", '"viscoplastic", "coulomb" or "tresca"')
    a_f: Literal["estimate"] | PosFloat | None = field(
        None, "(omit: estimate) viscoplastic friction coefficient (tau = a_f K |dv|^(m-1) dv); law = "
        '"viscoplastic" only', "m^-m", '"estimate" or a number > 0')
    mu: float | None = field(None, 'Coulomb friction coefficient; law = "coulomb" only', "",
                              "in (0, 2]", gt=0, le=2)
    factor: float | None = field(None, 'friction factor m_f (tau = m_f k); law = "tresca" '
                                  "only", "", "in (0, 1]", gt=0, le=1)
    v_reg: PosFloat | None = field(
        None, "friction regularisation velocity (omit: 1e-4 x roll surface speed for the "
        "viscoplastic law, 1e-3 x for Coulomb and Tresca)", "m/s", "> 0")
    a_f_max: float = field(1e6, "upper cap for the estimated a_f", "m^-m", "> 0", gt=0)

    @model_validator(mode="after")
    def _check_law(self) -> FrictionConfig:
        need = {"coulomb": "mu", "tresca": "factor"}.get(self.law)
        problems = []
        if need and getattr(self, need) is None:
            problems.append(f"friction.{need}: required for law = \"{self.law}\" (allowed: "
                            + ("in (0, 2]" if need == "mu" else "in (0, 1]") + ")")
        for key, law in (("mu", "coulomb"), ("factor", "tresca")):
            if getattr(self, key) is not None and self.law != law:
                problems.append(f"friction.{key}: only for law = \"{law}\", the law is "
                                f"\"{self.law}\"")
        if self.law == "viscoplastic" and self.a_f is None:
            self.a_f = "estimate"
        if self.law != "viscoplastic" and self.a_f is not None:
            problems.append(f"friction.a_f: only for law = \"viscoplastic\", the law is "
                            f"\"{self.law}\"")
        if problems:
            raise Problems(problems)
        return self

    def regularisation_velocity(self, u_roll: float) -> float:
        """v_reg (m/s), or its default fraction of the roll surface speed ``u_roll``."""
        if self.v_reg is not None:
            return self.v_reg
        return (1e-4 if self.law == "viscoplastic" else 1e-3) * u_roll

    def law_object(self, u_roll: float, m: float):
        """The friction law in reduced units (stresses over K), ``model/friction.py``."""
        v = self.regularisation_velocity(u_roll)
        if self.law == "coulomb":
            return CoulombFriction(v, mu=self.mu)
        if self.law == "tresca":
            return TrescaFriction(v, factor=self.factor)
        return ViscoplasticFriction(v, K=1.0, m=m)

    @property
    def a_f_rule(self) -> float | None:
        """a_f for the solvers: None = estimate (3.15); 0 for the laws without a_f."""
        if self.law != "viscoplastic":
            return 0.0
        return None if self.a_f == "estimate" else float(self.a_f)
