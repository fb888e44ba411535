"""The friction laws by name: what a case file's ``[friction] law = "..."`` selects.

A law module declares its parameters, how to build the law, its default regularisation speed
and its slab-theory counterpart, and registers itself here; the case schema
(``config/friction.py``), the slab comparison, the warm-start distance and the summary read
the registry, so adding a law is its own module, its test and a line in docs/theory.md. Another
package adds a law through the entry-point group ``hotroll.friction`` (``model/registry.py``,
docs/how-to/add-a-law.md).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from hotroll.model.friction.base import FrictionLaw
from hotroll.model.parameters import Parameter
from hotroll.model.registry import Registry


@dataclass(frozen=True)
class FrictionSpec:
    """A friction law for the case file.

    ``build(values, v_reg, m)``: the law in reduced units (stresses over K) from the given
    parameters, the regularisation speed (m/s) and the rate exponent. ``v_reg_fraction``: the
    default regularisation speed over the roll surface speed. ``slab``: the slab theory's form
    (``"coulomb"``, ``"tresca"`` or ``"sticking"``) and the parameter it takes, or None.
    """

    name: str
    summary: str
    source: str
    parameters: tuple[Parameter, ...]
    build: Callable[[dict, float, float], FrictionLaw]
    v_reg_fraction: float
    slab: tuple[str, str | None] | None = None


#: Registered friction laws by the name a case file uses (the entry-point group
#: ``hotroll.friction``).
FRICTION_LAWS: Registry[FrictionSpec] = Registry("friction", "friction law", FrictionSpec)


def register(spec: FrictionSpec) -> FrictionSpec:
    """Add ``spec`` to :data:`FRICTION_LAWS` (a name once)."""
    return FRICTION_LAWS.register(spec.name, spec)
