"""The case's ``[friction]`` section: the friction law by name (``model/friction``'s registry),
its parameters, the regularisation speed and the cap of the estimated a_f.

The section is built from the registry: every registered law's parameters are fields (with
their unit and allowed range), a law takes only its own, a parameter with a default (the
viscoplastic law's a_f = "estimate") takes it when omitted. Adding a law touches its own
module, not this one. Part of the case description of :mod:`hotroll.config.case`.
"""

from __future__ import annotations

from typing import Any, ClassVar, Literal

from pydantic import create_model, model_validator

from hotroll.config.base import PosFloat, Problems, field
from hotroll.config.law_section import LawSection, parameter_fields
from hotroll.model.friction import FRICTION_LAWS, FrictionLaw


class _FrictionSection(LawSection):
    """The checks and the law object of ``FrictionConfig`` (its fields come from the registry)."""

    registry: ClassVar[dict] = FRICTION_LAWS
    section: ClassVar[str] = "friction"

    @model_validator(mode="after")
    def _check_law(self):
        spec, problems = FRICTION_LAWS[self.law], self.other_law_problems()
        for p in spec.parameters:
            if getattr(self, p.name) is None:
                if p.default is not None:
                    setattr(self, p.name, p.default)
                elif p.required:
                    problems.append(f"{self.section}.{p.name}: required for law = \"{self.law}\" "
                                    f"(allowed: {p.allowed})")
        if problems:
            raise Problems(problems)
        return self

    def regularisation_velocity(self, u_roll: float) -> float:
        """v_reg (m/s), or the law's default fraction of the roll surface speed ``u_roll``."""
        if self.v_reg is not None:
            return self.v_reg
        return FRICTION_LAWS[self.law].v_reg_fraction * u_roll

    def law_object(self, u_roll: float, m: float) -> FrictionLaw:
        """The friction law in reduced units (stresses over K), ``model/friction``."""
        return FRICTION_LAWS[self.law].build(self.given(), self.regularisation_velocity(u_roll), m)

    @property
    def uses_a_f(self) -> bool:
        """The law takes a_f (the viscoplastic law: given, or estimated by (3.15))."""
        return "a_f" in [p.name for p in FRICTION_LAWS[self.law].parameters]

    @property
    def a_f_rule(self) -> float | None:
        """a_f for the solvers: None = estimate (3.15); 0 for the laws without a_f."""
        if not self.uses_a_f:
            return 0.0
        return None if self.a_f == "estimate" else float(self.a_f)


def _fields() -> dict:
    """The fields of a friction table: the law, its parameters, v_reg and a_f_max."""
    return dict(
        law=(Literal[tuple(FRICTION_LAWS)], field(
            next(iter(FRICTION_LAWS)), "friction law: " + "; ".join(
                f"{s.name} ({s.summary})" for s in FRICTION_LAWS.values()), "",
            ", ".join(f'"{n}"' for n in FRICTION_LAWS))),
        **parameter_fields(FRICTION_LAWS),
        v_reg=(PosFloat | None, field(
            None, "friction regularisation velocity (omit: " + ", ".join(
                f"{s.v_reg_fraction:g} x roll surface speed for {s.name}"
                for s in FRICTION_LAWS.values()) + ")", "m/s", "> 0")),
        a_f_max=(float, field(1e6, "upper cap for the estimated a_f", "m^-m", "> 0", gt=0)),
    )


def _side(name: str):
    """The friction table of one roll, [friction.<name>]: the same keys as [friction]."""
    base = type(f"_{name.title()}Friction", (_FrictionSection,),
                {"__module__": __name__, "section": f"friction.{name}",
                 "__annotations__": {"section": ClassVar[str]}})
    return create_model(f"{name.title()}RollFriction", __base__=base, __module__=__name__,
                        **_fields())


UpperRollFriction, LowerRollFriction = _side("upper"), _side("lower")


class _CaseFriction(_FrictionSection):
    """[friction] with its per-roll tables: a side's table without a law (or with [friction]'s)
    changes only the keys it gives; with another law it is that law's whole data."""

    @model_validator(mode="before")
    @classmethod
    def _sides_inherit(cls, data: Any) -> Any:
        if not isinstance(data, dict):
            return data
        own = {k: v for k, v in data.items() if k not in ("upper", "lower")}
        law = own.get("law", next(iter(FRICTION_LAWS)))
        out = dict(data)
        for name in ("upper", "lower"):
            side = data.get(name)
            if isinstance(side, dict) and side.get("law", law) == law:
                out[name] = {**own, **side}
        return out


FrictionConfig = create_model(
    "FrictionConfig", __base__=_CaseFriction, __module__=__name__, **_fields(),
    upper=(UpperRollFriction | None, field(
        None, "the upper roll's own friction, [friction.upper]: the keys of [friction]; "
        "without law (or with [friction]'s law) only the keys it changes (omit: [friction])",
        "", "a table of [friction]'s keys")),
    lower=(LowerRollFriction | None, field(
        None, "the lower roll's own friction, [friction.lower], as [friction.upper]", "",
        "a table of [friction]'s keys")),
)
FrictionConfig.__doc__ = "The [friction] section: a friction law of the registry and its data."
