"""Memory and time of a case, estimated before meshing (issue 18): a mesh that would not fit
is refused with the estimate unless forced (``solver.force = true``, ``--force``).

Triangles: the integral of 1/(sqrt3/4 s^2) over the strip, s the size the mesher is asked for
(``fem/mesh.py``): h on the top over the fine zone, growing linearly to the core
size on the axis, and away from the fine zone by the grading to the far size. Taylor-Hood
P2/P1 has about 4.5 unknowns per triangle (2 (vertices + edges) + vertices, vertices ~ T/2,
edges ~ 3T/2). Memory and time: fits of measured runs (sparse direct factorisation, one
thread; the constants below say which). A [thermal] case's own temperature mesh is small
beside the mechanics' and not counted; its coupling iterations make it slower than the
estimate (about 2 x, docs/studies/thermal_cost.md).
"""
from __future__ import annotations

import math
import os
import sys
from dataclasses import dataclass

import numpy as np

from hotroll.fem.extruded_mesh import width_axis
from hotroll.fem.mesh import MeshSpec, plate_fine_length, plate_zone, steady_zone, top_height
from hotroll.solvers.settling import default_end_time
from hotroll.solvers.steady_settings import SteadySettings

#: unknowns per triangle of Taylor-Hood P2/P1 (2 x (vertices + edges) + vertices)
DOFS_PER_TRIANGLE = 4.5
#: measured: the meshes hold this many times the integral's triangles (0.82-0.91 on 9 cases)
MESHER_FACTOR = 0.87
#: measured: the unknowns the refinement at the contact's start adds (ratio 16, grading 0.3)
#: over ``corner_triangles``' fan: 245, 281, 364, 389 on hot_strip_finishing, Case R,
#: roughing_slab, narrow_bar's 2D pass against the fan's 441 (0.56-0.88; their mean)
CORNER_FACTOR = 0.73
#: peak resident memory of a run: fixed part (Python, NGSolve, the modules) and per unknown
#: (matrix, sparse LU fill, vectors). Measured, Example 1 steady, one thread: 189 MB at 2.3e3
#: unknowns, 208 MB at 1.2e4, 285 MB at 4.7e4, 457 MB at 1.2e5, 862 MB at 2.7e5
BASE_BYTES = 190e6
BYTES_PER_DOF = 2.5e3
#: steady solve: wall seconds per Newton iteration on one core, a N + b N^1.5 (the sparse
#: factorisation of a 2D problem grows as N^1.5), fitted to the same runs (the machine
#: shared): 0.046 s at 2.3e3 unknowns, 0.22 s at 1.2e4, 0.97 s at 4.7e4, 2.9 s at 1.2e5,
#: 9.9 s at 2.7e5; iterations per steady solve: 20-43 measured
SECONDS_A, SECONDS_B, STEADY_ITERATIONS = 1.35e-5, 4.3e-8, 30
#: the 3D pass of [spread] (issue 53) on the extruded prism mesh: Taylor-Hood unknowns per 2D
#: triangle, per width level (the layer's vertices and edges: 3 x 2T + T/2) and per layer (the
#: edges across it and its quadrilaterals: 3 x 2T); 41,538 against 41,145 counted on the
#: bundled narrow_bar (5 layers)
DOFS_PER_LEVEL, DOFS_PER_LAYER = 6.5, 6.0
#: ... its memory, a N^p (the 3D factorisation's fill grows faster than N), and its wall
#: seconds, c N^q for the whole 3D pass (set-up and solve), fitted to benchmarks/bench_3d.py's
#: three narrow-bar sizes (2.0-5.2e4 unknowns, 5.7-30.5 s, 0.38-1.23 GB) and three roughing
#: sizes (7.7e4-1.95e5, 119-1167 s, 2.02-8.83 GB), the code of 773fc10 (Newton on kept
#: factors from 6e4 unknowns, docs/validation/spread_3d.md "Three sizes at 3799a44"): the
#: peak memory as 0.14 GB (the process's, in BASE_BYTES) + a N^p, within 7 % of each; the
#: seconds by least squares in log-log, 0.74-1.43x of each (the roughing pass takes more
#: iterations per unknown than the bar)
BYTES_3D_COEF, BYTES_3D_EXP = 60.0, 1.544
SECONDS_3D_COEF, SECONDS_3D_EXP = 1.075e-10, 2.462
#: the report's scheme: seconds per step and unknown on one core (0.49 s per step with 2
#: threads on C2, 6.8e4 unknowns, docs/results.md; 1.6 x for one thread); the steps: end
#: time / dt (an upper bound: the run stops at the steady state, often a third of it)
STEP_SECONDS_PER_DOF = 1.15e-5


@dataclass(frozen=True)
class Estimate:
    triangles: int
    dofs: int
    memory_bytes: float
    seconds: float
    limit_bytes: float

    @property
    def fits(self) -> bool:
        return self.memory_bytes <= self.limit_bytes

    def text(self) -> str:
        return (f"about {self.dofs:,} unknowns ({self.triangles:,} triangles), "
                f"{self.memory_bytes / 1e9:.2g} GB of memory and {_duration(self.seconds)} "
                f"on one core (estimate; limit {self.limit_bytes / 1e9:.3g} GB)")


def _duration(s: float) -> str:
    return f"{s:.0f} s" if s < 120 else f"{s / 60:.0f} min" if s < 7200 else f"{s / 3600:.1f} h"


