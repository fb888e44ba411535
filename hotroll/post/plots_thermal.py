"""The temperature figure of a coupled run (issue 16), from its output files only.

``fig_temperature.png``: the temperature field over the strip and zoomed on the roll bite
(thermal.npz: the field on its own strip mesh, graded to the roll-chill layer; fields.npz's
vertex values if it is missing), and the surface temperature along the top with the heat flux to the roll along
the contact (top.csv, contact.csv), the exit mean and surface temperatures of summary.json
marked. Written by ``plots.plot_all`` when the run has a ``[thermal]`` section.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from matplotlib.tri import Triangulation

from .plots import (_Run, _col, _draw_contact_edges, _draw_outline, _draw_roll, _full_extent,
                    _na, _save, _set_window, _title, _vline, _window_range, plt)


def _fig_temperature(run: _Run, path: Path) -> Path | None:
    if not run.summary.get("thermal"):
        return None
    tri, T = _temperature_field(run)
    if tri is None:
        return None
    full, window = _full_extent(tri), run.bite_window()
    fig, axes = plt.subplots(3, 1, figsize=(10, 11), layout="constrained")
    for ax, win in ((axes[0], None), (axes[1], window)):
        lo, hi = _window_range(tri, T, win)
        tp = ax.tripcolor(tri, T, shading="gouraud", cmap="inferno", vmin=lo, vmax=hi)
        fig.colorbar(tp, ax=ax, label="T [K]", shrink=0.9)
        _draw_outline(ax, tri)
        _draw_roll(ax, run, (full[0], full[1]))
        _draw_contact_edges(ax, run, lw=1.0)
        _set_window(ax, win, full=full)
    axes[1].set_aspect("auto")      # y stretched: the chilled layer is thin against the bite
    axes[0].set_title(_title(run, "temperature [K]"))
    axes[1].set_title("zoom on the roll bite (y stretched), temperature [K]")
    _surface_panel(axes[2], run)
    return _save(fig, path)


def _temperature_field(run: _Run):
    """(Triangulation, vertex temperatures) of thermal.npz, else of fields.npz, else None."""
    path = run.dir / "thermal.npz"
    if path.is_file():
        with np.load(path) as f:
            p, t, T = (np.asarray(f[k]) for k in ("points", "triangles", "temperature"))
        return Triangulation(p[:, 0], p[:, 1], t), T.astype(float)
    tri = run.triangulation()
    if tri is None or "temperature" not in run.fields:
        return None, None
    return tri, np.asarray(run.fields["temperature"], dtype=float)


def _surface_panel(ax, run: _Run) -> None:
    x, T = _col(run.top, "x"), _col(run.top, "temperature")
    if x is None or T is None:
        _na(ax, "top.csv has no temperature")
        return
    s = run.summary
    ax.plot(x, T, "-", color="tab:red", lw=1.2, label="surface temperature (top.csv)")
    for key, label, style in (("exit_temperature_mean", "exit mean (mixing cup)", "--"),
                              ("exit_temperature_surface", "exit surface", ":")):
        if s.get(key) is not None:
            ax.axhline(s[key], color="0.3", ls=style, lw=1.0, label=f"{label} {s[key]:.1f} K")
    rng = run.contact_range()
    if rng is not None:
        ax.axvspan(rng[0], rng[1], color="tab:orange", alpha=0.12, label="contact")
        _vline(ax, rng[1], "contact exit", color="tab:red")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("T [K]")
    ax.grid(alpha=0.3)
    xc, q = _col(run.contact, "x"), _col(run.contact, "heat_flux_to_roll")
    if xc is not None and q is not None and len(xc):
        ax2 = ax.twinx()
        ax2.plot(xc, q / 1e6, ".", ms=3, color="tab:blue", label="heat flux to the roll")
        ax2.set_ylabel("heat flux to the roll [MW/m$^2$]", color="tab:blue")
        ax2.legend(fontsize=8, loc="lower right")
    ax.legend(fontsize=8, loc="lower left")
    ax.set_title("along the top surface: temperature [K] and heat flux to the roll [MW/m$^2$]")


FIGURES = (("fig_temperature.png", _fig_temperature),)
