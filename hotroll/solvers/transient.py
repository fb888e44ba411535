"""Explicit Lagrangian time stepping to the steady state, report Sections 3.3-3.4.

Each step n: a_f from (3.15) with the previous velocity; solve (3.6) on Omega_n (Picard (3.8) or
Newton); move every P2 geometry node, x_{n+1} = x_n + dt v_n (3.7); project nodes that entered
the roll back onto it and flag contact nodes (3.9), a contact node staying in contact up to the
exit point (bilateral (2.28a)); every 10 steps put all contact nodes on the roll surface. The
first iterate of the first step uses m = 1 (Section 3.4).

Steady state and the summary windows: ``settling.py``.
"""
from __future__ import annotations

import json
import math
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Callable

import numpy as np

from hotroll.fem import quantities as Q
from hotroll.fem.mesh import build_plate_mesh
from hotroll.fem.nonlinear import LinearSolveError, SolveStats, picard, solve
from hotroll.fem.penalties import PenaltyTable
from hotroll.fem.reproducible import fe_space
from hotroll.fem.rolling_form import RollingForm
from hotroll.fem.top_boundary import TopBoundary
from hotroll.files import atomic
from hotroll.model.friction_estimate import estimate_a_f
from hotroll.model.material import NortonHoff
from hotroll.solvers import couplings as C
from hotroll.solvers.problem import Problem, Solution
from hotroll.solvers.record import solution_record
from hotroll.solvers.settling import steady_reached, summary_windows, transit_time
from hotroll.solvers.threads import solver_threads


class TangledMeshError(RuntimeError):
    """The moving mesh has an element with a non-positive Jacobian determinant."""


@dataclass
class TransientSettings:
    dt: float
    end_time: float
    nonlinear: str = "newton"
    tol: float = 1e-5
    max_it: int = 20
    steady_tol: float = 2e-3
    max_steps: int = 100000
    wall_time_limit: float | None = None
    checkpoint_every: int = 25
    contact_tol: float = 1e-5
    project_every: int = 10
    a_f: float | None = None      # None: estimate (3.15) at every step
    a_f_max: float = 1e6
    a_f_start: float = 1.0        # a_f of the very first solve when estimating
    free_surface: str = "traced"  # "traced": free tops move with the material, no (3.2d);
                                  # "constrained": (3.2d) on them, held at their flat heights


