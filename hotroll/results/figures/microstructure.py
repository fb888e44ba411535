"""The schedule's microstructure figure (issue 33): through the half thickness after each
transport, the fraction recrystallised, the grain size handed on and the retained strain;
per pass, the strain against the critical strain of dynamic recrystallisation."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from hotroll.files import atomic


def plot_microstructure(profiles: list[dict], path: Path) -> bool:
    """microstructure.png from schedule.json's ``profiles`` (their ``microstructure``
    records); False (no file) when the schedule ran without a model."""
    records = [(p["pass"], p["microstructure"]) for p in profiles if p.get("microstructure")]
    if not records:
        return False
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(2, 2, figsize=(11, 7.5), constrained_layout=True)
    colours = plt.cm.viridis(np.linspace(0.0, 0.9, len(records)))
    for (name, rec), c in zip(records, colours):
        eta = np.asarray(rec["eta"])
        ax[0, 0].plot(eta, rec["strain"], "-", color=c, label=name)
        ax[0, 0].plot(eta, rec["critical_strain"], ":", color=c)
        if "recrystallised_fraction" not in rec:
            continue
        ax[0, 1].plot(eta, rec["recrystallised_fraction"], "-", color=c, label=name)
        ax[1, 0].plot(eta, 1e6 * np.asarray(rec["grain_size"]), "-", color=c, label=name)
        ax[1, 1].plot(eta, rec["retained_strain"], "-", color=c, label=name)
    titles = (("strain at the exit (-) and critical strain eps_c (:)", "strain (-)"),
              ("recrystallised after the transport", "fraction X (-)"),
              ("grain size handed on", "grain size (um)"),
              ("retained strain handed on", "strain (-)"))
    for a, (title, ylabel) in zip(ax.ravel(), titles):
        a.set_title(title)
        a.set_xlabel("eta = y / half thickness (0 centre, 1 surface) (-)")
        a.set_ylabel(ylabel)
        a.grid(alpha=0.3)
    ax[0, 1].set_ylim(-0.02, 1.02)
    ax[0, 0].legend(fontsize=8)
    try:
        with atomic(Path(path)) as tmp:
            fig.savefig(tmp, dpi=110)
    finally:
        plt.close(fig)
    return True
