"""Writing results: atomic JSON/CSV/NPZ files. The ParaView (VTK) files are the solver's to write
(``Solution.write_vtk``, ``solvers/record_fields.py``): results imports no FE."""
from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from hotroll.files import DiskFullError, atomic, disk_full  # noqa: F401  (the app's writers use them)


def _atomic_write_text(path: Path, text: str) -> None:
    with atomic(path) as tmp:
        with open(tmp, "w") as f:
            f.write(text)


def _clean(v):
    if isinstance(v, (np.floating, float)):
        return float(v) if math.isfinite(v) else None
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.bool_,)):
        return bool(v)
    if isinstance(v, (list, tuple, np.ndarray)):
        return [_clean(x) for x in v]
    if isinstance(v, Mapping):       # a dict or a typed Summary
        return {k: _clean(x) for k, x in v.items()}
    return v


def write_json(path: Path, data: dict) -> None:
    """JSON with NaN/inf written as null."""
    _atomic_write_text(Path(path), json.dumps(_clean(data), indent=2) + "\n")


def write_csv(path: Path, columns: dict[str, np.ndarray] | list[dict]) -> None:
    """A CSV with a header line, from column arrays or from a list of row dicts."""
    if isinstance(columns, list):
        keys = list(columns[0].keys()) if columns else []
        rows = [[r.get(k) for k in keys] for r in columns]
    else:
        keys = list(columns.keys())
        rows = list(zip(*[np.asarray(columns[k]).tolist() for k in keys]))
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(keys)
    for r in rows:
        w.writerow(["" if x is None else (repr(float(x)) if isinstance(x, float) else x)
                    for x in r])
    _atomic_write_text(Path(path), buf.getvalue())


def write_npz(path: Path, **arrays) -> None:
    with atomic(Path(path)) as tmp:
        np.savez_compressed(tmp, **arrays)


def write_text(path: Path, text: str) -> None:
    """A text file, atomically (``atomic``)."""
    _atomic_write_text(Path(path), text)
