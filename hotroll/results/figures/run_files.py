"""A run directory read back for the figures (no NGSolve): summary.json, contact.csv,
top.csv, history.csv, fields.npz; any may be missing."""
from __future__ import annotations

import csv
import json
import math
import warnings
from pathlib import Path

import numpy as np
from matplotlib.tri import Triangulation

Table = dict  # column name -> 1D float array




# ---------------------------------------------------------------------------
# loading
# ---------------------------------------------------------------------------

def load_summary(out_dir: Path) -> dict:
    path = Path(out_dir) / "summary.json"
    if not path.is_file():
        return {}
    try:
        with open(path) as f:
            data = json.load(f)
    except (OSError, ValueError) as exc:
        warnings.warn(f"could not read {path}: {exc}")
        return {}
    return data if isinstance(data, dict) else {}


def to_float(text: str) -> float:
    text = text.strip()
    if text.lower() in ("true", "false"):
        return float(text.lower() == "true")
    try:
        return float(text)
    except ValueError:
        return math.nan


def load_csv(out_dir: Path, name: str) -> Table | None:
    """Read a comma separated file with a header line into {column: array}.

    Returns None if the file is missing or holds no data rows.
    """
    path = Path(out_dir) / name
    if not path.is_file():
        return None
    with open(path, newline="") as f:
        reader = csv.reader(f, skipinitialspace=True)
        rows = [r for r in reader if r and any(c.strip() for c in r)]
    if len(rows) < 2:
        return None
    header = [h.strip() for h in rows[0]]
    cols: dict[str, list[float]] = {h: [] for h in header}
    for row in rows[1:]:
        for h, cell in zip(header, row):
            cols[h].append(to_float(cell))
        for h in header[len(row):]:
            cols[h].append(math.nan)
    return {h: np.asarray(v, dtype=float) for h, v in cols.items()}


def load_fields(out_dir: Path) -> dict | None:
    path = Path(out_dir) / "fields.npz"
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


def column(table: Table | None, name: str) -> np.ndarray | None:
    if table is None:
        return None
    return table.get(name)


class RunFiles:
    """Everything that could be loaded from one output directory."""

    def __init__(self, out_dir: Path):
        self.dir = Path(out_dir)
        self.summary = load_summary(self.dir)
        self.contact = load_csv(self.dir, "contact.csv")
        self.top = load_csv(self.dir, "top.csv")
        self.history = load_csv(self.dir, "history.csv")
        self.fields = load_fields(self.dir)

    # -- derived quantities ---------------------------------------------
    @property
    def name(self) -> str:
        return str(self.summary.get("case_name") or self.dir.name)

    def roll(self) -> tuple[np.ndarray, float] | None:
        centre = self.summary.get("roll_centre")
        radius = self.summary.get("roll_radius")
        if (centre is None or radius is None) and self.fields is not None:
            centre = self.fields.get("roll_centre", centre)
            radius = self.fields.get("roll_radius", radius)
        if centre is None or radius is None:
            return None
        centre = np.asarray(centre, dtype=float).reshape(-1)
        if centre.size < 2:
            return None
        return centre[:2], float(np.asarray(radius, dtype=float))

    def neutral_x(self) -> float | None:
        p = self.summary.get("neutral_point")
        if p is not None and len(p) >= 1 and p[0] is not None and np.isfinite(p[0]):
            return float(p[0])
        x, vs = column(self.contact, "x"), column(self.contact, "v_slip")
        if x is None or vs is None:
            return None
        return zero_crossing(x, vs)

    def contact_range(self) -> tuple[float, float] | None:
        """x of the first touching point and of the contact exit."""
        xs = []
        for key in ("contact_start", "contact_end"):
            p = self.summary.get(key)
            if p is not None and len(p) >= 1 and p[0] is not None:
                xs.append(float(p[0]))
        if len(xs) == 2 and all(np.isfinite(xs)):
            return min(xs), max(xs)
        x = column(self.contact, "x")
        if x is not None and np.isfinite(x).any():
            return float(np.nanmin(x)), float(np.nanmax(x))
        if self.fields is not None and "contact_edges" in self.fields:
            edges = np.asarray(self.fields["contact_edges"], dtype=int).reshape(-1, 2)
            if edges.size:
                px = self.fields["points"][edges.ravel(), 0]
                return float(px.min()), float(px.max())
        return None

    def triangulation(self) -> Triangulation | None:
        if self.fields is None:
            return None
        pts = np.asarray(self.fields["points"], dtype=float)
        tris = np.asarray(self.fields["triangles"], dtype=int)
        if pts.ndim != 2 or tris.ndim != 2 or len(tris) == 0:
            return None
        return Triangulation(pts[:, 0], pts[:, 1], tris)

    def bite_window(self) -> tuple[float, float, float, float] | None:
        """(x0, x1, y0, y1) of a zoom on the roll bite."""
        rng = self.contact_range()
        if rng is None:
            return None
        xa, xb = rng
        length = max(xb - xa, 1e-12)
        x0, x1 = xa - 0.6 * length, xb + 0.6 * length
        ymax = None
        if self.fields is not None:
            pts = self.fields["points"]
            inside = (pts[:, 0] >= x0) & (pts[:, 0] <= x1)
            if inside.any():
                ymax = float(pts[inside, 1].max())
        if ymax is None and self.top is not None and "y" in self.top:
            ymax = float(np.nanmax(self.top["y"]))
        if ymax is None:
            ymax = length
        return x0, x1, 0.0, 1.12 * ymax


def zero_crossing(x: np.ndarray, y: np.ndarray) -> float | None:
    """x of the first sign change of y from negative to positive (linear interp.)."""
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    order = np.argsort(x)
    x, y = x[order], y[order]
    for i in range(len(x) - 1):
        if y[i] <= 0.0 < y[i + 1] or y[i] < 0.0 <= y[i + 1]:
            if y[i + 1] == y[i]:
                return float(x[i])
            return float(x[i] - y[i] * (x[i + 1] - x[i]) / (y[i + 1] - y[i]))
    return None
