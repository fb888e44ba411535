"""The flow-stress laws by name: what a case file's ``[material] law = "..."`` selects.

A law module declares its parameters (name, text, unit, allowed range) and how to build the law
from them, and registers itself here; the case schema (``config/material.py``), the documentation
and the command line read the registry, so adding a law is its own module, its test and a line
in docs/theory.md. Another package adds a law through the entry-point group
``hotroll.flow_stress`` (``model/registry.py``, docs/how-to/add-a-law.md).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping

from hotroll.model.flow_stress.base import FlowStressLaw
from hotroll.model.parameters import Parameter
from hotroll.model.registry import Registry


@dataclass(frozen=True)
class LawSpec:
    """A flow-stress law for the case file.

    ``build(values, eps0)``: the law from the given parameters (a dict of those given, SI) and
    the regularisation strain rate eps0 (1/s). ``check(values)``: cross-parameter problems as
    (parameter, message) pairs, before anything is solved. ``source``: the published source.
    """

    name: str
    summary: str
    source: str
    parameters: tuple[Parameter, ...]
    build: Callable[[dict, float], FlowStressLaw]
    check: Callable[[dict], list[tuple[str, str]]] | None = None


def _same_parameters(spec: LawSpec, registered: Mapping[str, LawSpec]) -> None:
    """A parameter name means one thing in all laws (unit and limits)."""
    for other in registered.values():
        for p in spec.parameters:
            for q in other.parameters:
                if p.name == q.name and (p.unit, p.gt, p.ge, p.lt, p.le) != (q.unit, q.gt, q.ge,
                                                                              q.lt, q.le):
                    raise ValueError(f"parameter {p.name!r} of {spec.name!r} differs from "
                                     f"{other.name!r}'s")


#: Registered laws by the name a case file uses (the entry-point group ``hotroll.flow_stress``).
FLOW_STRESS_LAWS: Registry[LawSpec] = Registry("flow_stress", "flow-stress law", LawSpec,
                                               _same_parameters)
LAWS = FLOW_STRESS_LAWS   # the name before the one registry mechanism


def register(spec: LawSpec) -> LawSpec:
    """Add ``spec`` to :data:`LAWS` (a name once; a parameter name means one thing in all laws)."""
    return LAWS.register(spec.name, spec)
