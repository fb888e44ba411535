"""The convergence history figure (history.csv)."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import MaxNLocator

from hotroll.results.figures.draw import not_available, run_title, save_figure
from hotroll.results.figures.run_files import RunFiles, column

_HISTORY_PANELS = (
    ("strain_rate_measure", "strain-rate measure", True),
    ("slip_measure", "slip measure", True),
    ("a_f", r"$a_f$", False),
    ("roll_force", "roll force [N/m]", False),
    ("neutral_angle", "neutral angle [°]", False),
    ("iterations", "iterations per step", False),
)


def fig_history(run: RunFiles, path: Path) -> Path | None:
    h = run.history
    if h is None:
        return None
    t = column(h, "time")
    xlabel, title = "time [s]", "time history"
    steady = t is None or not np.isfinite(t).any()
    if steady:   # the steady solver: one row per coupling update and per Newton solve
        t = column(h, "step")
        xlabel = "history row (coupling update or Newton solve)"
        title = "steady solver history: coupling updates and Newton solves, not time steps"
    if t is None:
        return None
    fig, axes = plt.subplots(2, 3, figsize=(13, 7), sharex=True, layout="constrained")
    for ax, (key, label, logy) in zip(axes.ravel(), _HISTORY_PANELS):
        if key == "neutral_angle":
            neutral_panel(ax, run, t, xlabel)
            continue
        y = column(h, key)
        if y is None or not np.isfinite(y).any():
            not_available(ax, f"{key} not available")
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
    fig.suptitle(run_title(run, title))
    return save_figure(fig, path)


def neutral_history(run: RunFiles) -> tuple[str, np.ndarray | None, float | None]:
    """The history's neutral panel: (its title, each row's neutral angle in degrees or None,
    the summary's in degrees or None). The title is the summary's story
    (``RunFiles.neutral``); where it has no neutral point the rows' splits of the slip's
    signs are not drawn (in a sticking zone they are noise, not a neutral point)."""
    neutral = run.neutral()
    if neutral.kind != "point":
        return neutral.label, None, None
    y = column(run.history, "neutral_angle")
    rows = None if y is None or not np.isfinite(y).any() else np.degrees(y)
    return neutral.label, rows, neutral.angle_deg


def neutral_panel(ax, run: RunFiles, t, xlabel: str) -> None:
    """The neutral angle of each row and the summary's, or the summary's story alone."""
    title, rows, final = neutral_history(run)
    ax.set_title(title, fontsize=8, wrap=True)
    if rows is None:         # the text alone (not_available would clear the shared x ticks)
        ax.text(0.5, 0.5, title.replace(": none: ", ":\nnone: ").replace(" from ", "\nfrom "),
                ha="center", va="center", transform=ax.transAxes, color="0.4")
        ax.set_yticks([])
        ax.set_xlabel(xlabel)
        return
    ax.plot(t, rows, ".-", ms=3, label="each row")
    ax.axhline(final, color="k", ls=":", lw=1.2, label="the summary's")   # = the last row
    ax.set_ylabel("neutral angle [°]")
    ax.set_xlabel(xlabel)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
