"""Building test cases from a base dict: one section replaced and dotted keys overridden."""
from __future__ import annotations

import copy

from hotroll.app.config import Case, case_from_dict


def build_case(base: dict, section: str | None = None, table: dict | None = None,
               **dotted) -> Case:
    """``base`` with ``[section]`` replaced by ``table`` (if given) and ``{"sec.key": v}`` set."""
    d = copy.deepcopy(base)
    if table is not None:
        d[section] = table
    for key, value in dotted.items():
        sec, name = key.split(".")
        d.setdefault(sec, {})[name] = value
    return case_from_dict(d)
