"""A run directory read back for the figures (no NGSolve): summary.json, contact.csv,
top.csv, history.csv, fields.npz; any may be missing."""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.tri import Triangulation

from hotroll.results.neutral import Neutral
from hotroll.results.run_dir import RunDir

Table = dict  # column name -> 1D float array




# ---------------------------------------------------------------------------
# loading
# ---------------------------------------------------------------------------

def column(table: Table | None, name: str) -> np.ndarray | None:
    if table is None:
        return None
    return table.get(name)


class RunFiles:
    """Everything that could be loaded from one output directory."""

    def __init__(self, out_dir: Path):
        self.dir = Path(out_dir)
        files = RunDir(self.dir)
        self.summary = files.summary(strict=False)
        self.contact = files.table("contact.csv")
        self.top = files.table("top.csv")
        self.history = files.table("history.csv")
        self.fields = files.fields()

    def dir_table(self, name: str) -> Table | None:
        """Another CSV table of the run directory (e.g. an asymmetric pass's
        ``contact_lower.csv``), None if missing."""
        return RunDir(self.dir).table(name)

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

    def rolls(self) -> list[tuple[np.ndarray, float, int]]:
        """(centre, radius, side) of each roll drawn: the upper (``roll``), and for an
        asymmetric pass (a summary with two ``rolls``) the lower, its centre below the exit
        mid-plane (y = 0) by h1/2 + its radius."""
        roll = self.roll()
        if roll is None:
            return []
        out = [(roll[0], roll[1], 1)]
        rolls = self.summary.get("rolls") or []
        if len(rolls) == 2 and rolls[1].get("radius"):
            (xc, yc), R = roll
            R2 = float(rolls[1]["radius"])
            out.append((np.array([xc, -(yc - R) - R2]), R2, -1))
        return out

    def neutral(self) -> Neutral:
        """The run's neutral story, as its summary tells it (``results/neutral.py``): every
        figure draws this one, never a sign change of its own."""
        return Neutral.from_summary(self.summary or {})

    def neutral_x(self) -> float | None:
        """x of the neutral point (m), None where the summary says there is none."""
        n = self.neutral()
        return n.point[0] if n.kind == "point" and n.point else None

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
        if len(self.rolls()) == 2 and self.fields is not None:      # the whole thickness
            ymin = float(self.fields["points"][:, 1].min())
            return x0, x1, 1.12 * ymin, 1.12 * ymax
        return x0, x1, 0.0, 1.12 * ymax
