"""Several runs overlaid: contact profiles and top-boundary velocities."""
from __future__ import annotations

from pathlib import Path
from typing import Mapping

import matplotlib.pyplot as plt

from hotroll.results.figures.draw import draw_neutral, draw_vline, save_figure
from hotroll.results.figures.profiles import zoom_slip
from hotroll.results.figures.run_files import RunFiles, column


def plot_compare(runs: Mapping[str, Path], out_png: Path, *, title: str = "") -> Path:
    """Overlay contact profiles and top-boundary velocities of several runs.

    Panels: (a) v_slip, (b) v_slip around the neutral points, (c) contact
    pressure (compressive positive; exit-corrected where available), (d) tangential stress,
    (e) v1 and (f) v2 along the top boundary.  Labels are the dict keys.
    """
    loaded = [(RunFiles(Path(d)), str(label)) for label, d in runs.items()]
    fig, axes = plt.subplots(3, 2, figsize=(12, 11), layout="constrained")
    (a_vs, a_zoom), (a_sn, a_st), (a_v1, a_v2) = axes

    for i, (r, label) in enumerate(loaded):
        colour = f"C{i}"
        c = r.contact
        x = column(c, "x")
        if x is not None:
            vs = column(c, "v_slip")
            if vs is not None:
                a_vs.plot(x, vs, ".-", ms=3, color=colour, label=label)
            sn = column(c, "normal_stress_corrected")
            if sn is None:
                sn = column(c, "normal_stress")
            if sn is not None:         # the contact pressure, compressive positive
                a_sn.plot(x, -sn, ".-", ms=3, color=colour, label=label)
            st = column(c, "shear_stress")
            if st is not None:
                a_st.plot(x, st, ".-", ms=3, color=colour, label=label)
            # each run's neutral point, or its sticking zone, as its summary tells it
            marks = [(kind, pos, f"{label}: {text}") for kind, pos, text in r.neutral().marks("x")]
            for ax in (a_vs, a_sn, a_st):
                draw_neutral(ax, marks if ax is a_vs else [(k, p, None) for k, p, _ in marks],
                             color=colour)
        t = r.top
        xt = column(t, "x")
        if xt is not None:
            for ax, key in ((a_v1, "v1"), (a_v2, "v2")):
                y = column(t, key)
                if y is not None:
                    ax.plot(xt, y, "-", lw=1.3, color=colour, label=label)
            rng = r.contact_range()
            if rng is not None:
                for ax in (a_v1, a_v2):
                    draw_vline(ax, rng[0], None, color=colour, ls="--", lw=0.8)
                    draw_vline(ax, rng[1], None, color=colour, ls="-.", lw=0.8)

    zoom_slip(a_zoom, loaded)
    a_vs.axhline(0.0, color="0.5", lw=0.8)
    a_st.axhline(0.0, color="0.5", lw=0.8)
    panels = (
        (a_vs, r"(a) relative velocity $v_s$", r"$v_s$ [m/s]"),
        (a_zoom, r"(b) $v_s$ around the neutral points", r"$v_s$ [m/s]"),
        (a_sn, r"(c) contact pressure $p = -T_n\cdot n$ (compressive > 0) [Pa]", "[Pa]"),
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
    return save_figure(fig, out_png)