class TransientRun:
    """The report's scheme on one case; ``run`` advances it and returns its state."""

    time_stepping = True    # the Solver interface (solvers/problem.py)

    def __init__(self, problem: Problem, settings: TransientSettings,
                 checkpoint_dir: Path | None = None, fingerprint: str = ""):
        import ngsolve

        self.problem, self.s = problem, settings
        self.ckpt = Path(checkpoint_dir) if checkpoint_dir else None
        self.fingerprint = fingerprint
        self.state = Solution()
        rp, mat = problem.rp, problem.material
        resumed_mesh = self._load_mesh()
        self.mesh = resumed_mesh or build_plate_mesh(rp, problem.length, problem.mesh)
        if self.ckpt and not resumed_mesh:
            self.ckpt.mkdir(parents=True, exist_ok=True)
            self.mesh.ngmesh.Save(str(self.ckpt / "mesh.vol"))
        reduced = NortonHoff(1.0, mat.m, mat.eps0)
        self.strain, self.thermal, consistency = problem.field_setup(self.mesh, lagrangian=True)
        self.form = RollingForm(self.mesh, rp, reduced, problem.friction, PenaltyTable(problem.h),
                                free_surface=settings.free_surface,
                                tensions=problem.reduced_tensions, consistency=consistency,
                                rate_offset=self.thermal.rate_offset()
                                if self.thermal is not None else None)
        V = self.form.fes.components[0]
        self.disp = ngsolve.GridFunction(V)
        self.top = TopBoundary(self.mesh, V.ndof // 2)
        if self.thermal is not None:     # the temperature carried with the material
            self.thermal.attach(self.form, self.disp, self.top)
        # carried with the material by ``advance`` (solvers/couplings.py)
        self.couplings = ([C.StrainTransport(self.strain, self.form.nonlinear.velocity)]
                          if self.strain is not None else [])
        self.couplings += [C.Temperature(self.thermal)] if self.thermal is not None else []
        self.d = self.disp.vec.FV().NumPy()
        self._det = ngsolve.GridFunction(fe_space(ngsolve.L2, self.mesh, order=0))   # for _check_mesh
        # summary means: whole projection periods covering 3 h of roll travel; the steady test
        # compares two windows of at least 6 periods each
        self.window, self.steady_window = summary_windows(problem.h, rp.u_roll, settings.dt,
                                                          settings.project_every)
        self.last_stats = SolveStats()
        if not self._load_state():
            self._detect(project=True)
        self.mesh.SetDeformation(self.disp)

    # --- geometry ----------------------------------------------------------------------------
    def _detect(self, project: bool) -> None:
        self.top.detect(self.problem.rp, self.d, self.s.contact_tol, project,
                        bilateral=True)
        self.top.write_indicator(self.form.chi.vec.FV().NumPy())

    def head_x(self) -> float:
        return float(np.max(self.top.X0[:, 0] + self.d[: self.top.nv]))

    # --- one solve -----------------------------------------------------------------------------
    def _solve(self) -> SolveStats:
        return solve(self.form.nonlinear, self.s.nonlinear, self.s.tol, self.s.max_it)

    def _estimate_a_f(self) -> float:
        if self.s.a_f is not None:
            return self.s.a_f
        prof = Q.contact_profile(self.form, self.top, self.d, 1.0)
        vol, back = Q.a_f_inputs(self.form)
        lam = abs(prof["v_slip"][0]) / self.problem.rp.u_roll if len(prof["v_slip"]) else 0.0
        return estimate_a_f(vol, self.problem.h, lam, back,
                            self.problem.rp.u_roll, self.problem.material.m,
                            a_f_max=self.s.a_f_max)

    def initial_solve(self) -> SolveStats:
        """First step: one m = 1 iterate (Section 3.4), then the m solve; a_f estimate iterated."""
        f = self.form
        f.a_f.Set(self.s.a_f if self.s.a_f is not None else self.s.a_f_start)
        f.m.Set(1.0)
        first = picard(f.nonlinear, self.s.tol, 1)
        f.m.Set(self.problem.material.m)
        stats = self._solve()
        stats.iterations += first.iterations
        if self.s.a_f is None:  # iterate a_f <- (3.15)(v) to a fixed point, as the notes do
            for _ in range(10):
                a_old, a_new = f.a_f.Get(), self._estimate_a_f()
                f.a_f.Set(a_new)
                more = self._solve()
                stats.iterations += more.iterations
                if abs(a_new - a_old) <= 1e-2 * a_new:
                    break
        return stats

    # --- recording -----------------------------------------------------------------------------
    def measure(self) -> dict:
        """All per-step figures in SI units (stresses times K)."""
        row = {"step": self.state.step, "time": self.state.time}
        row.update(Q.measure(self.form, self.top, self.d, self.problem.material.K, self.problem.h,
                             self.head_x()))
        if self.thermal is not None:
            row.update(self.thermal.measure(self.problem.rp.axis_x, self.problem.h))
        row.update({"iterations": self.last_stats.iterations,
                    "residual": self.last_stats.residual,
                    "solver_converged": self.last_stats.converged})
        return row

    # --- steady state ----------------------------------------------------------------------------
    def is_steady(self) -> bool:
        rp = self.problem.rp
        carried = self.strain is not None or self.thermal is not None
        return (self.state.time >= transit_time(rp, carried)
                and steady_reached(self.state.history, self.steady_window, self.s.project_every,
                                   self.s.steady_tol, rp.bite_angle))

    # --- main loop -------------------------------------------------------------------------------
    def run(self, progress: Callable[[dict], None] | None = None) -> Solution:
        st, s = self.state, self.s
        t_wall = time.perf_counter()
        with solver_threads():
            if st.history and st.history[-1]["step"] == st.step:   # resumed after a finished run
                st.status = self._terminal(t_wall) or "running"
                if st.status != "running":
                    return st
                self.advance()
            while True:
                if st.step == 0:
                    self.last_stats = self.initial_solve()
                else:
                    if s.a_f is None:
                        self.form.a_f.Set(self._estimate_a_f())
                    vec = self.form.nonlinear.gf.vec.FV().NumPy()
                    last = vec.copy()
                    try:
                        self._check_mesh()
                        self.last_stats = self._solve()
                    except (LinearSolveError, TangledMeshError) as e:
                        # keep what is finished: the last step's fields, the history, a checkpoint
                        vec[:] = last
                        st.status, st.failure = "failed", f"step {st.step}: {e}"
                        break
                row = self.measure()
                st.history.append(row)
                if progress:
                    progress(row)
                status = self._terminal(t_wall)
                if status:
                    st.status = status
                    break
                self.advance()
                if self.ckpt and st.step % s.checkpoint_every == 0:
                    self.save_checkpoint()
        if self.ckpt:
            self.save_checkpoint()
        return st

    def solution_record(self, frame_shift: float = 0.0) -> Solution:
        """The solved pass as data, all that the results read (``solvers/record.py``)."""
        return solution_record(self, frame_shift)

    def _terminal(self, t_wall: float) -> str | None:
        """Why the run stops after the current step, or None."""
        st, s, row = self.state, self.s, self.state.history[-1]
        if not all(math.isfinite(row[k]) for k in ("roll_force", "plastic_power")):
            return "failed"
        if self.is_steady():
            return "steady"
        if st.time + 0.5 * s.dt >= s.end_time:
            return "end_time"
        if st.step + 1 >= s.max_steps:
            return "max_steps"
        if s.wall_time_limit and time.perf_counter() - t_wall > s.wall_time_limit:
            return "wall_time"
        return None

    def advance(self) -> None:
        """(3.7) for every P2 node, then contact detection (3.9)."""
        nv_dofs = self.form.fes.components[0].ndof
        # the nodes are material points: eps += dt edot, and they keep their temperature (one
        # implicit step); a_f (3.15) is set before each solve (``run``)
        for coupling in self.couplings:
            coupling.advance(self.s.dt)
        self.d += self.s.dt * self.form.nonlinear.gf.vec.FV().NumPy()[:nv_dofs]
        self.state.step += 1
        self.state.time += self.s.dt
        self._detect(project=self.state.step % self.s.project_every == 0)
        if self.s.free_surface == "constrained":
            self._hold_free_tops()
        self.mesh.SetDeformation(self.disp)

    def _hold_free_tops(self) -> None:
        """Constrained model: (3.2d) says the free tops do not move normally; the flat tops
        keep their heights (entry thickness before X_roll, the gap after it) and the nodes only
        slide along them. Without this they creep by the penalty's leak v.n = sigma_n/gamma."""
        rp, top = self.problem.rp, self.top
        free = ~self.top.vertex_contact
        verts = top.verts[free]
        xy = top.vertex_positions(self.d, verts)
        xy[:, 1] = np.where(xy[:, 0] > rp.axis_x, rp.half_exit, rp.half_entry)
        top.set_vertices(self.d, verts, xy)
        rows = np.nonzero(~top.edge_contact)[0]
        xm = top.midpoint_positions(self.d, rows)
        ends = np.stack([top.vertex_positions(self.d, top.ea[rows])[:, 1],
                         top.vertex_positions(self.d, top.eb[rows])[:, 1]], 1)
        # a free edge's midpoint goes on the chord of its ends (flat edges: the flat height)
        xm[:, 1] = ends.mean(axis=1)
        top.set_midpoints(self.d, rows, xm)

    def _check_mesh(self) -> None:
        """Raise TangledMeshError if (3.7) has turned an element inside out (det J <= 0)."""
        from ngsolve import Det, GridFunction, specialcf, x

        self._det.Set(Det(specialcf.JacobianMatrix(2)))
        bad = self._det.vec.FV().NumPy() <= 0.0
        if bad.any():
            xc = GridFunction(self._det.space)
            xc.Set(x)
            xs = xc.vec.FV().NumPy()[bad]
            raise TangledMeshError(f"{int(bad.sum())} elements turned inside out by the "
                                   f"Lagrangian update (3.7), at x = {xs.min():.4g}.."
                                   f"{xs.max():.4g} m")

    # --- checkpoints -----------------------------------------------------------------------------
    def save_checkpoint(self) -> None:
        """Atomic write of everything needed to resume (mesh saved once at start)."""
        st = self.state
        with atomic(self.ckpt / "state.npz") as tmp:
            self._write_state(tmp, st)

    def _write_state(self, tmp, st) -> None:
        np.savez(tmp, disp=self.d, sol=self.form.nonlinear.gf.vec.FV().NumPy(),
                 contact=self.top.vertex_contact,
                 strain=self.strain.values if self.strain is not None else np.zeros(0),
                 temperature=(self.thermal.values if self.thermal is not None
                              else np.zeros(0)),
                 a_f=self.form.a_f.Get(), step=st.step, time=st.time,
                 meta=json.dumps({"fingerprint": self.fingerprint, "status": st.status,
                                  "history": st.history, "settings": asdict(self.s)}))

    def _load_mesh(self):
        import ngsolve

        if not (self.ckpt and (self.ckpt / "state.npz").exists() and self._meta_ok()):
            return None
        return ngsolve.Mesh(str(self.ckpt / "mesh.vol"))

    def _meta_ok(self) -> bool:
        with np.load(self.ckpt / "state.npz") as z:
            return json.loads(str(z["meta"]))["fingerprint"] == self.fingerprint

    def _load_state(self) -> bool:
        if not (self.ckpt and (self.ckpt / "state.npz").exists() and self._meta_ok()):
            return False
        with np.load(self.ckpt / "state.npz") as z:
            if z["disp"].shape != self.d.shape:
                return False
            self.d[:] = z["disp"]
            self.form.nonlinear.gf.vec.FV().NumPy()[:] = z["sol"]
            self.form.a_f.Set(float(z["a_f"]))
            if "contact" in z.files:      # the bilateral contact set carries over
                self.top.vertex_contact[:] = z["contact"]
            if self.strain is not None and "strain" in z.files and z["strain"].size:
                self.strain.values[:] = z["strain"]
            if (self.thermal is not None and "temperature" in z.files
                    and z["temperature"].size):
                self.thermal.values[:] = z["temperature"]
            meta = json.loads(str(z["meta"]))
            self.state = Solution(int(z["step"]), float(z["time"]), meta["history"],
                                        "running")
        self._detect(project=False)
        return True
