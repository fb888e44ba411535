"""The outlet's state through the thickness (``exit_profile.csv``): the temperature, the strain
and, for an asymmetric pass, the through-thickness shear strain gamma_xy, against eta = y over
the half exit thickness (0 the centre line and 1 the surface; an asymmetric pass's from -1,
the lower surface, to 1)."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from hotroll.results.figures.draw import run_title, save_figure
from hotroll.results.figures.run_files import RunFiles, column

#: (column, axis label) of each panel, in this order, where the file has the column's values
PANELS = (("temperature", "temperature [K]"), ("strain", "equivalent strain [-]"),
          ("pass_strain", "pass strain along the streamline [-]"),
          ("shear_strain", "shear strain gamma_xy [-]"))


def fig_exit_profile(run: RunFiles, path: Path) -> Path | None:
    """One panel per quantity the outlet's profile holds (``PANELS``), each against eta; None
    without ``exit_profile.csv`` or with none of them."""
    table = run.dir_table("exit_profile.csv")
    eta = column(table, "eta")
    if eta is None:
        return None
    panels = [(key, label, column(table, key)) for key, label in PANELS]
    panels = [(k, lab, v) for k, lab, v in panels if v is not None and np.any(np.isfinite(v))]
    if not panels:
        return None
    fig, axes = plt.subplots(1, len(panels), figsize=(3.2 * len(panels) + 1.0, 4.2),
                             sharey=True, squeeze=False)
    for ax, (_, label, values) in zip(axes[0], panels):
        ax.plot(values, eta, ".-", ms=3, color="tab:blue")
        ax.set_xlabel(label)
        ax.grid(alpha=0.3)
    full = float(np.min(eta)) < 0.0
    axes[0][0].set_ylabel("eta [-]: " + ("-1 lower, 1 upper surface" if full
                                         else "0 centre, 1 surface"))
    fig.suptitle(run_title(run, "the outlet through the thickness (exit_profile.csv)"))
    fig.tight_layout()
    return save_figure(fig, path)
