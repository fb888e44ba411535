"""What the direct steady solver takes and gives besides the run itself: its settings (mesh
zone, tolerances, free-surface model), the default strip lengths, the continuation path in m,
the warm start carried between neighbouring cases, and the solve's result record."""
from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field

import numpy as np

from hotroll.fem.free_surface import StripShape

#: Newton iterations of a continuation stage when the case leaves ``solver.max_iterations``
#: out (the coupled solve at the target m adds 3 per a_f / free-surface update, ``max_outer``).
STAGE_ITERATIONS = 30


def stage_iterations(given: int | None) -> int:
    """The Newton limit of a continuation stage: the case's ``solver.max_iterations`` where
    given (below 30 too: issue 51 item 7), else ``STAGE_ITERATIONS``."""
    return STAGE_ITERATIONS if given is None else int(given)


@dataclass
class SteadySettings:
    tol: float = 1e-5
    max_it: int = STAGE_ITERATIONS   # Newton iterations per continuation stage
    a_f: float | None = None         # None: (3.15), iterated to its fixed point
    a_f_max: float = 1e6
    a_f_rtol: float = 1e-2           # fixed point of the a_f rule reached at this change
    strain_rtol: float = 1e-3        # ... and of the strain field (strain-dependent flow stress)
    thermal_rtol: float = 1e-4       # ... and of the temperature (max change / max T)
    upstream: float | None = None    # flat entry length before the touching point (None: auto)
    downstream: float | None = None  # flat exit length after the roll gap (None: auto)
    m_path: tuple[float, ...] = ()   # continuation in m ending at the target (() : direct)
    stage_tol: float = 1e-2          # Newton tolerance on the intermediate stages
    fine_margin: float = 0.125       # fine mesh this many contact lengths (+4h) around the arc
    core_factor: float = 4.0         # mesh size on the axis / h (at most half_exit/8)
    free_surface: str = "traced"     # "traced": streamline tops; "constrained": flat, (3.2d)
    surface_tol: float = 1e-3        # shape converged when no traced top moves more than this x h
    roll_tol: float = 1e-5           # a flattening roll settled when its surface moves less than
                                     # this x the exit half-thickness per update
    max_outer: int = 30              # a_f / free-surface updates at the target m
    couple_below: float = 1e-2       # update them once the Newton update (at the P2 nodes) is
                                     # below this x U
    couple_below_warm: float = 0.1   # ... after a warm start (a neighbour's or a similar
                                     # pass's solution: its couplings are near their own)
    contact: str = "multiplier"      # exact contact (a multiplier on the arc) or "penalty"
    unilateral: bool = True          # exact contact: the strip may leave the roll (x_e free)

    def mesh_zone(self, rp, h: float) -> tuple[float, float, float, float]:
        """(upstream, downstream, fine margin, core factor) of the strip's mesh at contact
        size ``h`` (the memory estimate uses it before meshing). The interior carries little
        of the error: 4h on the axis (at least 8 elements through the exit half-thickness)
        halves the DOFs of the transient's 2h for the same roll force to 4e-5 (M2,
        docs/theory.md 4b)."""
        up, down = default_lengths(rp)
        core = max(1.0, min(self.core_factor, rp.half_exit / (8.0 * h)))
        return (self.upstream or up, self.downstream or down,
                self.fine_margin * rp.contact_length + 4 * h, core)


def default_lengths(rp) -> tuple[float, float]:
    """Upstream and downstream lengths: one contact length and two full thicknesses at least,
    so that the strip is rigid at both cut faces (checked in the tests by doubling them)."""
    lc = rp.contact_length
    return max(lc, 4.0 * rp.half_entry), max(lc, 4.0 * rp.half_exit)


def continuation_path(m: float) -> list[float]:
    """Continuation 1 -> m: geometric steps of at most a factor 2 in m."""
    n = max(1, math.ceil(math.log(1.0 / m) / math.log(2.0)))
    return [float(v) for v in np.geomspace(1.0, m, n + 1)[1:]] if m < 1.0 else [m]


@dataclass
class WarmStart:
    """A solved steady state that a neighbouring case on the same mesh can start from: its
    velocity-pressure vector, strip shape, a_f, and the m and roll speed it was solved for."""

    solution: np.ndarray
    shape: StripShape
    a_f: float
    m: float
    u_roll: float
    mesh_key: str
    free_surface: str = "traced"


@dataclass
class FullWarmStart:
    """A solved full strip (``solvers/full_steady.py``) that a neighbouring case on the same
    mesh can start from: its vector, both sides' shapes ({+1: upper, -1: lower}), the sides
    whose strip wraps its roll, and the m and reference roll speed it was solved for."""

    solution: np.ndarray
    shapes: dict
    wraps: tuple
    m: float
    u_roll: float
    mesh_key: str
    free_surface: str = "traced"


def mesh_key(mesh) -> str:
    """Hash of the vertex coordinates and element count: equal keys, same mesh and DOFs."""
    pts = np.array([v.point for v in mesh.vertices], dtype=float)
    return hashlib.sha256(pts.tobytes() + str(mesh.ne).encode()).hexdigest()[:16]


@dataclass
class SteadyResult:
    stats: list = field(default_factory=list)   # SolveStats per solve
    rows: list = field(default_factory=list)    # measured figures after each solve
    surface_moves: list = field(default_factory=list)   # surface residual per update, m
    a_f_history: list = field(default_factory=list)
    wall_time: float = 0.0
    mesh_time: float = 0.0

    settled: bool = False        # a_f and the free surface reached their fixed point
    fallback: bool = False       # the direct solve failed; solved again along m = 1 -> target
    warm_failed: bool = False    # the warm start did not converge or settle; solved again cold
    failure: str = ""            # why the last solve stopped: a linear solve that failed

    @property
    def iterations(self) -> int:
        return sum(s.iterations for s in self.stats)

    @property
    def converged(self) -> bool:
        return bool(self.stats) and self.stats[-1].converged and self.settled
