"""An asymmetric pass's two rolls (issue 52): each roll's contact pressure and shear stress
(MPa) against its angle, on one figure, from ``contact.csv`` (the upper roll) and
``contact_lower.csv`` (the lower, in its own frame: the angle from its own vertical centre
line, positive towards the entry, the stresses as the upper's would be). The neutral angles
of the summary's ``rolls`` marked; the cross-shear zone lies between them."""
from __future__ import annotations

import math
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from hotroll.results.figures.draw import run_title, save_figure
from hotroll.results.figures.run_files import RunFiles, column

SIDES = (("upper", "contact.csv", "C0"), ("lower", "contact_lower.csv", "C3"))


def fig_rolls(run: RunFiles, path: Path) -> Path | None:
    """Both rolls' pressure and shear (MPa) against the angle (degrees); None for a run with
    one roll (no ``contact_lower.csv``)."""
    tables = {side: run.dir_table(name) for side, name, _ in SIDES}
    if tables["lower"] is None or tables["upper"] is None:
        return None
    entries = {e.get("side"): e for e in (run.summary.get("rolls") or [])}
    fig, (ax_p, ax_t) = plt.subplots(2, 1, figsize=(7.5, 6.5), sharex=True)
    for side, _, colour in SIDES:
        t = tables[side]
        ang, p, tau = (column(t, k) for k in ("angle", "normal_stress", "shear_stress"))
        if ang is None or p is None or tau is None:
            continue
        deg = np.degrees(ang)
        speed = entries.get(side, {}).get("surface_speed")
        label = f"{side} roll" + (f" ({speed:.4g} m/s)" if speed else "")
        ax_p.plot(deg, -p / 1e6, ".-", ms=3, color=colour, label=label)
        ax_t.plot(deg, tau / 1e6, ".-", ms=3, color=colour, label=label)
        neutral = entries.get(side, {}).get("neutral_angle")
        if isinstance(neutral, (int, float)) and math.isfinite(neutral):
            for ax in (ax_p, ax_t):
                ax.axvline(math.degrees(neutral), color=colour, ls="--", lw=0.8)
    ax_t.axhline(0.0, color="0.5", lw=0.8)
    ax_p.set_ylabel("contact pressure (MPa)")
    ax_t.set_ylabel("shear stress (MPa)")
    ax_t.set_xlabel("angle from the roll's vertical centre line (degrees; entry on the left)")
    ax_t.invert_xaxis()
    ax_p.legend(loc="best", fontsize=8)
    ax_p.set_title(run_title(run, "both rolls' contact (dashed: neutral angles)"))
    fig.tight_layout()
    return save_figure(fig, path)
