"""The recrystallisation parameter sets by name (issue 33): each set's module registers it once."""
from __future__ import annotations

from hotroll.model.microstructure.base import RecrystallisationSet

SETS: dict[str, RecrystallisationSet] = {}


class UnknownSet(KeyError):
    """A set name that is not registered."""


def register(s: RecrystallisationSet) -> RecrystallisationSet:
    if s.name in SETS:
        raise ValueError(f"recrystallisation set {s.name!r} registered twice")
    SETS[s.name] = s
    return s


def get_set(name: str) -> RecrystallisationSet:
    try:
        return SETS[name]
    except KeyError:
        raise UnknownSet(f"unknown recrystallisation set {name!r} (allowed: "
                         f"{', '.join(SETS)})") from None


def sets_for(grade: str | None) -> list[str]:
    """The sets whose steels include ``grade``."""
    return [n for n, s in SETS.items() if grade is not None and grade.lower() in
            (g.lower() for g in s.steels)]
