"""The temperature figure of a coupled run (thermal.npz, or fields.npz's vertex values),
the surface temperature and the heat flux to the roll along the top; an asymmetric pass's
lower surface and its roll's heat flux beside them (top_lower.csv, contact_lower.csv)."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.tri import Triangulation

from hotroll.results.figures.draw import (
    draw_contact_edges,
    draw_outline,
    draw_roll,
    draw_vline,
    full_extent,
    not_available,
    run_title,
    save_figure,
    set_window,
    window_range,
)
from hotroll.results.figures.run_files import RunFiles, column


def fig_temperature(run: RunFiles, path: Path) -> Path | None:
    if not run.summary.get("thermal"):
        return None
    tri, T = _temperature_field(run)
    if tri is None:
        return None
    full, window = full_extent(tri), run.bite_window()
    fig, axes = plt.subplots(3, 1, figsize=(10, 11), layout="constrained")
    for ax, win in ((axes[0], None), (axes[1], window)):
        lo, hi = window_range(tri, T, win)
        tp = ax.tripcolor(tri, T, shading="gouraud", cmap="inferno", vmin=lo, vmax=hi)
        fig.colorbar(tp, ax=ax, label="T [K]", shrink=0.9)
        draw_outline(ax, tri)
        draw_roll(ax, run, (full[0], full[1]))
        draw_contact_edges(ax, run, lw=1.0)
        set_window(ax, win, full=full)
    axes[1].set_aspect("auto")      # y stretched: the chilled layer is thin against the bite
    axes[0].set_title(run_title(run, "temperature [K]"))
    axes[1].set_title("zoom on the roll bite (y stretched), temperature [K]")
    _surface_panel(axes[2], run)
    return save_figure(fig, path)


def _temperature_field(run: RunFiles):
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


def _surface_panel(ax, run: RunFiles) -> None:
    x, T = column(run.top, "x"), column(run.top, "temperature")
    if x is None or T is None:
        not_available(ax, "top.csv has no temperature")
        return
    s = run.summary
    lower = run.dir_table("top_lower.csv")
    two = lower is not None and column(lower, "temperature") is not None
    ax.plot(x, T, "-", color="tab:red", lw=1.2,
            label="upper surface (top.csv)" if two else "surface temperature (top.csv)")
    if two:
        ax.plot(column(lower, "x"), column(lower, "temperature"), "-", color="tab:purple",
                lw=1.2, label="lower surface (top_lower.csv)")
    for key, label, style in (("exit_temperature_mean", "exit mean (mixing cup)", "--"),
                              ("exit_temperature_surface",
                               "exit upper surface" if two else "exit surface", ":"),
                              ("exit_temperature_surface_lower", "exit lower surface", "-.")):
        if s.get(key) is not None:
            ax.axhline(s[key], color="0.3", ls=style, lw=1.0, label=f"{label} {s[key]:.1f} K")
    rng = run.contact_range()
    if rng is not None:
        ax.axvspan(rng[0], rng[1], color="tab:orange", alpha=0.12, label="contact")
        draw_vline(ax, rng[1], "contact exit", color="tab:red")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("T [K]")
    ax.grid(alpha=0.3)
    ax2 = None
    for table, label, color in ((run.contact, "heat flux to the upper roll" if two
                                 else "heat flux to the roll", "tab:blue"),
                                (run.dir_table("contact_lower.csv") if two else None,
                                 "heat flux to the lower roll", "tab:cyan")):
        xc, q = column(table, "x"), column(table, "heat_flux_to_roll")
        if xc is not None and q is not None and len(xc):
            ax2 = ax2 or ax.twinx()
            ax2.plot(xc, q / 1e6, ".", ms=3, color=color, label=label)
    if ax2 is not None:
        ax2.set_ylabel("heat flux to the roll [MW/m$^2$]", color="tab:blue")
        ax2.legend(fontsize=8, loc="lower right")
    ax.legend(fontsize=8, loc="lower left")
    ax.set_title("along the " + ("upper and lower surfaces" if two else "top surface")
                 + ": temperature [K] and heat flux to the roll [MW/m$^2$]")

