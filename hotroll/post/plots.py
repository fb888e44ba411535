"""Figures made only from the files a run writes into its output directory.

No NGSolve import: everything is read back from ``summary.json``,
``contact.csv``, ``top.csv``, ``history.csv`` and ``fields.npz`` (any of them
may be missing; figures that need a missing file are skipped).

Conventions (as written by the solver): SI units, the model is the upper half
of the plate (y = 0 is the symmetry axis), the roll centre lies above the
plate and the plate moves in +x.  A point of the roll surface at angle ``phi``
(measured from the roll's vertical centre line, positive towards the entry)
is ``(xc - R sin(phi), yc - R cos(phi))``.

Public functions
----------------
plot_all(out_dir)                        -> list[Path]   (fig_*.png in out_dir; the
                                                          temperature's in plots_thermal.py)
plot_compare(runs, out_png, title="")    -> Path         (overlay of several runs)
"""

from __future__ import annotations

import csv
import json
import math
import warnings
from pathlib import Path
from typing import Callable, Mapping, Sequence

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402
from matplotlib.tri import LinearTriInterpolator, Triangulation  # noqa: E402

from ..files import DiskFullError, atomic  # noqa: E402

__all__ = ["plot_all", "plot_compare"]

DPI = 120
ROLL_FACE = "0.75"
CONTACT_COLOUR = "red"

Table = dict  # column name -> 1D float array


# ---------------------------------------------------------------------------
# loading
# ---------------------------------------------------------------------------

def _load_summary(out_dir: Path) -> dict:
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


def _to_float(text: str) -> float:
    text = text.strip()
    if text.lower() in ("true", "false"):
        return float(text.lower() == "true")
    try:
        return float(text)
    except ValueError:
        return math.nan


def _load_csv(out_dir: Path, name: str) -> Table | None:
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
            cols[h].append(_to_float(cell))
        for h in header[len(row):]:
            cols[h].append(math.nan)
    return {h: np.asarray(v, dtype=float) for h, v in cols.items()}


def _load_fields(out_dir: Path) -> dict | None:
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


def _col(table: Table | None, name: str) -> np.ndarray | None:
    if table is None:
        return None
    return table.get(name)


class _Run:
    """Everything that could be loaded from one output directory."""

    def __init__(self, out_dir: Path):
        self.dir = Path(out_dir)
        self.summary = _load_summary(self.dir)
        self.contact = _load_csv(self.dir, "contact.csv")
        self.top = _load_csv(self.dir, "top.csv")
        self.history = _load_csv(self.dir, "history.csv")
        self.fields = _load_fields(self.dir)

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
        x, vs = _col(self.contact, "x"), _col(self.contact, "v_slip")
        if x is None or vs is None:
            return None
        return _zero_crossing(x, vs)

    def contact_range(self) -> tuple[float, float] | None:
        """x of the first touching point and of the contact exit."""
        xs = []
        for key in ("contact_start", "contact_end"):
            p = self.summary.get(key)
            if p is not None and len(p) >= 1 and p[0] is not None:
                xs.append(float(p[0]))
        if len(xs) == 2 and all(np.isfinite(xs)):
            return min(xs), max(xs)
        x = _col(self.contact, "x")
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


def _zero_crossing(x: np.ndarray, y: np.ndarray) -> float | None:
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


# ---------------------------------------------------------------------------
# drawing helpers
# ---------------------------------------------------------------------------

def _title(run: _Run, what: str) -> str:
    return f"{run.name}: {what}"


def _save(fig: plt.Figure, path: Path) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        with atomic(path) as tmp:
            fig.savefig(tmp, dpi=DPI)
    finally:
        plt.close(fig)
    return path


def _draw_roll(ax, run: _Run, x_range: tuple[float, float] | None = None) -> None:
    """Draw the roll as a grey area bounded by its lower arc."""
    roll = run.roll()
    if roll is None:
        return
    (xc, yc), radius = roll
    if x_range is None:
        x_range = (xc - radius, xc + radius)
    # phi such that xc - R sin(phi) sweeps x_range (clipped to the circle)
    s0 = np.clip((xc - x_range[1]) / radius, -1.0, 1.0)
    s1 = np.clip((xc - x_range[0]) / radius, -1.0, 1.0)
    phi = np.linspace(np.arcsin(s0), np.arcsin(s1), 400)
    ax_x = xc - radius * np.sin(phi)
    ax_y = yc - radius * np.cos(phi)
    poly = np.column_stack([np.r_[ax_x, ax_x[-1], ax_x[0]],
                            np.r_[ax_y, yc, yc]])
    ax.add_patch(Polygon(poly, closed=True, facecolor=ROLL_FACE, edgecolor="none",
                         alpha=0.5, zorder=0.5))
    ax.plot(ax_x, ax_y, color="k", lw=1.2, zorder=3, label="roll")
    ax.plot([xc], [yc], marker="+", color="k", ms=8, zorder=3)


