"""Figures made only from the files a run writes into its output directory.

No NGSolve import: everything is read back from ``summary.json``, ``contact.csv``, ``top.csv``,
``history.csv``, ``fields.npz`` and ``thermal.npz`` (any of them may be missing; figures that
need a missing file are skipped).

Conventions (as written by the solver): SI units, the model is the upper half of the plate
(y = 0 is the symmetry axis), the roll centre lies above the plate and the plate moves in +x.
A point of the roll surface at angle ``phi`` (measured from the roll's vertical centre line,
positive towards the entry) is ``(xc - R sin(phi), yc - R cos(phi))``.

``FIGURES`` is the one registry (file name, figure function, when it applies); ``plot_all``
and the HTML report (``results/report.py``) both iterate it. A new figure is a function in
its family's module and a line here.
"""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Callable

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

from hotroll.files import DiskFullError  # noqa: E402
from hotroll.results.figures.compare import plot_compare  # noqa: E402
from hotroll.results.figures.exit_profile import fig_exit_profile  # noqa: E402
from hotroll.results.figures.fields import fig_mesh, fig_sigma_ef, fig_velocity  # noqa: E402
from hotroll.results.figures.history import fig_history  # noqa: E402
from hotroll.results.figures.profiles import fig_contact, fig_contact_angle, fig_top  # noqa: E402
from hotroll.results.figures.roll import fig_roll  # noqa: E402
from hotroll.results.figures.rolls import fig_rolls  # noqa: E402
from hotroll.results.figures.run_files import RunFiles  # noqa: E402
from hotroll.results.figures.spread import fig_spread  # noqa: E402
from hotroll.results.figures.thermal import fig_temperature  # noqa: E402

__all__ = ["FIGURES", "RunFiles", "plot_all", "plot_compare"]

#: (file name, figure): each figure returns its path, or None where the files do not allow it.
FIGURES: tuple[tuple[str, Callable[[RunFiles, Path], Path | None]], ...] = (
    ("fig_mesh.png", fig_mesh),
    ("fig_sigma_ef.png", fig_sigma_ef),
    ("fig_velocity.png", fig_velocity),
    ("fig_contact.png", fig_contact),
    ("fig_contact_angle.png", fig_contact_angle),
    ("fig_top.png", fig_top),
    ("fig_history.png", fig_history),
    ("fig_temperature.png", fig_temperature),   # a coupled run's (None without [thermal])
    ("fig_roll.png", fig_roll),                 # a flattening roll's (None for a rigid one)
    ("fig_rolls.png", fig_rolls),               # an asymmetric pass's two rolls (else None)
    ("fig_exit_profile.png", fig_exit_profile),  # the outlet through the thickness (a profile)
    ("fig_spread.png", fig_spread),             # the 3D pass across the width ([spread])
)


def plot_all(out_dir) -> list[Path]:
    """Write all figures that the files in ``out_dir`` allow; return their paths.

    A figure that fails is reported with a warning and skipped so that one bad file does not
    cost the others; a full disk (``files.DiskFullError``) stops.
    """
    out_dir = Path(out_dir)
    run = RunFiles(out_dir)
    written: list[Path] = []
    for name, func in FIGURES:
        try:
            p = func(run, out_dir / name)
        except DiskFullError:
            plt.close("all")
            raise
        except Exception as exc:  # noqa: BLE001 - post-processing must not abort a run
            plt.close("all")
            warnings.warn(f"{name}: skipped ({type(exc).__name__}: {exc})")
            continue
        if p is not None:
            written.append(p)
    return written
