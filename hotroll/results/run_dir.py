"""A run's output directory read back: the one reader of ``summary.json``, the CSV tables
(``contact.csv``, ``top.csv``, ``history.csv``, ``exit_profile.csv``) and ``fields.npz``, used
by the Python API, the figures, the HTML page, the slab comparison and the resume of schedules
and studies (docs/reference/summary.md lists what each file holds)."""
from __future__ import annotations

import csv
import json
import math
import warnings
from pathlib import Path

import numpy as np

from hotroll.results.summary import Summary

#: Cells that read as numbers besides the numerals: switches written by the history.
_SWITCHES = {"true": 1.0, "false": 0.0}


def _number(cell: str) -> float | None:
    """A cell as a float (empty: NaN; true/false: 1/0), None when it is text."""
    text = cell.strip()
    if text == "":
        return math.nan
    if text.lower() in _SWITCHES:
        return _SWITCHES[text.lower()]
    try:
        return float(text)
    except ValueError:
        return None


class RunDir:
    """One run's output directory (what ``workflows/runner.py: run_case`` wrote)."""

    def __init__(self, path: str | Path):
        self.path = Path(path)

    def summary(self, *, strict: bool = True) -> Summary:
        """``summary.json`` as a ``Summary`` (keys another version wrote are kept);
        ``strict=False``: an empty one (with a warning if the file is unreadable) when it is
        missing or broken, for drawing what the other files allow."""
        path = self.path / "summary.json"
        try:
            data = json.loads(path.read_text())
        except (OSError, ValueError) as exc:
            if strict:
                raise
            if path.is_file():
                warnings.warn(f"could not read {path}: {exc}")
            return Summary()
        if not isinstance(data, dict):
            if strict:
                raise ValueError(f"{path}: expected a JSON object")
            return Summary()
        return Summary.from_dict(data, strict=False)

    def table(self, name: str) -> dict[str, np.ndarray] | None:
        """A CSV table as columns: numbers as float arrays (empty cells NaN, true/false 1/0),
        a column with text as an object array; None if the file is missing or has no rows."""
        path = self.path / name
        if not path.is_file():
            return None
        with open(path, newline="") as fh:
            rows = [r for r in csv.reader(fh, skipinitialspace=True) if any(c.strip() for c in r)]
        if len(rows) < 2:
            return None
        head, body = [h.strip() for h in rows[0]], rows[1:]
        out = {}
        for j, name_j in enumerate(head):
            cells = [r[j] if j < len(r) else "" for r in body]
            numbers = [_number(c) for c in cells]
            out[name_j] = (np.asarray(numbers, dtype=float) if None not in numbers
                           else np.asarray(cells, dtype=object))
        return out

    def fields(self) -> dict | None:
        """``fields.npz`` (vertex points, triangles and fields); None if missing or unreadable."""
        path = self.path / "fields.npz"
        if not path.is_file():
            return None
        try:
            with np.load(path, allow_pickle=False) as data:
                fields = {k: np.asarray(data[k]) for k in data.files}
        except (OSError, ValueError) as exc:
            warnings.warn(f"could not read {path}: {exc}")
            return None
        if "points" not in fields or "triangles" not in fields:
            return None
        return fields

    def finished_summary(self, case_toml: str) -> Summary | None:
        """The summary of a finished run of this very case (``case.toml`` the same text), else
        None: what a schedule or a study reads back instead of solving again."""
        s, c = self.path / "summary.json", self.path / "case.toml"
        if s.is_file() and c.is_file() and c.read_text() == case_toml:
            return Summary.from_dict(json.loads(s.read_text()), strict=False)
        return None
