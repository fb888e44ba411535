"""A study's figure drawn from its table (``[plot]`` of the study file): one panel per summary
field against a column, one line per value of a varied key; the done rows only."""
from __future__ import annotations

import math
from pathlib import Path

from hotroll.config.study import PlotConfig, key_unit
from hotroll.files import atomic
from hotroll.results.figures import plot_compare


def _num(v) -> float:
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def plot_table(rows: list[dict], plot: PlotConfig, out_png: Path, *, units: dict | None = None,
               title: str = "") -> Path | None:
    """``out_png`` from the rows (a study table); None when no row is done. A varied key whose
    values are names (a Table 2 mesh) is plotted against the summary's h_contact instead;
    other names (a friction law) are categories in the order of the table. A column the
    table does not have is a ValueError naming it."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    units = units or {}
    done = [r for r in rows if r.get("status") == "done"]
    if not done:
        return None
    x = plot.x
    if x == "mesh.h_contact" and any(isinstance(r.get(x), str) for r in done):
        x = "h_contact"
    have = {k for r in rows for k in r}
    missing = [k for k in [x, *plot.y] if k not in have]
    if missing:
        raise ValueError(f"plot: {', '.join(missing)} not a column of the table")
    names = list(dict.fromkeys(r.get(x) for r in done if not math.isfinite(_num(r.get(x)))))
    if names:                             # categories: their position, their name as tick
        pos = {v: i for i, v in enumerate(dict.fromkeys(r.get(x) for r in done))}
        done = [{**r, x: pos[r.get(x)]} for r in done]
    groups: dict = {}
    for r in done:
        groups.setdefault(r.get(plot.lines) if plot.lines else None, []).append(r)
    n = len(plot.y)
    fig, axes = plt.subplots(n, 1, figsize=(7, 2.5 * n + 0.8), sharex=True, squeeze=False,
                             layout="constrained")
    for ax, key in zip(axes[:, 0], plot.y):
        for value, grp in sorted(groups.items(), key=lambda kv: _num(kv[0])):
            pts = sorted((_num(r.get(x)), _num(r.get(key))) for r in grp)
            pts = [p for p in pts if math.isfinite(p[0]) and math.isfinite(p[1])]
            if not pts:
                continue
            xs, ys = zip(*pts)
            unit = key_unit(plot.lines) if plot.lines else "-"
            label = None if value is None else f"{plot.lines} = {value:.4g}" + (
                f" {unit}" if unit != "-" else "") if isinstance(value, (int, float)) \
                and not isinstance(value, bool) else f"{plot.lines} = {value}"
            ax.plot(xs, ys, "o-", ms=4, label=label)
        ax.set_ylabel(f"{key} [{units.get(key, '-')}]")
        ax.grid(alpha=0.3, which="both")
        if plot.xscale == "log":
            ax.set_xscale("log")
        if plot.lines and ax is axes[0, 0]:
            ax.legend(fontsize=8)
    if names:
        axes[-1, 0].set_xticks(list(pos.values()), [str(v) for v in pos])
    axes[-1, 0].set_xlabel(f"{x} [{units[x] if x in units else key_unit(x)}]")
    if title:
        fig.suptitle(title)
    out_png = Path(out_png)
    try:
        with atomic(out_png) as tmp:
            fig.savefig(tmp, dpi=120)
    finally:
        plt.close(fig)
    return out_png


def plot_profiles(rows: list[dict], out: Path, out_png: Path, *, title: str = "") -> Path | None:
    """The contact profiles of the done cases overlaid (``post.plots.plot_compare``)."""
    runs = {str(r["case"]): Path(out) / "cases" / str(r["case"]) for r in rows
            if r.get("status") == "done"}
    return plot_compare(runs, out_png, title=title) if runs else None
