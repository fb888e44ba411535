"""Field figures: the mesh, the flow stress and the velocity over the strip."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.tri import LinearTriInterpolator

from hotroll.results.figures.draw import (
    contourf,
    draw_contact_edges,
    draw_outline,
    draw_roll,
    full_extent,
    run_title,
    save_figure,
    set_window,
    window_range,
)
from hotroll.results.figures.run_files import RunFiles

# ---------------------------------------------------------------------------
# single-run figures
# ---------------------------------------------------------------------------

def fig_mesh(run: RunFiles, path: Path) -> Path | None:
    tri = run.triangulation()
    if tri is None:
        return None
    full = full_extent(tri)
    window = run.bite_window()
    fig, axes = plt.subplots(2, 1, figsize=(10, 8), layout="constrained")
    for ax, win, lw in ((axes[0], None, 0.25), (axes[1], window, 0.5)):
        ax.triplot(tri, color="tab:blue", lw=lw)
        draw_roll(ax, run, (full[0], full[1]))
        draw_contact_edges(ax, run, lw=1.5 if win is None else 2.5)
        set_window(ax, win, full=full)
    axes[0].set_title(run_title(run, "deformed mesh"))
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
    return save_figure(fig, path)


def fig_sigma_ef(run: RunFiles, path: Path) -> Path | None:
    tri = run.triangulation()
    if tri is None or "sigma_ef" not in run.fields:
        return None
    sig = np.asarray(run.fields["sigma_ef"], dtype=float)
    full = full_extent(tri)
    window = run.bite_window()
    fig, axes = plt.subplots(2, 1, figsize=(10, 8), layout="constrained")
    for ax, win in ((axes[0], None), (axes[1], window)):
        lo, hi = window_range(tri, sig, win)
        tp = ax.tripcolor(tri, sig, shading="gouraud", cmap="jet", vmin=lo, vmax=hi)
        fig.colorbar(tp, ax=ax, label=r"$\sigma_{ef}$ [Pa]", shrink=0.9)
        draw_outline(ax, tri)
        draw_roll(ax, run, (full[0], full[1]))
        draw_contact_edges(ax, run, lw=1.0)
        set_window(ax, win, full=full)
    axes[0].set_title(run_title(run, r"effective stress $\sigma_{ef}$ [Pa]"))
    axes[1].set_title(r"zoom on the roll bite, $\sigma_{ef}$ [Pa]")
    return save_figure(fig, path)


def fig_velocity(run: RunFiles, path: Path) -> Path | None:
    tri = run.triangulation()
    if tri is None or "v" not in run.fields:
        return None
    v = np.asarray(run.fields["v"], dtype=float).reshape(-1, 2)
    full = full_extent(tri)
    window = run.bite_window()
    fig, axes = plt.subplots(3, 1, figsize=(9, 10), layout="constrained")
    contourf(axes[0], tri, v[:, 0], window, r"$v_1$ [m/s]")
    axes[0].set_title(run_title(run, r"velocity $v_1$ [m/s] near the roll bite"))
    contourf(axes[1], tri, v[:, 1], window, r"$v_2$ [m/s]", cmap="coolwarm",
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
        draw_outline(a, tri)
        draw_roll(a, run, (full[0], full[1]))
        draw_contact_edges(a, run, lw=1.0)
        set_window(a, window, full=full)
    return save_figure(fig, path)
