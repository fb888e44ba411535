"""A law's parameter as a case file gives it: name, text, unit, allowed range (plain data; the
case schema in ``config/`` turns each into a validated field). Shared by the flow-stress and
friction law registries."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Parameter:
    """One parameter of a law as the case file gives it (SI units; ``unit`` as printed)."""

    name: str
    text: str
    unit: str
    allowed: str
    required: bool = True
    #: words allowed besides numbers (e.g. "estimate") and the value taken when not given
    words: tuple[str, ...] = ()
    default: float | str | None = None
    gt: float | None = None
    ge: float | None = None
    lt: float | None = None
    le: float | None = None