def available_bytes() -> float:
    """Inside a dask worker, its memory limit (a local cluster splits the machine's memory
    among its workers); else the memory this machine has free (MemAvailable), else its
    total."""
    dist = sys.modules.get("distributed")       # a worker has it; a plain run does not
    if dist is not None:                        # import it (memory and time for nothing)
        try:
            limit = dist.get_worker().memory_manager.memory_limit
            if limit:
                return float(limit)
        except (ValueError, AttributeError):
            pass
    try:
        with open("/proc/meminfo") as f:
            info = {ln.split(":")[0]: float(ln.split()[1]) * 1024 for ln in f}
        return info.get("MemAvailable", info["MemTotal"])
    except (OSError, KeyError, ValueError, IndexError):
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))


def triangles(rp, h: float, h_far: float, x0: float, x1: float, fine_lo: float, fine_hi: float,
              core: float, grading: float) -> float:
    """The integral of the triangle density over the strip x in [x0, x1] (module docstring)."""
    n = 400
    xs = np.linspace(x0, x1, 4 * n + 1)
    yt = top_height(rp, xs)
    dist = np.maximum(np.maximum(fine_lo - xs, xs - fine_hi), 0.0)
    eta = np.linspace(0.0, 1.0, 41)[:, None]                      # 0 on the axis, 1 on top
    s_fine = h * (core + (1.0 - core) * eta)                      # h on top, core h on the axis
    s = np.minimum(s_fine + grading * dist[None, :], h_far)
    density = 1.0 / (math.sqrt(3.0) / 4.0 * s**2)
    per_x = np.trapezoid(density, eta[:, 0], axis=0) * yt          # integral over y
    return float(np.trapezoid(per_x, xs))


def corner_triangles(h: float, ratio: float, grading: float) -> float:
    """The triangles the contact start's refinement adds (``fem/mesh._refine_corner``): the
    size from h / ratio at the corner growing by the grading back to h, s = h/ratio + g r, over
    the half disc below the entry top, less the uniform mesh's there: (pi / (sqrt3/4 g^2))
    (ln ratio + 1 / ratio - 1) - the half disc of radius (h - h/ratio) / g at size h, times
    CORNER_FACTOR (netgen grades around a point size more steeply than that)."""
    if ratio <= 1.0:
        return 0.0
    c, hc = math.sqrt(3.0) / 4.0, h / ratio
    graded = math.pi / (c * grading**2) * (math.log(ratio) + 1.0 / ratio - 1.0)
    radius = (h - hc) / grading
    return CORNER_FACTOR * (graded - 0.5 * math.pi * radius**2 / (c * h**2))


def estimate(case) -> Estimate:
    """The estimate for a validated case (its method's mesh; the temperature's own mesh of a
    [thermal] case is small beside it and not counted; with [spread] the 3D pass's unknowns,
    memory and time added)."""
    rp, h = case.pass_.roll_pass(), case.mesh.h
    spec = MeshSpec(h=h, fine_length=0.0, h_far=case.mesh.h_far, grading=case.mesh.grading)
    far = max(spec.far(rp), h)
    if case.solver.method == "steady":      # the lengths build.steady_settings passes on
        up, down, margin, core = SteadySettings(
            upstream=case.solver.steady_entry_length,
            downstream=case.solver.steady_exit_length).mesh_zone(rp, h)
        x0, x1, lo, hi = steady_zone(rp, up, down, margin)
    else:
        end = case.solver.end_time or default_end_time(rp)
        x0, x1, lo, hi = plate_zone(rp, case.plate.length, plate_fine_length(rp, h, end))
        core = spec.core_factor
    tri = MESHER_FACTOR * triangles(rp, h, far, x0, x1, lo, hi, core, case.mesh.grading)
    if case.solver.method == "steady":
        tri += MESHER_FACTOR * corner_triangles(h, case.mesh.corner_refinement,
                                                case.mesh.grading)
    if not case.roll_gap().symmetric:      # the full-thickness strip: the half strip mirrored
        tri *= 2
    dofs = DOFS_PER_TRIANGLE * tri
    if case.solver.method == "steady":
        seconds = STEADY_ITERATIONS * (SECONDS_A * dofs + SECONDS_B * dofs**1.5)
    else:
        seconds = max(1.0, end / case.dt) * STEP_SECONDS_PER_DOF * dofs
    memory = BASE_BYTES + BYTES_PER_DOF * dofs
    if case.spread is not None:           # the 3D pass across the width after the 2D one
        half = 0.5 * case.pass_.width
        layers = len(width_axis(case.spread.modelled(half), *case.spread.layers(half, h))) - 1
        dofs3 = ((layers + 1) * DOFS_PER_LEVEL + layers * DOFS_PER_LAYER) * tri
        memory += BYTES_3D_COEF * dofs3**BYTES_3D_EXP
        seconds += SECONDS_3D_COEF * dofs3**SECONDS_3D_EXP
        dofs += dofs3
    limit = case.solver.memory_limit or available_bytes()
    return Estimate(int(tri), int(dofs), memory, seconds, float(limit))


class ResourceError(Exception):
    """A case whose estimated memory is over the limit (not forced)."""


def check(case) -> Estimate:
    """The estimate; ResourceError naming ``mesh.h_contact`` when it does not fit and the case
    is not forced."""
    est = estimate(case)
    if not est.fits and not case.solver.force:
        raise ResourceError(
            f"mesh.h_contact: a mesh of h_contact = {case.mesh.h:.4g} m needs {est.text()}; "
            f"coarsen mesh.h_contact, raise solver.memory_limit [B], or force it "
            f"(solver.force = true, --force)")
    return est
