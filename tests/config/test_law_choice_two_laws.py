"""config/thermal.py's law field when a kind has two laws (a plugin may register a second one
through the entry-point group ``hotroll.heat_transfer``; the package registers one per kind,
tests/config/test_law_section.py): the description lists both, "; " between them, the first
registered is the default and both are allowed."""
from __future__ import annotations

import typing

import hotroll.config.thermal as thermal
from hotroll.model.heat_transfer.registry import HeatTransferSpec


def _spec(name: str, summary: str) -> HeatTransferSpec:
    return HeatTransferSpec(name, "surface", summary, "", (), lambda v: None)


def test_two_surface_laws_are_listed_in_the_fields_description(monkeypatch):
    laws = {"a": _spec("a", "q = 1"), "b": _spec("b", "q = 2")}
    monkeypatch.setattr(thermal, "laws_of", lambda kind: laws)
    kind, info = thermal._law_choice("surface")
    assert typing.get_args(kind) == ("a", "b") and info.default == "a"
    assert info.description == ('heat-transfer law of the surface: a (q = 1); b (q = 2) [-]; '
                                'allowed: "a", "b"')