def _draw_contact_edges(ax, run: _Run, lw: float = 2.0) -> None:
    if run.fields is None or "contact_edges" not in run.fields:
        return
    edges = np.asarray(run.fields["contact_edges"], dtype=int).reshape(-1, 2)
    if edges.size == 0:
        return
    pts = np.asarray(run.fields["points"], dtype=float)
    segs = pts[edges]
    ax.add_collection(LineCollection(segs, colors=CONTACT_COLOUR, linewidths=lw,
                                     zorder=4, label="contact"))


def _draw_outline(ax, tri: Triangulation, lw: float = 0.8) -> None:
    """Boundary of the plate (edges belonging to exactly one triangle)."""
    t = tri.triangles
    edges = np.sort(np.vstack([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]), axis=1)
    uniq, count = np.unique(edges, axis=0, return_counts=True)
    bnd = uniq[count == 1]
    if len(bnd) == 0:
        return
    pts = np.column_stack([tri.x, tri.y])
    ax.add_collection(LineCollection(pts[bnd], colors="k", linewidths=lw, zorder=2))


def _set_window(ax, window, *, full: Sequence[float] | None = None) -> None:
    if window is not None:
        ax.set_xlim(window[0], window[1])
        ax.set_ylim(window[2], window[3])
    elif full is not None:
        ax.set_xlim(full[0], full[1])
        ax.set_ylim(full[2], full[3])
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")


def _full_extent(tri: Triangulation, pad: float = 0.05):
    x0, x1 = float(tri.x.min()), float(tri.x.max())
    y0, y1 = float(tri.y.min()), float(tri.y.max())
    dx, dy = x1 - x0, y1 - y0
    p = pad * max(dx, dy, 1e-12)
    return x0 - p, x1 + p, min(y0, 0.0) - 0.2 * p, y1 + 4 * p


def _window_range(tri: Triangulation, values: np.ndarray, window) -> tuple[float, float]:
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


def _contourf(ax, tri: Triangulation, values, window, label: str, cmap="viridis",
              symmetric: bool = False):
    lo, hi = _window_range(tri, values, window)
    if symmetric:  # diverging colour map centred on zero
        hi = max(abs(lo), abs(hi))
        lo = -hi
    # odd number of bins when symmetric, so that zero sits inside the neutral bin
    levels = np.linspace(lo, hi, 22 if symmetric else 21)
    cs = ax.tricontourf(tri, np.asarray(values, dtype=float), levels=levels,
                        cmap=cmap, extend="both")
    ax.figure.colorbar(cs, ax=ax, label=label, shrink=0.9)
    return cs


def _vline(ax, x, label, **kw):
    if x is None or not np.isfinite(x):
        return
    style = dict(color="k", ls="--", lw=1.0)
    style.update(kw)
    ax.axvline(x, label=label, **style)


def _na(ax, text="not available") -> None:
    ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes,
            color="0.4")
    ax.set_xticks([])
    ax.set_yticks([])


# ---------------------------------------------------------------------------
# single-run figures
# ---------------------------------------------------------------------------

def _fig_mesh(run: _Run, path: Path) -> Path | None:
    tri = run.triangulation()
    if tri is None:
        return None
    full = _full_extent(tri)
    window = run.bite_window()
    fig, axes = plt.subplots(2, 1, figsize=(10, 8), layout="constrained")
    for ax, win, lw in ((axes[0], None, 0.25), (axes[1], window, 0.5)):
        ax.triplot(tri, color="tab:blue", lw=lw)
        _draw_roll(ax, run, (full[0], full[1]))
        _draw_contact_edges(ax, run, lw=1.5 if win is None else 2.5)
        _set_window(ax, win, full=full)
    axes[0].set_title(_title(run, "deformed mesh"))
    axes[1].set_title("zoom on the roll bite" + (" (contact edges red)"))
    for key, marker in (("contact_start", "o"), ("contact_end", "s")):
        p = run.summary.get(key)
        if p is not None and len(p) >= 2:
            axes[1].plot(p[0], p[1], marker=marker, color="k", mfc="none",
                         ms=7, zorder=5, ls="none",
                         label="first touching point" if key == "contact_start"
                         else "contact exit")
    handles, _ = axes[1].get_legend_handles_labels()
    if handles:
        axes[1].legend(loc="lower left", fontsize=8)
    return _save(fig, path)


