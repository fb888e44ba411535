"""The steady solve's loop drives a discretisation that is not a rolling strip (issue 52, the
seam for 3D: ``solvers/discretisation.py``).

A second implementation of ``StripDiscretisation``, written here in a page: power-law
(Norton-Hoff) flow in a half channel of height H, driven by a pressure gradient G through its
inlet face, with one coupling of its own: G moved until the channel carries a target flux Q*.
It inherits ``SteadySolve`` (the Newton with the couplings inside it, the history rows) and
nothing of the half or full strip. Independent reference: the power-law Poiseuille flow,
Q = m/(2m+1) (G/K)^(1/m) H^((2m+1)/m), so the coupling must settle at
G* = K ((2m+1) Q* / (m H^((2m+1)/m)))^m."""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from hotroll.fem.forms import NonlinearProblem, norton_hoff_volume
from hotroll.fem.reproducible import integrate
from hotroll.fem.spaces import taylor_hood
from hotroll.model.material import NortonHoff
from hotroll.solvers.couplings import Coupling
from hotroll.solvers.discretisation import StripDiscretisation
from hotroll.solvers.steady_settings import SteadySettings
from hotroll.solvers.steady_solve import SteadySolve
from hotroll.solvers.verification import rectangle

K, M, H, L = 2.0, 0.4, 1.0, 2.0
Q_TARGET = 0.3


def g_exact(q: float) -> float:
    """The pressure gradient of the power-law Poiseuille flow carrying q (by hand)."""
    return K * ((2.0 * M + 1.0) * q / (M * H ** ((2.0 * M + 1.0) / M))) ** M


class FluxTarget(Coupling):
    """G moved by the power law's own exponent, G (Q*/Q)^m (exact for the continuum law; the
    discrete flux settles it in a few rounds); the change is |Q/Q* - 1| over ``rtol``."""

    name = "flux"

    def __init__(self, channel, rtol: float = 1e-6):
        self.channel, self.rtol = channel, rtol

    def update(self, result) -> float:
        q = self.channel.flux()
        G = self.channel.G
        G.Set(G.Get() * (Q_TARGET / q) ** M)
        return abs(q / Q_TARGET - 1.0) / self.rtol


class Channel(SteadySolve):
    """A half channel [0, L] x [0, H] (symmetry at y = 0, no slip at y = H) as the steady
    solve's discretisation: its mesh, spaces and form, its coupling, its history rows."""

    def __init__(self, h: float = 0.125):
        from ngsolve import Parameter, ds, dx

        self.mesh = rectangle(L, H, round(L / h), round(H / h), ("sym", "out", "wall", "in"))
        fes = taylor_hood(self.mesh, dirichletx="wall", dirichlety="sym|wall|in|out")
        material = NortonHoff(K=K, m=M, eps0=1e-6)
        self.G = Parameter(0.5 * g_exact(Q_TARGET))       # a guess off by 2^m in flux
        m = Parameter(M)

        def integrand(u, p, w, v, q):
            vol = norton_hoff_volume(material, m, u, p, w, v, q, K=K)
            return vol * dx - self.G * L * v[0] * ds("in")

        u_ref = Q_TARGET / H
        self.form = SimpleNamespace(nonlinear=NonlinearProblem(fes, integrand,
                                                               velocity_scale=u_ref),
                                    m=m, friction_dual=None, compliance=None)
        self.problem = SimpleNamespace(material=material, roll=None)
        self.s = SteadySettings(tol=1e-9, max_outer=20)
        self.mesh_key, self.mesh_time, self.record = ("channel", h), 0.0, True

    # --- the StripDiscretisation hooks ---------------------------------------------------
    def _cold_start(self) -> None:
        """A parabola carrying the target flux (the Newtonian profile), pressure 0."""
        from ngsolve import CF, y

        nl = self.form.nonlinear
        nl.gf.vec[:] = 0.0
        nl.gf.components[0].Set(CF((1.5 * Q_TARGET / H * (1.0 - (y / H) ** 2), 0.0)))
        nl.fix_dirichlet()

    def _fresh_searches(self) -> None:
        pass

    def _couplings(self, warm: bool = False) -> list:
        return [FluxTarget(self)]

    def _couple_below(self, state: dict, given: float | None) -> float:
        return self.s.couple_below if given is None else given

    def _warm(self, warm, vec, target) -> None:
        raise NotImplementedError("no warm start")

    def update_surface(self) -> float:
        return 0.0                       # no free surface

    def measure(self, stats, index: int) -> dict:
        return {"step": index, "G": self.G.Get(), "flux": self.flux(),
                "iterations": stats.iterations, "solver_converged": stats.converged}

    def solution_record(self, frame_shift: float = 0.0):
        raise NotImplementedError("the channel writes no results")

    def head_x(self) -> float:
        return L

    @property
    def solution(self) -> np.ndarray:
        return self.form.nonlinear.gf.vec.FV().NumPy()

    def flux(self) -> float:
        """The mean over x of the flow rate int_0^H u_x dy (m^2/s)."""
        u = self.form.nonlinear.velocity
        return integrate(u[0], self.mesh, order=6) / L


@pytest.fixture(scope="module")
def channel():
    ch = Channel()
    sol = ch.run()
    return ch, sol


def test_the_channel_is_a_discretisation_of_the_protocol(channel):
    assert isinstance(channel[0], StripDiscretisation)


def test_the_loop_settles_the_channels_own_coupling_at_the_analytic_gradient(channel):
    """Independent (the power-law Poiseuille flow by hand): the steady solve's loop, run on
    the channel, settles its flux coupling at G* to the discretisation's flux error (P2 on
    h = H/8: measured 1.0e-5 in G), from a start at G*/2 (the flux off by 2^(1/m))."""
    ch, sol = channel
    assert sol.status == "steady" and ch.result.settled
    assert ch.G.Get() == pytest.approx(g_exact(Q_TARGET), rel=1e-4)
    assert ch.flux() == pytest.approx(Q_TARGET, rel=1e-5)
    assert math.isclose(sol.history[-1]["flux"], ch.flux(), rel_tol=1e-12)


def test_the_loop_records_a_row_per_solve_and_coupling_update(channel):
    """The loop's own bookkeeping on a foreign discretisation: one history row per coupling
    update and one for the final Newton solve; the first update sees the guess's G."""
    ch, sol = channel
    rows = sol.history
    assert len(rows) >= 3 and rows[0]["G"] != rows[-1]["G"]
    assert rows[-1]["solver_converged"] and rows[-1]["iterations"] > 0
    assert sum(r["iterations"] == 0 for r in rows) == len(rows) - 1
