"""Figure of ``hotroll compare``: contact pressure and shear along the arc, FE and slab theory.

x axis: roll angle in degrees from the roll's vertical centre line (0 = roll gap), drawn with
the entry on the left (the axis decreases to the right, in the rolling direction). Pressure is
the compressive normal stress (FE: -normal_stress) in Pa, kPa or MPa (by its magnitude); the
shear is the stress on the strip along the roll's direction of motion in the same unit (> 0
where the roll drags the strip forward, i.e. between the entry and the neutral point; the
slab's shear magnitude gets that sign). The FE run's neutral point, or its sticking zone where
no point is neutral, as its summary tells it (``results/neutral.py``).
"""
from __future__ import annotations

import math
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from hotroll.results.figures.draw import draw_neutral, save_figure, stress_unit
from hotroll.results.neutral import Neutral, angle_text


def _clip_limits(ax, curves, raw, pad=0.12):
    """y limits that hold the lines (``curves``); raw points outside are drawn at the edge
    with their value written next to them."""
    vals = np.concatenate([np.asarray(c, float) for c in curves if c is not None and len(c)])
    vals = vals[np.isfinite(vals)]
    if not len(vals):
        return
    lo, hi = min(vals.min(), 0.0), max(vals.max(), 0.0)
    span = hi - lo or 1.0
    lo, hi = lo - pad * span, hi + pad * span
    ax.set_ylim(lo, hi)
    if raw is None:
        return
    x, y = raw
    x0, x1 = ax.get_xlim()
    for xi, yi in zip(x, y):
        if yi > hi or yi < lo:
            edge = hi if yi > hi else lo
            ax.plot([xi], [edge], marker="^" if yi > hi else "v", color="0.35", ms=6,
                    clip_on=False, zorder=5)
            left_half = (xi - x0) / (x1 - x0) < 0.5          # in axis fraction (x1 < x0 allowed)
            ax.annotate(f"raw {yi:.3g} (off scale)", (xi, edge), textcoords="offset points",
                        xytext=(8 if left_half else -8, -12 if yi > hi else 5),
                        ha="left" if left_half else "right", fontsize=7, color="0.3")


def plot_compare_profiles(contact: dict | None, slab, summary: dict, out_png: Path, *,
                          title: str = "", fe_only: bool = False) -> Path:
    """Two panels (pressure, shear) against the roll angle; FE smoothed line, FE raw dots,
    slab line, neutral angles as vertical lines. ``contact``: columns of contact.csv
    (or None); ``slab``: a :class:`hotroll.theory.SlabResult` or None (``fe_only``: the FE
    profiles alone, the run's own figure ``fig_contact_angle.png``)."""
    fig, (ap, at) = plt.subplots(2, 1, figsize=(8.5, 8), sharex=True, layout="constrained")
    pcurves, tcurves, praw, traw = [], [], None, None
    has_fe = contact is not None and len(contact.get("angle", []))
    f, unit = stress_unit(*([contact["normal_stress"], contact["shear_stress"]] if has_fe else []),
                          *([slab.pressure] if slab is not None else []))
    if has_fe:
        deg = np.degrees(contact["angle"])
        p_raw = -contact["normal_stress"] / f
        p_s = -contact.get("normal_stress_smooth", contact["normal_stress"]) / f
        t_raw = contact["shear_stress"] / f
        t_s = contact.get("shear_stress_smooth", contact["shear_stress"]) / f
        ap.plot(deg, p_s, "-", color="C0", lw=1.8, label="FE, smoothed (P1 projection)")
        ap.plot(deg, p_raw, ".", color="0.45", ms=4, label="FE, raw nodal values")
        at.plot(deg, t_s, "-", color="C0", lw=1.8, label="FE, smoothed (P1 projection)")
        at.plot(deg, t_raw, ".", color="0.45", ms=4, label="FE, raw nodal values")
        pcurves.append(p_s)
        tcurves.append(t_s)
        praw, traw = (deg, p_raw), (deg, t_raw)
    if slab is not None:
        deg = np.degrees(slab.angle)
        sign = np.where(slab.angle > slab.neutral_angle, 1.0, -1.0)
        ap.plot(deg, slab.pressure / f, "--", color="C3", lw=1.8, label="slab (Orowan)")
        at.plot(deg, sign * slab.shear / f, "--", color="C3", lw=1.8, label="slab (Orowan)")
        pcurves.append(slab.pressure / f)
        tcurves.append(sign * slab.shear / f)
    elif not fe_only:
        ap.text(0.5, 0.95, "slab theory not solved (see compare.md)", transform=ap.transAxes,
                ha="center", va="top", color="C3")
    # the FE run's neutral story as its summary tells it (results/neutral.py)
    marks = [(kind, pos, f"FE {label}") for kind, pos, label in
             Neutral.from_summary(summary or {}).marks("angle")] if has_fe else []
    for ax in (ap, at):
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.grid(alpha=0.3)
        draw_neutral(ax, marks, color="C0")
        if slab is not None:
            ax.axvline(math.degrees(slab.neutral_angle), color="C3", lw=1.0, ls=":",
                       label=f"slab neutral angle {angle_text(slab.neutral_angle)}")
        ax.legend(fontsize=8, loc="best")
    ap.set_ylabel(f"contact pressure [{unit}]")
    ap.set_title("contact pressure (compressive normal stress)")
    at.set_ylabel(f"shear stress [{unit}]")
    at.set_title("shear stress on the strip (> 0: roll drags the strip forward)")
    at.set_xlabel("roll angle from the vertical centre line [deg]  (entry left, exit = 0 right)")
    lo, hi = at.get_xlim()
    at.set_xlim(max(lo, hi), min(lo, hi))     # entry (large angle) on the left
    ap.tick_params(labelbottom=True)
    _clip_limits(ap, pcurves, praw)
    _clip_limits(at, tcurves, traw)
    fig.suptitle(title)
    return save_figure(fig, out_png)