def _fig_sigma_ef(run: _Run, path: Path) -> Path | None:
    tri = run.triangulation()
    if tri is None or "sigma_ef" not in run.fields:
        return None
    sig = np.asarray(run.fields["sigma_ef"], dtype=float)
    full = _full_extent(tri)
    window = run.bite_window()
    fig, axes = plt.subplots(2, 1, figsize=(10, 8), layout="constrained")
    for ax, win in ((axes[0], None), (axes[1], window)):
        lo, hi = _window_range(tri, sig, win)
        tp = ax.tripcolor(tri, sig, shading="gouraud", cmap="jet", vmin=lo, vmax=hi)
        fig.colorbar(tp, ax=ax, label=r"$\sigma_{ef}$ [Pa]", shrink=0.9)
        _draw_outline(ax, tri)
        _draw_roll(ax, run, (full[0], full[1]))
        _draw_contact_edges(ax, run, lw=1.0)
        _set_window(ax, win, full=full)
    axes[0].set_title(_title(run, r"effective stress $\sigma_{ef}$ [Pa]"))
    axes[1].set_title(r"zoom on the roll bite, $\sigma_{ef}$ [Pa]")
    return _save(fig, path)


def _fig_velocity(run: _Run, path: Path) -> Path | None:
    tri = run.triangulation()
    if tri is None or "v" not in run.fields:
        return None
    v = np.asarray(run.fields["v"], dtype=float).reshape(-1, 2)
    full = _full_extent(tri)
    window = run.bite_window()
    fig, axes = plt.subplots(3, 1, figsize=(9, 10), layout="constrained")
    _contourf(axes[0], tri, v[:, 0], window, r"$v_1$ [m/s]")
    axes[0].set_title(_title(run, r"velocity $v_1$ [m/s] near the roll bite"))
    _contourf(axes[1], tri, v[:, 1], window, r"$v_2$ [m/s]", cmap="coolwarm",
              symmetric=True)
    axes[1].set_title(r"velocity $v_2$ [m/s]")

    ax = axes[2]
    speed = np.hypot(v[:, 0], v[:, 1])
    ax.triplot(tri, color="0.8", lw=0.3)
    win = window if window is not None else full
    nx = 36
    ny = max(4, int(round(nx * (win[3] - win[2]) / max(win[1] - win[0], 1e-12))))
    gx, gy = np.meshgrid(np.linspace(win[0], win[1], nx + 2)[1:-1],
                         np.linspace(win[2], win[3], ny + 2)[1:-1])
    u1 = LinearTriInterpolator(tri, v[:, 0])(gx, gy)
    u2 = LinearTriInterpolator(tri, v[:, 1])(gx, gy)
    keep = ~np.ma.getmaskarray(u1) & ~np.ma.getmaskarray(u2)
    if keep.any():
        a1, a2 = np.ma.getdata(u1)[keep], np.ma.getdata(u2)[keep]
        q = ax.quiver(gx[keep], gy[keep], a1, a2, np.hypot(a1, a2),
                      cmap="viridis", angles="xy", pivot="tail", width=0.003)
        fig.colorbar(q, ax=ax, label="|v| [m/s]", shrink=0.9)
    else:  # mesh too coarse for the grid: arrows at the vertices instead
        q = ax.quiver(tri.x, tri.y, v[:, 0], v[:, 1], speed, cmap="viridis",
                      angles="xy")
        fig.colorbar(q, ax=ax, label="|v| [m/s]", shrink=0.9)
    ax.set_title("velocity vectors")
    for a in axes:
        _draw_outline(a, tri)
        _draw_roll(a, run, (full[0], full[1]))
        _draw_contact_edges(a, run, lw=1.0)
        _set_window(a, window, full=full)
    return _save(fig, path)


def _profile_panel(ax, x, y, ylabel: str, title: str, what: str, **style) -> None:
    """One contact profile against x with its zero line, or a 'not available' panel."""
    if y is None:
        _na(ax, f"{what} not available")
        return
    ax.plot(x, y, ".-", ms=3, **style)
    ax.axhline(0.0, color="0.5", lw=0.8)
    ax.set_ylabel(ylabel)
    ax.set_title(title)


