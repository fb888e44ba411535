"""What the steady solve needs from a discretisation of the strip (issue 52, the seam for 3D).

``SteadySolve`` (solvers/steady_solve.py: the Newton with the couplings inside it, the
continuation in m, the history rows; a mixin of each strip) calls only the methods and
attributes below on the strip it drives. Two strips implement them today: the half strip with its symmetry plane
(``SteadyRun`` itself: ``fem/mesh.py``, ``fem/rolling_form.py``, one ``TopBoundary``) and the
full-thickness strip between two rolls (``FullSteadyRun``: ``fem/full_strip.py``,
``fem/gap_form.py``, one ``TopBoundary`` per roll's side). A third (a 3D strip with spread)
implements them with its own mesh, spaces and form and inherits the solve unchanged.

A second discretisation that is no rolling strip at all, a power-law channel flow with a flux
coupling of its own, is driven by the loop in tests/solvers/test_second_discretisation.py (a
page of code: its mesh, spaces, form, coupling and history rows): the loop settles it at the
analytic pressure gradient. Not yet cut: the full strip still subclasses the half strip for a
few shared helpers; a strip object passed to the solve (composition rather than a mixin) is the
next step (docs/notes/issue52-plan.md, stage 4).
"""
from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np

from hotroll.model.solution import Solution


@runtime_checkable
class StripDiscretisation(Protocol):
    """The strip as the steady solve sees it."""

    #: the weak form: ``.nonlinear`` (the Newton problem, fem/forms.py), ``.m`` and ``.a_f``
    #: (Parameters), ``.friction_dual`` (or None), ``.compliance`` (the strip's elasticity or
    #: None)
    form: object
    #: what is solved and how (solvers/problem.py, solvers/steady_settings.py)
    problem: object
    s: object
    #: the FE mesh, the key a warm start checks it against, the time its set-up took (s)
    mesh: object
    mesh_key: object
    mesh_time: float

    def _cold_start(self) -> None:
        """The reference shape, the kinematic velocity guess and the friction parameters."""

    def _fresh_searches(self) -> None:
        """The contact ends' searches afresh (each solve)."""

    def _couplings(self, warm: bool = False) -> list:
        """The couplings of the fixed point, in their update order (solvers/couplings.py)."""

    def _couple_below(self, state: dict, given: float | None) -> float:
        """The Newton update (over U) below which the couplings move now."""

    def _warm(self, warm, vec: np.ndarray, target: float) -> None:
        """Start from a neighbour's solved state (a sweep's warm start)."""

    def update_surface(self) -> float:
        """Trace the free surfaces along the flow, remap the mesh; the residual (m)."""

    def measure(self, stats, index: int) -> dict:
        """One history row: the figures of the current solution (SI)."""

    def solution_record(self, frame_shift: float = 0.0) -> Solution:
        """The solved pass as a ``Solution`` (model/solution.py), for the results."""

    def head_x(self) -> float:
        """The strip's head (outlet) x, m."""

    @property
    def solution(self) -> np.ndarray:
        """The solution vector (velocity, pressure, multiplier)."""
