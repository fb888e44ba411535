"""The recrystallisation parameter sets by name (issue 33): each set's module registers it once;
another package adds a set through the entry-point group ``hotroll.microstructure``
(``model/registry.py``, docs/how-to/add-a-law.md)."""
from __future__ import annotations

from hotroll.model.microstructure.base import RecrystallisationSet
from hotroll.model.registry import Registry, UnknownName

#: Registered sets by the name a case file's ``[microstructure] model`` uses.
SETS: Registry[RecrystallisationSet] = Registry("microstructure", "recrystallisation set",
                                                RecrystallisationSet)


class UnknownSet(UnknownName):
    """A set name that is not registered."""


def register(s: RecrystallisationSet) -> RecrystallisationSet:
    return SETS.register(s.name, s)


def get_set(name: str) -> RecrystallisationSet:
    try:
        return SETS.get(name)
    except UnknownName as e:
        raise UnknownSet(str(e)) from None


def sets_for(grade: str | None) -> list[str]:
    """The sets whose steels include ``grade``."""
    return [n for n, s in SETS.items() if grade is not None and grade.lower() in
            (g.lower() for g in s.steels)]
