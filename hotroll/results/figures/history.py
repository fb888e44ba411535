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
    ("neutral_angle", "neutral angle [rad]", False),
    ("iterations", "iterations per step", False),
)


def fig_history(run: RunFiles, path: Path) -> Path | None:
    h = run.history
    if h is None:
        return None
    t = column(h, "time")
    xlabel, title = "time [s]", "time history"
    steady = t is None or not np.isfinite(t).any()
    if steady:   # the steady solver: one row per a_f / free-surface update and per Newton solve
        t = column(h, "step")
        xlabel, title = "a_f / free-surface update", "steady solver history"
    if t is None:
        return None
    fig, axes = plt.subplots(2, 3, figsize=(13, 7), sharex=True, layout="constrained")
    for ax, (key, label, logy) in zip(axes.ravel(), _HISTORY_PANELS):
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
