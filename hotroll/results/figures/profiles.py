"""Contact and top-boundary figures: profiles along x, over the roll angle, the slip
around the neutral point."""
from __future__ import annotations

import math
from pathlib import Path
from typing import Sequence

import matplotlib.pyplot as plt
import numpy as np

from hotroll.results.figures.draw import draw_vline, not_available, run_title, save_figure
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
    c = run.contact
    x = column(c, "x")
    if x is None:
        return None
    xn = run.neutral_x()
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
        if sn is not None:
            a_sn.plot(x, sn, ".-" if exact else ".", ms=2.5, color="C0" if exact else "0.6",
                      label="contact pressure (the multiplier's nodal forces / lengths)"
                      if exact
                      else "raw (nodal penalty reaction)")
        if sns is not None:
            a_sn.plot(x, sns, "-", lw=1.5, color="C0", label="P1 projection")
        if snc is not None:
            a_sn.plot(x, snc, "--", lw=1.2, color="C1", label="exit-corrected (raw)")
        a_sn.set_ylabel(r"$T_n\cdot n$ [Pa]")
        a_sn.set_title(r"normal contact stress $T_n\cdot n$ [Pa]")
        a_sn.legend(fontsize=8)
    else:
        not_available(a_sn, "normal stress not available")

    st, sts = column(c, "shear_stress"), column(c, "shear_stress_smooth")
    if sts is not None:
        a_st.plot(x, st, ".", ms=2.5, color="0.6", label="raw (friction law at the nodes)")
        profile_panel(a_st, x, sts, r"$T_\tau\cdot n_\tau$ [Pa]",
                       r"tangential stress $T_\tau\cdot n_\tau$ [Pa]", "shear stress",
                       color="tab:green", label="P1 projection")
        a_st.legend(fontsize=8)
    else:
        profile_panel(a_st, x, st, r"$T_\tau\cdot n_\tau$ [Pa]",
                       r"tangential stress $T_\tau\cdot n_\tau$ [Pa]", "shear stress",
                       color="tab:green")

    if vs is not None:
        zoom_slip(a_zoom, [(run, None)])
        a_zoom.set_title(r"$v_s$ around the neutral point")
    else:
        not_available(a_zoom)

    for ax in (a_vs, a_sn, a_st, a_zoom):
        ax.set_xlabel("x [m]")
        ax.grid(alpha=0.3)
        draw_vline(ax, xn, "neutral point")
    a_vs.legend(fontsize=8)
    extra = []
    ang = run.summary.get("neutral_angle")
    if ang is not None and np.isfinite(ang):
        extra.append(f"neutral angle {math.degrees(ang):.3g}°")
    fs = run.summary.get("forward_slip")
    if fs is not None and np.isfinite(fs):
        extra.append(f"forward slip {fs:.3g}")
    fig.suptitle(run_title(run, "contact profiles") + (" (" + ", ".join(extra) + ")"
                                                      if extra else ""))
    return save_figure(fig, path)


def fig_top(run: RunFiles, path: Path) -> Path | None:
    t = run.top
    x = column(t, "x")
    if x is None:
        return None
    rng = run.contact_range()
    xn = run.neutral_x()
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
        draw_vline(ax, xn, "neutral point", color="k", ls=":")
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
    if not neutral or not lengths:
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
