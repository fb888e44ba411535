"""The ``[spread]`` section's 3D pass (issue 53), from ``exit_section.csv``, ``width_along.csv``
and ``contact_map.npz``: the exit cross-section (the whole strip, mirrored from the quarter;
coloured by the entry temperature's difference from mid-width's where the pass carries one),
the half width along the bite at mid-thickness and on the surface, and the contact pressure
over the arc and the width."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from hotroll.results.figures.draw import run_title, save_figure
from hotroll.results.figures.run_files import RunFiles, column

MM = 1e3          # m -> mm on the axes
#: a section wider than this many thicknesses (its half width) is drawn at its edge only
WIDE = 4.0


def fig_spread(run: RunFiles, path: Path) -> Path | None:
    """Three panels: the exit cross-section against the stock's, the half width along x, the
    contact pressure map (angle x width); None without the 3D pass's files."""
    section, along = run.dir_table("exit_section.csv"), run.dir_table("width_along.csv")
    y, half = column(section, "y"), column(section, "half_width")
    if y is None or half is None:
        return None
    summary = run.summary or {}
    b0 = 0.5 * float(summary.get("width") or 2.0 * half.min())
    fig, axes = plt.subplots(1, 3, figsize=(15.0, 4.6))
    ax = axes[0]
    # the quarter's section mirrored about both symmetry planes: the whole exit section
    yy = np.concatenate([y, [y[-1] + 0.5 * (y[-1] - y[-2])]])
    bb = np.concatenate([half, [half[-1]]])
    xs = np.concatenate([bb, -bb[::-1], -bb, bb[::-1]]) * MM
    ys = np.concatenate([yy, yy[::-1], -yy, -yy[::-1]]) * MM
    ax.fill(xs, ys, color="tab:blue", alpha=0.3, label="exit section")
    off = summary.get("exit_temperature_offset")
    if off:            # the entry's difference from mid-width's, carried to the outlet
        e, zt, v = (np.asarray(off[k], dtype=float) for k in ("eta", "zeta", "values"))
        Y = np.repeat((e * yy[-1])[:, None], zt.size, axis=1)
        Z = np.interp(e * yy[-1], y, half)[:, None] * zt[None, :]
        from matplotlib.colors import CenteredNorm

        # colder edges blue, hotter red, mid-width's white (either sign: a heated edge too)
        half_range = max(float(np.nanmax(np.abs(v))) if np.any(np.isfinite(v)) else 0.0, 1e-9)
        norm = CenteredNorm(0.0, half_range)
        for sy in (-1.0, 1.0):
            for sz in (-1.0, 1.0):
                mesh = ax.pcolormesh(sz * Z * MM, sy * Y * MM, v, shading="gouraud",
                                     cmap="RdBu_r", norm=norm)
        fig.colorbar(mesh, ax=ax, label="T - T(mid-width), entry's carried [K]")
    for side in (-1.0, 1.0):
        ax.axvline(side * b0 * MM, color="k", ls="--", lw=1,
                   label="stock width" if side > 0 else None)
    ax.set_aspect("equal")
    ax.set_xlabel("z (width) [mm]")
    ax.set_ylabel("y (thickness) [mm]")
    title = f"exit section: spread {2.0 * (np.mean(half) - b0) * MM:.3g} mm"
    thick = 2.0 * float(yy[-1])
    if b0 > WIDE * thick:     # a plate: its edge, 3 thicknesses of it, at a readable scale
        ax.set_xlim((b0 - 3.0 * thick) * MM, (float(half.max()) + 0.5 * thick) * MM)
        title += " (the edge)"
    ax.set_title(title)
    ax.legend(fontsize=8, loc="lower left")
    ax = axes[1]
    x = column(along, "x")
    if x is not None:
        for key, style in (("centre", "-"), ("surface", "--")):
            v = column(along, key)
            if v is not None:
                ax.plot(x * MM, v * MM, style, label=f"half width, {key}")
        ax.axhline(b0 * MM, color="k", lw=0.8, ls=":", label="stock")
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("half width [mm]")
        ax.set_title("the width along the bite")
        ax.legend(fontsize=8)
    ax = axes[2]
    cmap = run.dir / "contact_map.npz"
    if cmap.exists():
        with np.load(cmap) as d:
            ang, z, p = np.degrees(d["angle"]), d["z"], d["pressure"]
        A = np.broadcast_to(ang, z.shape)
        pc = ax.pcolormesh(A, z * MM, p / 1e6, shading="gouraud", cmap="viridis")
        fig.colorbar(pc, ax=ax, label="contact pressure [MPa]")
        ax.invert_xaxis()                   # the entry (larger angle) on the left
        ax.set_xlabel("angle from the roll's centre line [deg]")
        ax.set_ylabel("z (from mid-width) [mm]")
        ax.set_title("contact pressure over the arc and the width")
    fig.suptitle(run_title(run, "3D pass with spread (exit_section.csv, width_along.csv, "
                                "contact_map.npz)"))
    fig.tight_layout()
    return save_figure(fig, path)
