"""hotroll from Python (issue 18): load a case, solve it, look at the result in a notebook.

    >>> import hotroll
    >>> case = hotroll.load_case("case.toml")              # or hotroll.example_case("1")
    >>> res = hotroll.solve(case.with_overrides(**{"mesh.h_contact": 0.02}))
    >>> res.roll_force, res.units["roll_force"]          # N/m (per m of width, one roll)
    >>> res.contact["normal_stress"]                     # Pa, along the arc (numpy arrays)
    >>> res.plot_contact(); res.plot_field("sigma_ef")
    >>> rows = hotroll.study("study.toml", out="DIR")      # a table, one dict per case
    >>> rows = hotroll.roll_schedule("finishing_mill", out="DIR")   # a schedule's table

Everything is SI (m, s, Pa, N, K); ``units`` says each summary figure's unit. A result reads
back what the run wrote to its directory (``summary.json``, ``contact.csv``, ``top.csv``,
``fields.npz``), so a finished run is opened with ``hotroll.open_result(DIR)`` as well.
"""
from __future__ import annotations

import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from hotroll.config.case import Case, CaseError, case_from_dict, load_case
from hotroll.config.schedule import load_schedule
from hotroll.config.study import load_study
from hotroll.examples import EXAMPLES, example_path, find_study, schedule_path
from hotroll.results.figures import plot_all
from hotroll.results.run_dir import RunDir
from hotroll.results.summary import Summary
from hotroll.workflows.runner import run_case
from hotroll.workflows.schedule import run_schedule
from hotroll.workflows.study import run_study

__all__ = ["Case", "CaseError", "Result", "example_case", "load_case", "case_from_dict",
           "open_result", "roll_schedule", "solve", "study"]


def example_case(name: str, method: str = "steady") -> Case:
    """A bundled case by name: the report's "1", "2", or a realistic pass such as
    "hot_strip_finishing" (``hotroll example`` lists them), solved by ``method`` ("steady",
    the default as on the command line, or "transient": the report's time stepping)."""
    files = EXAMPLES.get(name, [name])
    if len(files) != 1:
        raise CaseError(f"example {name!r} has several cases: {', '.join(files)}")
    return load_case(example_path(files[0])).with_overrides(**{"solver.method": method})


def solve(case: Case, out: str | Path | None = None, *, resume: bool = False) -> Result:
    """Run one case (the case's method: steady or transient) and return its result; ``out``:
    the output directory (default: a temporary one, kept as long as the result lives)."""
    tmp = None
    if out is None:
        tmp = tempfile.TemporaryDirectory(prefix="hotroll-")
        out = Path(tmp.name) / "run"
    run_case(case, Path(out), resume=resume)
    res = open_result(out)
    res._tmp = tmp
    return res


def open_result(out: str | Path) -> Result:
    """The result a run wrote to ``out``."""
    out = Path(out)
    files = RunDir(out)
    return Result(out, files.summary(), files.table("contact.csv") or {},
                  files.table("top.csv") or {})


def study(study_file: str | Path, out: str | Path, *, workers: int | None = None,
          scheduler: str | None = None, serial: bool = False,
          overrides: dict[str, Any] | None = None) -> list[dict]:
    """Run a study file or a bundled study's name (mesh_table, report_examples; ``hotroll
    study``), ``overrides`` (dotted keys) set on its base case; its table, one dict per
    combination (also ``out/study.csv``, ``study.parquet``, the figures of its [plot])."""
    st, base = load_study(find_study(study_file), overrides=overrides)
    return run_study(st, base, Path(out), workers=workers, scheduler=scheduler, serial=serial)


def roll_schedule(schedule_file: str | Path, out: str | Path, *,
                  figure: bool = True) -> list[dict]:
    """Roll a schedule file or a bundled schedule's name (``hotroll schedule``); its table."""
    path = Path(schedule_file)
    sch = load_schedule(path if path.exists() else schedule_path(str(schedule_file)))
    return run_schedule(sch, Path(out), figure=figure)


@dataclass
class Result:
    """One run's results (read from its directory ``out``)."""

    out: Path
    summary: Summary = field(repr=False)                 # typed, each key with its unit
    contact: dict[str, np.ndarray] = field(repr=False)   # along the arc: x, y, angle, stresses
    top: dict[str, np.ndarray] = field(repr=False)       # along the top boundary
    _tmp: Any = field(default=None, repr=False)

    def __getattr__(self, name: str) -> Any:
        """Summary figures as attributes: ``res.roll_force`` (N/m), ``res.forward_slip``."""
        summary = self.__dict__.get("summary") or {}
        if name in summary:
            return summary[name]
        raise AttributeError(f"{name!r}: not a field of the result or of its summary")

    def __repr__(self) -> str:
        s = self.summary
        return (f"Result({s.get('case_name')!r}, status {s.get('status')!r}, roll_force "
                f"{s.get('roll_force'):.6g} N/m, roll_torque {s.get('roll_torque'):.6g} N m/m, "
                f"out={str(self.out)!r})")

    @property
    def units(self) -> dict[str, str]:
        return self.summary.get("units", {})

    @property
    def fields(self) -> dict[str, np.ndarray]:
        """Vertex fields of the strip (fields.npz): points (m), triangles, v (m/s), pressure
        (Pa), edot (1/s), strain, sigma_ef (Pa), temperature (K), ..."""
        with np.load(self.out / "fields.npz") as z:
            return {k: z[k] for k in z.files}

    @property
    def converged(self) -> bool:
        return bool(self.summary.get("converged"))

    def plot_contact(self, ax=None):
        """Normal and shear stress along the arc against the roll angle (MPa, rad)."""
        import matplotlib.pyplot as plt

        ax = ax or plt.subplots(figsize=(7, 4))[1]
        c = self.contact
        for key, label in (("normal_stress_smooth", "normal stress"),
                           ("shear_stress_smooth", "shear stress")):
            if key in c:
                ax.plot(c["angle"], 1e-6 * c[key], label=label)
        ax.set_xlabel("roll angle from the gap (rad)")
        ax.set_ylabel("stress on the roll (MPa)")
        ax.legend()
        return ax

    def plot_field(self, name: str = "sigma_ef", ax=None):
        """A vertex field over the strip (``fields``), filled contours, SI units."""
        import matplotlib.pyplot as plt
        from matplotlib.tri import Triangulation

        f = self.fields
        if name not in f or f[name].ndim != 1:
            scalar = [k for k, v in f.items() if v.ndim == 1 and len(v) == len(f["points"])]
            raise KeyError(f"{name!r}: a scalar field is one of {', '.join(scalar)}")
        ax = ax or plt.subplots(figsize=(9, 3))[1]
        tri = Triangulation(f["points"][:, 0], f["points"][:, 1], f["triangles"])
        cs = ax.tricontourf(tri, f[name], levels=20)
        plt.colorbar(cs, ax=ax, label=name)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        return ax

    def figures(self) -> list[Path]:
        """The run's standard figures written into its directory (``hotroll run``'s)."""
        return plot_all(self.out)
