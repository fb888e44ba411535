"""A study case's final state on disk (``warm_state.npz``): what a resumed group starts its
next case from, as the uninterrupted group did (``workflows/study.py``): the half strip's
``WarmStart`` or the full strip's ``FullWarmStart``, and the half strip's run rebuilt from it
(the start of a similar pass on another mesh). Split from ``workflows/study.py``."""
from __future__ import annotations

import math
from pathlib import Path

from hotroll.fem.free_surface import StripShape
from hotroll.files import atomic
from hotroll.solvers.steady import SteadyRun
from hotroll.solvers.steady_settings import FullWarmStart, WarmStart
from hotroll.workflows.build import build_model, steady_settings

#: A solved case's final state (velocity-pressure vector, strip shape, a_f): a resumed group
#: starts its next case from it, as the uninterrupted group did.
WARM_FILE = "warm_state.npz"


def _shape_arrays(sh, prefix: str = "") -> dict:
    return {f"{prefix}x_c": sh.x_c, f"{prefix}entry_x": sh.entry_x,
            f"{prefix}entry_y": sh.entry_y, f"{prefix}exit_x": sh.exit_x,
            f"{prefix}exit_y": sh.exit_y, f"{prefix}x_e": math.nan if sh.x_e is None else sh.x_e}


def _shape_of(z, prefix: str = "") -> StripShape:
    x_e = float(z[f"{prefix}x_e"]) if f"{prefix}x_e" in z.files else math.nan   # issue 50
    return StripShape(float(z[f"{prefix}x_c"]), z[f"{prefix}entry_x"], z[f"{prefix}entry_y"],
                      z[f"{prefix}exit_x"], z[f"{prefix}exit_y"],
                      None if math.isnan(x_e) else x_e)


def save_warm(path: Path, warm) -> None:
    """A solved case's final state (``WarmStart`` of the half strip, ``FullWarmStart`` of
    the full strip: both sides' shapes, prefixed ``upper_``/``lower_``)."""
    import numpy as np

    common = {"solution": warm.solution, "m": warm.m, "u_roll": warm.u_roll,
              "mesh_key": warm.mesh_key, "free_surface": warm.free_surface}
    if isinstance(warm, FullWarmStart):
        arrays = {**common, "kind": "full", "wraps": np.asarray(warm.wraps, dtype=int),
                  **_shape_arrays(warm.shapes[1], "upper_"),
                  **_shape_arrays(warm.shapes[-1], "lower_")}
    else:
        arrays = {**common, "a_f": warm.a_f, **_shape_arrays(warm.shape)}
    with atomic(path) as tmp:
        np.savez(tmp, **arrays)


def load_warm(path: Path):
    import numpy as np

    z = np.load(path)
    if "kind" in z.files and str(z["kind"]) == "full":
        return FullWarmStart(z["solution"], {1: _shape_of(z, "upper_"), -1: _shape_of(z, "lower_")},
                             tuple(int(v) for v in z["wraps"]), float(z["m"]), float(z["u_roll"]),
                             str(z["mesh_key"]), str(z["free_surface"]))
    return WarmStart(z["solution"], _shape_of(z), float(z["a_f"]), float(z["m"]),
                     float(z["u_roll"]), str(z["mesh_key"]), str(z["free_surface"]))


def restore_run(case, warm):
    """A solved case's ``SteadyRun`` rebuilt from its case and final state (mesh, solution,
    strip shape): the start of a next case on another mesh (``transfer.SimilarPass``)."""
    model, _ = build_model(case)
    run = SteadyRun(model, steady_settings(case), case.plate.length)
    run.form.nonlinear.gf.vec.FV().NumPy()[:] = warm.solution
    run.shape = warm.shape.copy()
    run._set_shape()
    return run
