"""What the case sections that pick a law share (``[material]``, ``[friction]``): the chosen
law's parameters, the refusal of another law's, and the fields built from a law registry (each
registered law's parameters, with unit and allowed range; ``model/parameters.py``)."""
from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import Field

from hotroll.config.base import Section, field


class LawSection(Section):
    """A section naming a law of ``registry`` (``law``) and taking that law's parameters."""

    registry: ClassVar[dict] = {}
    section: ClassVar[str] = ""

    def given(self) -> dict:
        """The chosen law's parameters as set (given, or their defaults)."""
        return {p.name: getattr(self, p.name) for p in self.registry[self.law].parameters
                if getattr(self, p.name) is not None}

    def other_law_problems(self) -> list[str]:
        """A parameter of another law given: ``section.key: only for law = ...`` lines."""
        own = [p.name for p in self.registry[self.law].parameters]
        return [f"{self.section}.{p.name}: only for law = \"{other.name}\" (the law is "
                f"\"{self.law}\", which takes {', '.join(own) or 'nothing'})"
                for other in self.registry.values() for p in other.parameters
                if p.name not in own and getattr(self, p.name) is not None]


def parameter_fields(registry: dict) -> dict:
    """Every registered law's parameters as optional fields (a name once): numbers within the
    parameter's limits, and its words besides numbers (the limits then on the number alone)."""
    out: dict = {}
    for spec in registry.values():
        for p in spec.parameters:
            if p.name in out:
                continue
            limits = {k: v for k in ("gt", "ge", "lt", "le") if (v := getattr(p, k)) is not None}
            laws = " or ".join(f'"{s.name}"' for s in registry.values()
                               if any(q.name == p.name for q in s.parameters))
            text = f"{p.text}; law = {laws} only"
            if p.words:
                kind = Literal[p.words] | Annotated[float, Field(**limits)] | None
                out[p.name] = (kind, field(None, text, p.unit, p.allowed))
            else:
                out[p.name] = (float | None, field(None, text, p.unit, p.allowed, **limits))
    return out