def _fig_contact(run: _Run, path: Path) -> Path | None:
    c = run.contact
    x = _col(c, "x")
    if x is None:
        return None
    xn = run.neutral_x()
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), layout="constrained")
    (a_vs, a_sn), (a_st, a_zoom) = axes

    vs = _col(c, "v_slip")
    _profile_panel(a_vs, x, vs, r"$v_s$ [m/s]", r"relative (slip) velocity $v_s$", "v_slip")

    sn, snc = _col(c, "normal_stress"), _col(c, "normal_stress_corrected")
    sns = _col(c, "normal_stress_smooth")
    exact = run.summary.get("contact_method") == "multiplier"
    if exact:        # the multiplier is P1 already: its nodes, no projection or correction
        sns = snc = None
    if sn is not None or snc is not None:
        if sn is not None:
            a_sn.plot(x, sn, ".-" if exact else ".", ms=2.5, color="C0" if exact else "0.6",
                      label="contact multiplier (nodal)" if exact
                      else "raw (nodal penalty reaction)")
        if sns is not None:
            a_sn.plot(x, sns, "-", lw=1.5, color="C0", label="P1 projection")
        if snc is not None:
            a_sn.plot(x, snc, "--", lw=1.2, color="C1", label="exit-corrected (raw)")
        a_sn.set_ylabel(r"$T_n\cdot n$ [Pa]")
        a_sn.set_title(r"normal contact stress $T_n\cdot n$ [Pa]")
        a_sn.legend(fontsize=8)
    else:
        _na(a_sn, "normal stress not available")

    st, sts = _col(c, "shear_stress"), _col(c, "shear_stress_smooth")
    if sts is not None:
        a_st.plot(x, st, ".", ms=2.5, color="0.6", label="raw (friction law at the nodes)")
        _profile_panel(a_st, x, sts, r"$T_\tau\cdot n_\tau$ [Pa]",
                       r"tangential stress $T_\tau\cdot n_\tau$ [Pa]", "shear stress",
                       color="tab:green", label="P1 projection")
        a_st.legend(fontsize=8)
    else:
        _profile_panel(a_st, x, st, r"$T_\tau\cdot n_\tau$ [Pa]",
                       r"tangential stress $T_\tau\cdot n_\tau$ [Pa]", "shear stress",
                       color="tab:green")

    if vs is not None:
        _zoom_slip(a_zoom, [(run, None)])
        a_zoom.set_title(r"$v_s$ around the neutral point")
    else:
        _na(a_zoom)

    for ax in (a_vs, a_sn, a_st, a_zoom):
        ax.set_xlabel("x [m]")
        ax.grid(alpha=0.3)
        _vline(ax, xn, "neutral point")
    a_vs.legend(fontsize=8)
    extra = []
    ang = run.summary.get("neutral_angle")
    if ang is not None and np.isfinite(ang):
        extra.append(f"neutral angle {math.degrees(ang):.3g}°")
    fs = run.summary.get("forward_slip")
    if fs is not None and np.isfinite(fs):
        extra.append(f"forward slip {fs:.3g}")
    fig.suptitle(_title(run, "contact profiles") + (" (" + ", ".join(extra) + ")"
                                                      if extra else ""))
    return _save(fig, path)


def _fig_top(run: _Run, path: Path) -> Path | None:
    t = run.top
    x = _col(t, "x")
    if x is None:
        return None
    rng = run.contact_range()
    xn = run.neutral_x()
    fig, axes = plt.subplots(2, 1, figsize=(9, 7), sharex=True, layout="constrained")
    for ax, key, lab in ((axes[0], "v1", r"$v_1$ [m/s]"), (axes[1], "v2", r"$v_2$ [m/s]")):
        y = _col(t, key)
        if y is None:
            _na(ax, f"{key} not available")
            continue
        ax.plot(x, y, ".-", ms=3, label=key)
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
        if rng is not None:
            ax.axvspan(rng[0], rng[1], color="tab:orange", alpha=0.12, label="contact")
            _vline(ax, rng[0], "first touching point", color="tab:orange")
            _vline(ax, rng[1], "contact exit", color="tab:red")
        _vline(ax, xn, "neutral point", color="k", ls=":")
    vr = run.summary.get("roll_surface_speed")
    if vr is not None and np.isfinite(vr) and _col(t, "v1") is not None:
        axes[0].axhline(vr, color="0.4", lw=1.0, ls="-.", label="roll surface speed")
    axes[0].legend(fontsize=8, loc="best")
    axes[0].set_title(_title(run, "velocity along the top boundary"))
    axes[1].set_xlabel("x [m]")
    return _save(fig, path)


