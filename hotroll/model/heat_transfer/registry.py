"""The heat-transfer laws by name: what a case file's ``[thermal] contact_law = "..."`` and
``surface_law = "..."`` select. A law module declares its parameters (with unit and range),
where it acts (``kind``), how to build it and its source, and registers itself here; the
``[thermal]`` section (``config/thermal.py``) is built from the registry, so adding a law is its
own module, its test and a line in docs/theory.md. Another package adds a law through the
entry-point group ``hotroll.heat_transfer`` (``model/registry.py``, docs/how-to/add-a-law.md)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping

from hotroll.model.heat_transfer.base import KINDS, HeatTransferLaw
from hotroll.model.parameters import Parameter
from hotroll.model.registry import Registry


@dataclass(frozen=True)
class HeatTransferSpec:
    """A heat-transfer law for the case file: ``build(values)`` from the given parameters."""

    name: str
    kind: str
    summary: str
    source: str
    parameters: tuple[Parameter, ...]
    build: Callable[[dict], HeatTransferLaw]


def _known_kind(spec: HeatTransferSpec, registered: Mapping[str, HeatTransferSpec]) -> None:
    if spec.kind not in KINDS:
        raise ValueError(f"heat-transfer law {spec.name!r}: kind must be one of {KINDS}")


#: Registered heat-transfer laws by the name a case file uses (the entry-point group
#: ``hotroll.heat_transfer``).
HEAT_TRANSFER_LAWS: Registry[HeatTransferSpec] = Registry(
    "heat_transfer", "heat-transfer law", HeatTransferSpec, _known_kind)


def register(spec: HeatTransferSpec) -> HeatTransferSpec:
    """Add ``spec`` to :data:`HEAT_TRANSFER_LAWS` (a name once, a known kind)."""
    return HEAT_TRANSFER_LAWS.register(spec.name, spec)


def laws_of(kind: str) -> dict[str, HeatTransferSpec]:
    """The registered laws acting on ``kind`` ("contact" or "surface"), in registration order."""
    return {n: s for n, s in HEAT_TRANSFER_LAWS.items() if s.kind == kind}
