"""The heat-transfer laws by name: what a case file's ``[thermal] contact_law = "..."`` and
``surface_law = "..."`` select. A law module declares its parameters (with unit and range),
where it acts (``kind``), how to build it and its source, and registers itself here; the
``[thermal]`` section (``config/thermal.py``) is built from the registry, so adding a law is its
own module, its test and a line in docs/theory.md."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from hotroll.model.heat_transfer.base import KINDS, HeatTransferLaw
from hotroll.model.parameters import Parameter


@dataclass(frozen=True)
class HeatTransferSpec:
    """A heat-transfer law for the case file: ``build(values)`` from the given parameters."""

    name: str
    kind: str
    summary: str
    source: str
    parameters: tuple[Parameter, ...]
    build: Callable[[dict], HeatTransferLaw]


#: Registered heat-transfer laws by the name a case file uses.
HEAT_TRANSFER_LAWS: dict[str, HeatTransferSpec] = {}


def register(spec: HeatTransferSpec) -> HeatTransferSpec:
    """Add ``spec`` to :data:`HEAT_TRANSFER_LAWS` (a name once, a known kind)."""
    if spec.name in HEAT_TRANSFER_LAWS:
        raise ValueError(f"heat-transfer law {spec.name!r} registered twice")
    if spec.kind not in KINDS:
        raise ValueError(f"heat-transfer law {spec.name!r}: kind must be one of {KINDS}")
    HEAT_TRANSFER_LAWS[spec.name] = spec
    return spec


def laws_of(kind: str) -> dict[str, HeatTransferSpec]:
    """The registered laws acting on ``kind`` ("contact" or "surface"), in registration order."""
    return {n: s for n, s in HEAT_TRANSFER_LAWS.items() if s.kind == kind}