_HISTORY_PANELS = (
    ("strain_rate_measure", "strain-rate measure", True),
    ("slip_measure", "slip measure", True),
    ("a_f", r"$a_f$", False),
    ("roll_force", "roll force [N/m]", False),
    ("neutral_angle", "neutral angle [rad]", False),
    ("iterations", "iterations per step", False),
)


def _fig_history(run: _Run, path: Path) -> Path | None:
    h = run.history
    if h is None:
        return None
    t = _col(h, "time")
    xlabel, title = "time [s]", "time history"
    steady = t is None or not np.isfinite(t).any()
    if steady:   # the steady solver: one row per a_f / free-surface update and per Newton solve
        t = _col(h, "step")
        xlabel, title = "a_f / free-surface update", "steady solver history"
    if t is None:
        return None
    fig, axes = plt.subplots(2, 3, figsize=(13, 7), sharex=True, layout="constrained")
    for ax, (key, label, logy) in zip(axes.ravel(), _HISTORY_PANELS):
        y = _col(h, key)
        if y is None or not np.isfinite(y).any():
            _na(ax, f"{key} not available")
            ax.set_title(label)
            continue
        if key == "iterations":
            if steady:
                y, label = np.cumsum(y), "Newton iterations (cumulative)"
            ax.step(t, y, where="mid")
            ax.yaxis.set_major_locator(MaxNLocator(integer=True))
        else:
            ax.plot(t, y, ".-", ms=3)
        if logy and np.nanmin(y) > 0:
            ax.set_yscale("log")
        ax.set_title(label)
        ax.set_xlabel(xlabel)
        ax.grid(alpha=0.3)
    fig.suptitle(_title(run, title))
    return _save(fig, path)


# ---------------------------------------------------------------------------
# public API
# ---------------------------------------------------------------------------

def _fig_contact_angle(run: _Run, path: Path) -> Path | None:
    """Pressure and shear (MPa) over the roll angle: P1 projection, raw nodal values as dots,
    the axes fitted to the projection (off-scale raw values marked at the edge)."""
    from .compare_plot import plot_compare_profiles

    if run.contact is None or _col(run.contact, "angle") is None:
        return None
    return plot_compare_profiles(run.contact, None, run.summary, path, fe_only=True,
                                 title=_title(run, "contact pressure and shear"))


_FIGURES: tuple[tuple[str, Callable[[_Run, Path], Path | None]], ...] = (
    ("fig_mesh.png", _fig_mesh),
    ("fig_sigma_ef.png", _fig_sigma_ef),
    ("fig_velocity.png", _fig_velocity),
    ("fig_contact.png", _fig_contact),
    ("fig_contact_angle.png", _fig_contact_angle),
    ("fig_top.png", _fig_top),
    ("fig_history.png", _fig_history),
)


def plot_all(out_dir) -> list[Path]:
    """Write all figures that the files in ``out_dir`` allow; return their paths.

    A figure that fails is reported with a warning and skipped so that one
    bad file does not cost the others; a full disk (``files.DiskFullError``) stops.
    """
    from .plots_thermal import FIGURES as THERMAL_FIGURES

    out_dir = Path(out_dir)
    run = _Run(out_dir)
    written: list[Path] = []
    for name, func in _FIGURES + THERMAL_FIGURES:
        try:
            p = func(run, out_dir / name)
        except DiskFullError:
            plt.close("all")
            raise
        except Exception as exc:  # noqa: BLE001 - post-processing must not abort a run
            plt.close("all")
            warnings.warn(f"{name}: skipped ({type(exc).__name__}: {exc})")
            continue
        if p is not None:
            written.append(p)
    return written


