"""The declaration of a summary key (``_f``: its SI unit, label, meaning, page group and the
condition it exists under) and the value of a key the summary does not have (``ABSENT``), shared
by ``results/summary_keys.py`` and ``results/spread_keys.py``."""
from __future__ import annotations

from dataclasses import field
from typing import Any


class _Absent:
    """The value of a key the summary does not have (written nowhere, not even as null)."""

    def __repr__(self) -> str:
        return "ABSENT"


ABSENT: Any = _Absent()
#: The groups of the HTML page's table (in this order; the rest under "Other").
GROUPS = ("Pass", "Width and spread", "Temperature and heat", "Checks", "Solver")


def _f(unit: str | None, label: str, meaning: str = "", *, group: str | None = None,
       when: str | None = None):
    """A summary field: SI ``unit`` (None: a name, flag, count or list without one), ``label``
    for a person, ``meaning`` for the reference, the page's ``group``, and ``when`` it exists
    (None: always; "thermal", "width", "spread", "run", ...)."""
    return field(default=ABSENT, metadata={"unit": unit, "label": label, "meaning": meaning,
                                           "group": group, "when": when})
