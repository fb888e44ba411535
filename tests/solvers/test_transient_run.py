"""The transient run's own bookkeeping (hotroll/solvers/transient.py): the first contact
projection, the earliest steady state with a carried field, a finished run resumed, a failed
step's fields. Example 1's pass on the coarse mesh (h = 0.02 m), a few steps each.

Labels: [hand] numbers worked out by hand; [plumb] what a run keeps or does again."""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest
from casebuild import build_case, example1_coarse

from hotroll.fem.nonlinear import LinearSolveError
from hotroll.model.geometry import RollPass
from hotroll.solvers.settling import STEADY_KEYS
from hotroll.solvers.transient import TransientRun
from hotroll.workflows.runner import build_model

BASE = example1_coarse("transient_run", friction={"a_f": 3.0},
                       solver={"method": "transient", "threads": 1})


def test_the_first_contact_nodes_start_on_the_roll():
    """[hand] at a roll speed of 8 rad/s (U = 4.8 m/s) and dt = h/6 s, the contact tolerance
    is the drift bound 6 x 10 (U dt)^2 / 2R = 60 x 0.016^2 / 1.2 = 0.0128 m, more than the
    distance from the roll of the entry top's vertex next to the touching point (measured
    0.0093 m; h sin(alpha) = 0.008 m for a vertex h before it, alpha = 0.41 rad): that vertex
    is in contact from the start, and the start projects it (and its edge's midpoint) onto
    the roll, as every contact node (3.9); the other contact nodes lie on the arc already."""
    case = build_case(BASE, **{"pass.roll_angular_velocity": 8.0})
    problem, settings = build_model(case)
    assert settings.contact_tol == pytest.approx(60 * (4.8 * 0.02 / 6) ** 2 / 1.2, rel=1e-12)
    run = TransientRun(problem, settings)
    rp, top = problem.rp, run.top
    xv = top.vertex_positions(run.d)
    on = top.vertex_contact
    X0 = top.vertex_positions(np.zeros_like(run.d))
    entry = on & (X0[:, 0] < rp.x_touch - 1e-9)        # on the flat entry top before the bite
    assert entry.sum() == 1
    assert 0.005 < float(rp.signed_distance(X0[entry])[0]) < settings.contact_tol
    assert np.max(np.abs(rp.signed_distance(xv[on]))) < 1e-12
    xm = top.midpoint_positions(run.d)
    assert np.max(np.abs(rp.signed_distance(xm[top.edge_contact]))) < 1e-12


@pytest.mark.parametrize("field", ["strain", "thermal"])
def test_a_carried_field_delays_the_steady_state(field):
    """[hand] R = 0.625 m, 0.225 -> 0.2 m (l_c = sqrt(0.625^2 - 0.6^2) = 0.175 m), omega =
    1.4 rad/s (U = 0.875 m/s): one contact transit is 0.2 s; with a strain or a temperature
    carried by the material 0.2 x 1.2 x 0.225 / 0.2 = 0.27 s. A history steady by every
    measure is steady at 0.25 s without a carried field, and with one only from 0.27 s."""
    rp = RollPass(0.625, 0.225, 0.2, omega=1.4)
    assert rp.contact_length == pytest.approx(0.175, rel=1e-12)
    row = {key: 1.0 for key in STEADY_KEYS}

    def run(time, strain=None, thermal=None):
        return SimpleNamespace(problem=SimpleNamespace(rp=rp), strain=strain, thermal=thermal,
                               state=SimpleNamespace(time=time, history=[dict(row)] * 12),
                               steady_window=6,
                               s=SimpleNamespace(project_every=1, steady_tol=2e-3))

    assert TransientRun.is_steady(run(0.25))
    assert not TransientRun.is_steady(run(0.19))
    carried = {field: object()}
    assert not TransientRun.is_steady(run(0.25, **carried))
    assert not TransientRun.is_steady(run(0.2699, **carried))
    assert TransientRun.is_steady(run(0.2701, **carried))


def _counted(monkeypatch):
    calls = []
    for name in ("_solve", "initial_solve"):
        real = getattr(TransientRun, name)
        monkeypatch.setattr(TransientRun, name,
                            lambda self, _real=real, _name=name: calls.append(_name) or _real(self))
    return calls


def test_a_finished_run_resumed_returns_without_solving(tmp_path, monkeypatch):
    """[plumb] three steps (max_steps = 3: steps 0, 1, 2), checkpointed at the end; the same
    run built again from its checkpoint and run: the same status and history, nothing
    solved (the checkpoint of a finished run holds its last step's row)."""
    case = build_case(BASE, **{"solver.max_steps": 3})
    problem, settings = build_model(case)
    first = TransientRun(problem, settings, checkpoint_dir=tmp_path)
    st = first.run()
    assert st.status == "max_steps" and [r["step"] for r in st.history] == [0, 1, 2]
    calls = _counted(monkeypatch)
    again = TransientRun(problem, settings, checkpoint_dir=tmp_path)
    st2 = again.run()
    assert calls == []
    assert st2.status == "max_steps" and [r["step"] for r in st2.history] == [0, 1, 2]
    assert st2.history[-1]["roll_force"] == st.history[-1]["roll_force"]


def test_a_failed_step_keeps_the_last_steps_fields(monkeypatch):
    """[plumb] step 2's linear solve fails after it has written into the solution (a NaN
    update): the run stops "failed" naming the step, with the velocity and pressure of step 1
    as they were after its solve, and its history up to step 1."""
    problem, settings = build_model(build_case(BASE))
    run = TransientRun(problem, settings)
    vec = run.form.nonlinear.gf.vec.FV().NumPy()
    kept = {}

    def progress(row):
        kept[row["step"]] = vec.copy()

    real = TransientRun._solve

    def solve(self):
        if self.state.step == 2:
            vec[:] = math.nan
            raise LinearSolveError("no direct solver (test)")
        return real(self)

    monkeypatch.setattr(TransientRun, "_solve", solve)
    st = run.run(progress)
    assert st.status == "failed" and st.failure == "step 2: no direct solver (test)"
    assert [r["step"] for r in st.history] == [0, 1]
    assert np.all(np.isfinite(kept[1])) and np.array_equal(vec, kept[1])
