"""The flattened work roll (issue 32): how far its surface lies below the rigid roll through
the same gap, and the tractions that flatten it, along the contact (``contact.csv``'s
``roll_offset`` marks a flattening roll; no figure for a rigid one)."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from hotroll.results.figures.draw import run_title, save_figure
from hotroll.results.figures.run_files import RunFiles, column


def fig_roll(run: RunFiles, path: Path) -> Path | None:
    c, s = run.contact, run.summary
    x, y, off = column(c, "x"), column(c, "y"), column(c, "roll_offset")
    gap, R = s.get("contact_end"), s.get("roll_radius")
    if x is None or y is None or off is None or gap is None or R is None:
        return None
    order = np.argsort(x)
    x, y = x[order], y[order]
    xg, yg = float(gap[0]), float(gap[1])
    rigid = yg + R - np.sqrt(np.maximum(R**2 - (x - xg) ** 2, 0.0))
    fig, (a_d, a_t) = plt.subplots(2, 1, figsize=(8, 7), sharex=True, layout="constrained")
    a_d.plot(x, 1e6 * (rigid - y), ".-", ms=3, label="flattened surface (the strip's top)")
    a_d.axhline(0.0, color="0.5", lw=0.8, label="rigid roll through the same gap")
    flat = s.get("roll_flattening")
    req = s.get("roll_equivalent_radius")
    title = f"roll flattening ({s.get('roll_model', '?')})"
    if flat is not None and req is not None:
        title += f": largest {1e6 * flat:.3g} um, R_eq/R = {req / R:.4f}"
    a_d.set_title(run_title(run, title))
    a_d.set_ylabel("below the rigid roll [um]")
    a_d.legend(fontsize=8)
    sn, st = column(c, "normal_stress"), column(c, "shear_stress")
    if sn is not None:
        a_t.plot(x, -1e-6 * sn[order], ".-", ms=3, label="pressure on the roll")
    if st is not None:
        a_t.plot(x, 1e-6 * st[order], ".-", ms=3, color="tab:green", label="shear")
    a_t.axhline(0.0, color="0.5", lw=0.8)
    a_t.set_ylabel("traction [MPa]")
    a_t.set_xlabel("x [m]")
    a_t.legend(fontsize=8)
    for ax in (a_d, a_t):
        ax.grid(alpha=0.3)
    return save_figure(fig, path)
