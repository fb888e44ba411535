"""Drawing primitives shared by the figures: the roll, the contact edges, windows,
contours, markers and the atomic save."""
from __future__ import annotations

from pathlib import Path
from typing import Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.patches import Polygon
from matplotlib.tri import Triangulation

from hotroll.files import atomic
from hotroll.results.figures.run_files import RunFiles

DPI = 120
ROLL_FACE = "0.75"
CONTACT_COLOUR = "red"




# ---------------------------------------------------------------------------
# drawing helpers
# ---------------------------------------------------------------------------

def run_title(run: RunFiles, what: str) -> str:
    return f"{run.name}: {what}"


def save_figure(fig: plt.Figure, path: Path) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        with atomic(path) as tmp:
            fig.savefig(tmp, dpi=DPI)
    finally:
        plt.close(fig)
    return path


def draw_roll(ax, run: RunFiles, x_range: tuple[float, float] | None = None) -> None:
    """Draw the roll as a grey area bounded by its arc facing the strip (an asymmetric pass:
    both rolls, ``RunFiles.rolls``)."""
    for k, ((xc, yc), radius, side) in enumerate(run.rolls()):
        if x_range is None:
            x_range = (xc - radius, xc + radius)
        # phi such that xc - R sin(phi) sweeps x_range (clipped to the circle)
        s0 = np.clip((xc - x_range[1]) / radius, -1.0, 1.0)
        s1 = np.clip((xc - x_range[0]) / radius, -1.0, 1.0)
        phi = np.linspace(np.arcsin(s0), np.arcsin(s1), 400)
        ax_x = xc - radius * np.sin(phi)
        ax_y = yc - side * radius * np.cos(phi)
        poly = np.column_stack([np.r_[ax_x, ax_x[-1], ax_x[0]],
                                np.r_[ax_y, yc, yc]])
        ax.add_patch(Polygon(poly, closed=True, facecolor=ROLL_FACE, edgecolor="none",
                             alpha=0.5, zorder=0.5))
        ax.plot(ax_x, ax_y, color="k", lw=1.2, zorder=3, label="roll" if k == 0 else None)
        ax.plot([xc], [yc], marker="+", color="k", ms=8, zorder=3)


def draw_contact_edges(ax, run: RunFiles, lw: float = 2.0) -> None:
    if run.fields is None or "contact_edges" not in run.fields:
        return
    edges = np.asarray(run.fields["contact_edges"], dtype=int).reshape(-1, 2)
    if edges.size == 0:
        return
    pts = np.asarray(run.fields["points"], dtype=float)
    segs = pts[edges]
    ax.add_collection(LineCollection(segs, colors=CONTACT_COLOUR, linewidths=lw,
                                     zorder=4, label="contact"))


def draw_outline(ax, tri: Triangulation, lw: float = 0.8) -> None:
    """Boundary of the plate (edges belonging to exactly one triangle)."""
    t = tri.triangles
    edges = np.sort(np.vstack([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]), axis=1)
    uniq, count = np.unique(edges, axis=0, return_counts=True)
    bnd = uniq[count == 1]
    if len(bnd) == 0:
        return
    pts = np.column_stack([tri.x, tri.y])
    ax.add_collection(LineCollection(pts[bnd], colors="k", linewidths=lw, zorder=2))


def set_window(ax, window, *, full: Sequence[float] | None = None) -> None:
    if window is not None:
        ax.set_xlim(window[0], window[1])
        ax.set_ylim(window[2], window[3])
    elif full is not None:
        ax.set_xlim(full[0], full[1])
        ax.set_ylim(full[2], full[3])
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")


def full_extent(tri: Triangulation, pad: float = 0.05):
    x0, x1 = float(tri.x.min()), float(tri.x.max())
    y0, y1 = float(tri.y.min()), float(tri.y.max())
    dx, dy = x1 - x0, y1 - y0
    p = pad * max(dx, dy, 1e-12)
    return x0 - p, x1 + p, min(y0, 0.0) - 0.2 * p, y1 + 4 * p


def window_range(tri: Triangulation, values: np.ndarray, window) -> tuple[float, float]:
    """Finite min/max of vertex values inside the window (all if None)."""
    values = np.asarray(values, dtype=float)
    mask = np.isfinite(values)
    if window is not None:
        inside = ((tri.x >= window[0]) & (tri.x <= window[1])
                  & (tri.y >= window[2]) & (tri.y <= window[3]))
        if (mask & inside).any():
            mask &= inside
    if not mask.any():
        return 0.0, 1.0
    lo, hi = float(values[mask].min()), float(values[mask].max())
    if not hi > lo:
        d = max(abs(lo), 1.0) * 1e-6
        lo, hi = lo - d, hi + d
    return lo, hi


def contourf(ax, tri: Triangulation, values, window, label: str, cmap="viridis",
              symmetric: bool = False):
    lo, hi = window_range(tri, values, window)
    if symmetric:  # diverging colour map centred on zero
        hi = max(abs(lo), abs(hi))
        lo = -hi
    # odd number of bins when symmetric, so that zero sits inside the neutral bin
    levels = np.linspace(lo, hi, 22 if symmetric else 21)
    cs = ax.tricontourf(tri, np.asarray(values, dtype=float), levels=levels,
                        cmap=cmap, extend="both")
    ax.figure.colorbar(cs, ax=ax, label=label, shrink=0.9)
    return cs


def draw_vline(ax, x, label, **kw):
    if x is None or not np.isfinite(x):
        return
    style = dict(color="k", ls="--", lw=1.0)
    style.update(kw)
    ax.axvline(x, label=label, **style)


def draw_neutral(ax, marks, **style) -> None:
    """The neutral story's marks (``Neutral.marks``): a neutral point's line, or the sticking
    zone's span where no point is neutral, each with the story as its label."""
    for kind, at, label in marks:
        if kind == "line":
            ax.axvline(at[0], label=label, **{"color": "k", "ls": ":", "lw": 1.2, **style})
        else:
            ax.axvspan(at[0], at[1], label=label,
                       **{"color": "tab:purple", "alpha": 0.12, "lw": 0, **style})


#: (factor, unit) of a stress shown in the largest unit its magnitude reaches
STRESS_UNITS = ((1e6, "MPa"), (1e3, "kPa"), (1.0, "Pa"))


def stress_unit(*values) -> tuple[float, str]:
    """(factor, unit) to show stresses (Pa) in Pa, kPa or MPa by their largest magnitude: a
    K = 1 case's stresses of about 1 Pa are not drawn as 1e-6 MPa."""
    vals = [np.asarray(v, dtype=float) for v in values if v is not None]
    vals = [v[np.isfinite(v)] for v in vals]
    big = max((float(np.max(np.abs(v))) for v in vals if v.size), default=0.0)
    return next(((f, u) for f, u in STRESS_UNITS if big >= f), STRESS_UNITS[-1])


def not_available(ax, text="not available") -> None:
    ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes,
            color="0.4")
    ax.set_xticks([])
    ax.set_yticks([])