def _zoom_slip(ax, runs: Sequence[tuple[_Run, str | None]]) -> None:
    """v_slip vs x restricted to a window around the neutral point(s)."""
    neutral = [r.neutral_x() for r, _ in runs]
    neutral = [x for x in neutral if x is not None]
    lengths = []
    for r, _ in runs:
        rng = r.contact_range()
        if rng is not None:
            lengths.append(rng[1] - rng[0])
    if not neutral or not lengths:
        ax.text(0.5, 0.5, "no neutral point", ha="center", va="center",
                transform=ax.transAxes, color="0.4")
    half = 0.12 * max(lengths) if lengths else None
    ylo, yhi = [], []
    for i, (r, label) in enumerate(runs):
        x, vs = _col(r.contact, "x"), _col(r.contact, "v_slip")
        if x is None or vs is None:
            continue
        colour = f"C{i}" if len(runs) > 1 else "C0"
        ax.plot(x, vs, ".-", ms=4, color=colour, label=label)
        xn = r.neutral_x()
        if xn is not None:
            ax.plot([xn], [0.0], "o", mfc="none", color=colour, ms=8)
        if neutral and half is not None:
            sel = (x >= min(neutral) - half) & (x <= max(neutral) + half)
            if sel.any():
                ylo.append(np.nanmin(vs[sel]))
                yhi.append(np.nanmax(vs[sel]))
    ax.axhline(0.0, color="0.5", lw=0.8)
    if neutral and half is not None:
        ax.set_xlim(min(neutral) - half, max(neutral) + half)
        if ylo:
            lo, hi = min(ylo), max(yhi)
            pad = 0.1 * max(hi - lo, 1e-12)
            ax.set_ylim(lo - pad, hi + pad)
    ax.set_ylabel(r"$v_s$ [m/s]")
    ax.set_xlabel("x [m]")
    ax.grid(alpha=0.3)


def plot_compare(runs: Mapping[str, Path], out_png: Path, *, title: str = "") -> Path:
    """Overlay contact profiles and top-boundary velocities of several runs.

    Panels: (a) v_slip, (b) v_slip around the neutral points, (c) normal
    contact stress (exit-corrected where available), (d) tangential stress,
    (e) v1 and (f) v2 along the top boundary.  Labels are the dict keys.
    """
    loaded = [(_Run(Path(d)), str(label)) for label, d in runs.items()]
    fig, axes = plt.subplots(3, 2, figsize=(12, 11), layout="constrained")
    (a_vs, a_zoom), (a_sn, a_st), (a_v1, a_v2) = axes

    for i, (r, label) in enumerate(loaded):
        colour = f"C{i}"
        c = r.contact
        x = _col(c, "x")
        if x is not None:
            vs = _col(c, "v_slip")
            if vs is not None:
                a_vs.plot(x, vs, ".-", ms=3, color=colour, label=label)
            sn = _col(c, "normal_stress_corrected")
            if sn is None:
                sn = _col(c, "normal_stress")
            if sn is not None:
                a_sn.plot(x, sn, ".-", ms=3, color=colour, label=label)
            st = _col(c, "shear_stress")
            if st is not None:
                a_st.plot(x, st, ".-", ms=3, color=colour, label=label)
            xn = r.neutral_x()
            for ax in (a_vs, a_sn, a_st):
                _vline(ax, xn, None, color=colour, ls=":", lw=0.9)
        t = r.top
        xt = _col(t, "x")
        if xt is not None:
            for ax, key in ((a_v1, "v1"), (a_v2, "v2")):
                y = _col(t, key)
                if y is not None:
                    ax.plot(xt, y, "-", lw=1.3, color=colour, label=label)
            rng = r.contact_range()
            if rng is not None:
                for ax in (a_v1, a_v2):
                    _vline(ax, rng[0], None, color=colour, ls="--", lw=0.8)
                    _vline(ax, rng[1], None, color=colour, ls="-.", lw=0.8)

    _zoom_slip(a_zoom, loaded)
    a_vs.axhline(0.0, color="0.5", lw=0.8)
    a_st.axhline(0.0, color="0.5", lw=0.8)
    panels = (
        (a_vs, r"(a) relative velocity $v_s$", r"$v_s$ [m/s]"),
        (a_zoom, r"(b) $v_s$ around the neutral points", r"$v_s$ [m/s]"),
        (a_sn, r"(c) normal stress $T_n\cdot n$ [Pa]", "[Pa]"),
        (a_st, r"(d) tangential stress $T_\tau\cdot n_\tau$ [Pa]", "[Pa]"),
        (a_v1, r"(e) $v_1$ along the top boundary (-- entry, -. exit)", r"$v_1$ [m/s]"),
        (a_v2, r"(f) $v_2$ along the top boundary", r"$v_2$ [m/s]"),
    )
    for ax, ttl, ylab in panels:
        ax.set_title(ttl)
        ax.set_xlabel("x [m]")
        ax.set_ylabel(ylab)
        ax.grid(alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
    if title:
        fig.suptitle(title)
    return _save(fig, out_png)
