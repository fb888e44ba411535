"""Sweeps of neighbouring cases: each steady solve starts from the nearest solved one (issue 3).

A ``Sweep`` remembers the states it has solved. For a new steady case on the same mesh (same
geometry and mesh sizes: the vertex coordinates are compared) it starts Newton from the nearest
of them, the velocity scaled to the new roll speed (``SteadyRun._warm``); where only m, K, a_f or
the solver's tolerances differ, the previous run itself is kept, with its mesh, compiled forms
and factorisation; on an isothermal pass with rigid rolls also where the roll speed differs
(a form Parameter). Cases on other meshes, and transient ones, start cold.

Nearest = smallest sum of relative differences in m, roll surface speed, eps0 and v_reg (and a_f
when it is given as a number).
"""
from __future__ import annotations

import hashlib
from dataclasses import dataclass, field

from hotroll.config.case import Case, flat
from hotroll.solvers.full_steady import FullSteadyRun
from hotroll.solvers.steady import SteadyRun
from hotroll.solvers.transfer import SimilarPass
from hotroll.workflows.build import steady_settings

#: Keys a kept SteadyRun may differ in: they enter as parameters or settings, not in the form
#: (and the roll speed, for an isothermal pass with rigid rolls: ``form_key``).
_RUN_FREE = ("name", "material.m", "material.K", "friction.a_f", "friction.a_f_max",
             "plate.length")


def form_key(case: Case) -> str:
    """Hash of what the steady mesh and form are built from (everything but ``_RUN_FREE``,
    the solver's tolerances and the outputs)."""
    free = _RUN_FREE
    if not case.thermal and case.roll.model == "rigid":
        # the roll speed is a form Parameter (RollingForm.set_roll_speed); the temperature's
        # strip mesh depends on it (its first row), a flattening roll's surface is the run's
        free = free + ("pass.roll_angular_velocity",)
    d = {k: v for k, v in flat(case.to_dict()).items()
         if k not in free and not k.startswith(("output.", "solver."))}
    d["solver.steady_entry_length"] = case.solver.steady_entry_length
    d["solver.steady_exit_length"] = case.solver.steady_exit_length
    return hashlib.sha256(repr(sorted(d.items())).encode()).hexdigest()[:16]


def parameters(case: Case) -> dict[str, float]:
    """The parameters whose distance ranks the solved neighbours."""
    rp = case.pass_.roll_pass()
    p = {"m": case.material.rate_exponent(case.plate.temperature), "u_roll": rp.u_roll, "eps0": case.material.eps0,
         "v_reg": case.friction.regularisation_velocity(rp.u_roll)}
    # the friction law's own parameters (an estimated a_f is not one: it follows the solve)
    p.update({k: float(v) for k, v in case.friction.given().items() if not isinstance(v, str)})
    gap = case.roll_gap()
    if not gap.symmetric:
        # an asymmetric pass: each roll's own surface speed and friction (a study over the
        # speed ratio ranks its neighbours by them: with the upper roll's alone every ratio
        # lay at distance 0, the first solved taken)
        for roll in (gap.upper, gap.lower):
            name = "upper" if roll.side > 0 else "lower"
            p[f"u_roll_{name}"] = roll.surface_speed
            if roll.friction is not None:
                p.update({f"{k}_{name}": float(v) for k, v in roll.friction.parameters
                          if not isinstance(v, str)})
    return p


def distance(a: dict[str, float], b: dict[str, float]) -> float:
    """Sum of relative differences over the parameters both have."""
    return sum(abs(a[k] - b[k]) / max(abs(a[k]), abs(b[k])) for k in a.keys() & b.keys())


@dataclass
class Sweep:
    solved: list = field(default_factory=list)   # (case name, parameters, WarmStart)
    similar: bool = False     # start a case on a new mesh from the last solved pass (schedules)
    history: bool = True      # measure after every coupling update (history.csv), else the end
    _kept: tuple | None = None                   # (form key, SteadyRun) of the last solve
    _last: tuple | None = None                   # (case name, SteadyRun) last solved

    def steady_run(self, case: Case, model):
        """The previous run when only parameters differ, else a new SteadyRun."""
        key, settings = form_key(case), steady_settings(case)
        # not with a flattening roll: the kept run's strip map and form hold its own roll's
        # surface, the new case brings another (a reused run gave 15.5 MN/m against a fresh
        # run's 14.3 on the coarse Example 1 with an elastic roll, K 2e7 -> 3e7)
        if self._kept is not None and self._kept[0] == key and model.roll is None:
            run = self._kept[1]
            run.problem, run.s, run.plate_length = model, settings, case.plate.length
            # a tandem stand's solve may have moved its speed Parameters (TandemSpeed)
            run.form.set_roll_speed(model.rp, model.friction.v_reg)
            run.mesh_time = 0.0
        else:
            run = SteadyRun(model, settings, case.plate.length)
        self._kept = (key, run)
        run.record = self.history
        return run

    def nearest(self, case: Case, run):
        """(name, WarmStart) of the nearest solved case on ``run``'s mesh with the same
        free-surface model; else, with ``similar`` on, the last solved pass mapped onto this
        one (``algorithms/transfer.SimilarPass``); else (None, None)."""
        p = parameters(case)
        same = [(distance(p, q), name, w) for name, q, w in self.solved
                if w.mesh_key == run.mesh_key and w.free_surface == run.s.free_surface]
        if not same:
            last = self._last
            if (self.similar and last is not None and not isinstance(run, FullSteadyRun)
                    and last[1].s.free_surface == run.s.free_surface):
                return last[0], SimilarPass(last[1], last[0])
            return None, None
        _, name, warm = min(same, key=lambda t: t[0])
        return name, warm

    def add(self, case: Case, run) -> None:
        """Remember a converged Newton solve (its settled a_f and free surface)."""
        if run.result.stats and run.result.stats[-1].converged:
            self.solved.append((case.name, parameters(case), run.warm_start()))
            if not isinstance(run, FullSteadyRun):    # a similar pass maps the half strip
                self._last = (case.name, run)
