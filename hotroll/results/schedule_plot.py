"""The schedule's figure: force, torque, power, temperature and strain per pass."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from hotroll.files import atomic


def plot_schedule(rows: list[dict], path: Path, width: float | None = None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = np.arange(1, len(rows) + 1)
    names = [r["name"] for r in rows]
    col = lambda key: np.array([np.nan if r.get(key) is None else r[key] for r in rows], float)
    fig, ax = plt.subplots(2, 2, figsize=(11, 7.5), constrained_layout=True)
    a = ax[0, 0]
    if width:
        a.bar(n, 1e-6 * col("roll_force_total"), color="tab:blue")
        a.set_ylabel("roll force, whole width (MN)")
    else:
        a.bar(n, 1e-6 * col("roll_force"), color="tab:blue")
        a.set_ylabel("roll force (MN/m)")
    a.set_title("roll force")
    a = ax[0, 1]
    w, per = (width, "") if width else (1.0, "/m")
    a.plot(n, 1e-3 * w * col("roll_torque"), "o-", color="tab:blue")
    a.set_ylabel(f"torque per roll (kN m{per})", color="tab:blue")
    b = a.twinx()
    b.plot(n, 2e-6 * w * col("roll_power"), "s--", color="tab:red")
    b.set_ylabel(f"power of both rolls (MW{per})", color="tab:red")
    b.set_ylim(bottom=0.0)
    a.set_ylim(bottom=0.0)
    a.set_title("torque (o) and power (s)" + (", whole width" if width else ", per m width"))
    a = ax[1, 0]
    a.plot(n, col("entry_temperature_mean") - 273.15, "o-", label="entry mean")
    a.plot(n, col("exit_temperature_mean") - 273.15, "s-", label="exit mean")
    a.plot(n, col("exit_temperature_surface") - 273.15, "v--", label="exit surface (gap)")
    edge = col("next_entry_temperature_edge")        # a [spread] schedule's, after a transport
    if len(rows) > 1 and np.any(np.isfinite(edge[:-1])):
        a.plot(n[1:], edge[:-1] - 273.15, "d:", label="entry edge (thickness mean)")
    a.set_ylabel("temperature (°C)")
    a.set_title("temperature")
    a.legend()
    a = ax[1, 1]
    a.plot(n, col("exit_strain_mean"), "o-", label="exit strain (FE mean)")
    a.plot(n, col("homogeneous_exit_strain"), "s--", label="entry + 2/√3 ln(h0/h1)")
    a.plot(n, 1e3 * col("exit_thickness") / max(1e3 * col("entry_thickness")[0], 1e-300),
           "^:", label="exit thickness / first entry")
    a.set_title("strain and thickness")
    a.legend()
    for a in ax.ravel():
        a.set_xticks(n, names)
        a.set_xlabel("pass")
        a.grid(alpha=0.3)
    try:
        with atomic(Path(path)) as tmp:
            fig.savefig(tmp, dpi=110)
    finally:
        plt.close(fig)
