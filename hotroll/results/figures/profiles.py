"""Contact and top-boundary figures: profiles along x, over the roll angle, the slip
around the neutral point."""
from __future__ import annotations

from pathlib import Path
from typing import Sequence

import matplotlib.pyplot as plt
import numpy as np

from hotroll.results.figures.draw import (
    draw_neutral,
    draw_vline,
    not_available,
    run_title,
    save_figure,
    stress_unit,
)
from hotroll.results.figures.run_files import RunFiles, column
from hotroll.results.figures.slab import plot_compare_profiles


def profile_panel(ax, x, y, ylabel: str, title: str, what: str, **style) -> None:
    """One contact profile against x with its zero line, or a 'not available' panel."""
    if y is None:
        not_available(ax, f"{what} not available")
        return
    ax.plot(x, y, ".-", ms=3, **style)
    ax.axhline(0.0, color="0.5", lw=0.8)
    ax.set_ylabel(ylabel)
    ax.set_title(title)


def fig_contact(run: RunFiles, path: Path) -> Path | None:
    """Slip, contact pressure (compressive positive, as every figure draws it) and shear
    along x, and the slip around the neutral point; the neutral story of the summary on every
    panel (``RunFiles.neutral``)."""
    c = run.contact
    x = column(c, "x")
    if x is None:
        return None
    neutral = run.neutral()
    marks = neutral.marks("x")
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), layout="constrained")
    (a_vs, a_sn), (a_st, a_zoom) = axes

    vs = column(c, "v_slip")
    profile_panel(a_vs, x, vs, r"$v_s$ [m/s]", r"relative (slip) velocity $v_s$", "v_slip")

    sn, snc = column(c, "normal_stress"), column(c, "normal_stress_corrected")
    sns = column(c, "normal_stress_smooth")
    exact = run.summary.get("contact_method") == "multiplier"
    if exact:        # the multiplier's nodal forces over their lengths: no projection or correction
        sns = snc = None
    if sn is not None or snc is not None:
        # the contact pressure p = -T_n.n (compressive positive), as fig_contact_angle
        f, unit = stress_unit(sn, sns, snc)
        if sn is not None:
            a_sn.plot(x, -sn / f, ".-" if exact else ".", ms=2.5, color="C0" if exact else "0.6",
                      label="contact pressure (the multiplier's nodal forces / lengths)"
                      if exact
                      else "raw (nodal penalty reaction)")
        if sns is not None:
            a_sn.plot(x, -sns / f, "-", lw=1.5, color="C0", label="P1 projection")
        if snc is not None:
            a_sn.plot(x, -snc / f, "--", lw=1.2, color="C1", label="exit-corrected (raw)")
        a_sn.axhline(0.0, color="0.5", lw=0.8)
        a_sn.set_ylabel(f"$p = -T_n\\cdot n$ [{unit}]")
        a_sn.set_title(f"contact pressure p (compressive > 0) [{unit}]")
        a_sn.legend(fontsize=8)
    else:
        not_available(a_sn, "normal stress not available")

    st, sts = column(c, "shear_stress"), column(c, "shear_stress_smooth")
    f, unit = stress_unit(st, sts)
    ylabel = f"$T_\\tau\\cdot n_\\tau$ [{unit}]"
    title = f"shear stress on the strip (> 0: the roll drags it forward) [{unit}]"
    if sts is not None:
        a_st.plot(x, st / f, ".", ms=2.5, color="0.6", label="raw (friction law at the nodes)")
        profile_panel(a_st, x, sts / f, ylabel, title, "shear stress",
                      color="tab:green", label="P1 projection")
        a_st.legend(fontsize=8)
    else:
        profile_panel(a_st, x, None if st is None else st / f, ylabel, title, "shear stress",
                      color="tab:green")

    if vs is not None:
        zoom_slip(a_zoom, [(run, None)])
        a_zoom.set_title(r"$v_s$ around the neutral point" if neutral.kind == "point"
                         else r"$v_s$ along the contact (no neutral point)")
    else:
        not_available(a_zoom)

    for ax in (a_vs, a_sn, a_st, a_zoom):
        ax.set_xlabel("x [m]")
        ax.grid(alpha=0.3)
        draw_neutral(ax, marks)
    a_vs.legend(fontsize=7, loc="lower right")
    extra = [neutral.label]
    fs = run.summary.get("forward_slip")
    if fs is not None and np.isfinite(fs):
        extra.append(f"forward slip {100 * fs:.3g} %")
    fig.suptitle(run_title(run, "contact profiles") + "\n" + ", ".join(extra))
    return save_figure(fig, path)


def fig_top(run: RunFiles, path: Path) -> Path | None:
    t = run.top
    x = column(t, "x")
    if x is None:
        return None
    rng = run.contact_range()
    marks = run.neutral().marks("x")
    fig, axes = plt.subplots(2, 1, figsize=(9, 7), sharex=True, layout="constrained")
    for ax, key, lab in ((axes[0], "v1", r"$v_1$ [m/s]"), (axes[1], "v2", r"$v_2$ [m/s]")):
        y = column(t, key)
        if y is None:
            not_available(ax, f"{key} not available")
            continue
        ax.plot(x, y, ".-", ms=3, label=key)
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
        if rng is not None:
            ax.axvspan(rng[0], rng[1], color="tab:orange", alpha=0.12, label="contact")
            draw_vline(ax, rng[0], "first touching point", color="tab:orange")
            draw_vline(ax, rng[1], "contact exit", color="tab:red")
        draw_neutral(ax, marks)
    vr = run.summary.get("roll_surface_speed")
    if vr is not None and np.isfinite(vr) and column(t, "v1") is not None:
        axes[0].axhline(vr, color="0.4", lw=1.0, ls="-.", label="roll surface speed")
    axes[0].legend(fontsize=8, loc="best")
    axes[0].set_title(run_title(run, "velocity along the top boundary"))
    axes[1].set_xlabel("x [m]")
    return save_figure(fig, path)


# ---------------------------------------------------------------------------
# public API
# ---------------------------------------------------------------------------

def fig_contact_angle(run: RunFiles, path: Path) -> Path | None:
    """Pressure and shear (MPa) over the roll angle: P1 projection, raw nodal values as dots,
    the axes fitted to the projection (off-scale raw values marked at the edge)."""
    if run.contact is None or column(run.contact, "angle") is None:
        return None
    return plot_compare_profiles(run.contact, None, run.summary, path, fe_only=True,
                                 title=run_title(run, "contact pressure and shear"))




def zoom_slip(ax, runs: Sequence[tuple[RunFiles, str | None]]) -> None:
    """v_slip vs x restricted to a window around the neutral point(s)."""
    neutral = [r.neutral_x() for r, _ in runs]
    neutral = [x for x in neutral if x is not None]
    lengths = []
    for r, _ in runs:
        rng = r.contact_range()
        if rng is not None:
            lengths.append(rng[1] - rng[0])
    if (not neutral or not lengths) and len(runs) > 1:   # one run: its title says why
        ax.text(0.5, 0.5, "no neutral point", ha="center", va="center",
                transform=ax.transAxes, color="0.4")
    half = 0.12 * max(lengths) if lengths else None
    ylo, yhi = [], []
    for i, (r, label) in enumerate(runs):
        x, vs = column(r.contact, "x"), column(r.contact, "v_slip")
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
