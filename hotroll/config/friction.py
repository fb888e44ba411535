"""The case's ``[friction]`` section (the ``[material]`` section is ``config/material.py``).

Part of the case description of :mod:`hotroll.config.case` (which re-exports it); each law's
parameters are checked against the law chosen, with ``section.key`` errors.
"""

from __future__ import annotations

from typing import Literal

from pydantic import model_validator

from hotroll.config.base import PosFloat, Problems, Section, field
from hotroll.model.friction import CoulombFriction, TrescaFriction, ViscoplasticFriction


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
