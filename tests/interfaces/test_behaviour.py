"""Behaviour of the real thing (issue 20): resume after an interruption, a real ``hotroll run``
through the command line with its exit codes, the VTU file read back, the figures checked by
their data. Coarse cases of Example 1's geometry (h = 0.02 m)."""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from casebuild import build_case, example1_coarse, shared_scope
from typer.testing import CliRunner

from hotroll.cli import app
from hotroll.results.outcome import EXIT_CODES, exit_code
from hotroll.workflows.runner import run_case

BASE = example1_coarse("behaviour", friction={"a_f": 3.0}, solver={
    "method": "transient", "end_time": 0.04, "threads": 1, "checkpoint_every": 4})

def _history(out):
    return np.genfromtxt(out / "history.csv", delimiter=",", names=True)


# --- resume -----------------------------------------------------------------------------------
class _Counter:
    """Counts TransientRun._solve calls; raises KeyboardInterrupt (a kill) at call ``stop``."""

    def __init__(self, monkeypatch, stop=None):
        from hotroll.solvers.transient import TransientRun

        self.n, self.stop, real = 0, stop, TransientRun._solve

        def counted(run):
            self.n += 1
            if self.stop is not None and self.n == self.stop:
                raise KeyboardInterrupt("killed (test)")
            return real(run)

        monkeypatch.setattr(TransientRun, "_solve", counted)


def test_resume_after_an_interruption_repeats_nothing(tmp_path, monkeypatch):
    """Killed during step 9 (checkpoints every 4 steps: the last at step 8), the resumed run
    solves only steps 8..n-1 and ends with the uninterrupted run's history; a changed case in
    the same directory starts from step 0."""
    case = build_case(BASE)
    whole = _Counter(monkeypatch)
    ref = run_case(case, tmp_path / "whole")
    n = ref["steps"]
    assert n >= 11 and whole.n == n                  # one _solve per step (step 0: initial)
    ref_hist = _history(tmp_path / "whole")

    out = tmp_path / "killed"
    killed = _Counter(monkeypatch, stop=10)          # the 10th solve is step 9's
    with pytest.raises(KeyboardInterrupt):
        run_case(case, out)
    assert killed.n == 10
    resumed = _Counter(monkeypatch)
    s = run_case(case, out)
    assert resumed.n == n - 8                        # steps 8..n-1 only
    assert s["steps"] == n and s["status"] == ref["status"] == "end_time"
    hist = _history(out)
    assert len(hist) == n and list(hist["step"]) == list(range(n))
    for key in ("roll_force", "roll_torque", "neutral_angle", "forward_slip", "head_x"):
        assert np.allclose(hist[key], ref_hist[key], rtol=1e-9, atol=1e-14, equal_nan=True), key
    assert s["roll_force"] == pytest.approx(ref["roll_force"], rel=1e-9)

    # a finished run resumed: nothing solved again
    again = _Counter(monkeypatch)
    assert run_case(case, out)["roll_force"] == pytest.approx(s["roll_force"], rel=1e-12)
    assert again.n == 0

    # a changed case (another a_f) in the same directory: the checkpoint is not its own
    changed = _Counter(monkeypatch)
    c = run_case(build_case(BASE, **{"friction.a_f": 3.5}), out)
    assert changed.n == n and c["steps"] == n
    assert c["roll_force"] != pytest.approx(s["roll_force"], rel=1e-6)


def test_checkpoint_round_trip(tmp_path):
    """A checkpoint restores everything a step needs: displacement, solution, a_f, the
    bilateral contact set (even where a fresh detection would differ), the strain at the
    nodes, step, time and history; a checkpoint of another case (its fingerprint) is not
    used."""
    from hotroll.solvers.transient import TransientRun
    from hotroll.workflows.runner import build_model

    case = build_case(BASE, "material", {"law": "hensel-spittel", "A": 1.0, "m2": 0.2,
                                         "m3": 0.2})
    model, settings = build_model(case)
    ckpt = tmp_path / "ckpt"
    run = TransientRun(model, settings, checkpoint_dir=ckpt, fingerprint="A")
    assert run.strain is not None
    run.s.end_time = 3.5 * run.s.dt
    run.run()
    assert run.state.step == 3
    # a contact node 5 tolerances off the roll: the carried (bilateral) contact set keeps it,
    # a fresh detection would release it (test_rolling.py::test_contact_is_bilateral_...)
    top, rp = run.top, model.rp
    P = top.vertex_positions(run.d)
    on = np.nonzero(top.vertex_contact & (P[:, 0] < rp.axis_x - 0.05))[0]
    k = on[len(on) // 2]
    r = np.hypot(*(P[k] - rp.centre))
    off = np.array(rp.centre) + (P[k] - rp.centre) * (r + 5 * settings.contact_tol) / r
    top.set_vertices(run.d, top.verts[[k]], off[None])
    run.strain.values[:] += np.linspace(0.0, 1.0, run.strain.values.size)
    run.form.a_f.Set(4.25)
    run.save_checkpoint()
    again = TransientRun(model, settings, checkpoint_dir=ckpt, fingerprint="A")
    # the vertices as saved (the detection after loading puts the midpoints of the contact
    # edges back on the arc, here those next to the node moved off it)
    assert np.allclose(again.top.vertex_positions(again.d), top.vertex_positions(run.d),
                       rtol=0.0, atol=1e-12)
    assert np.array_equal(again.form.nonlinear.gf.vec.FV().NumPy(),
                          run.form.nonlinear.gf.vec.FV().NumPy())
    assert again.form.a_f.Get() == 4.25
    assert np.array_equal(again.top.vertex_contact, run.top.vertex_contact)
    assert np.array_equal(again.strain.values, run.strain.values)
    assert (again.state.step, again.state.time) == (3, pytest.approx(3 * settings.dt))
    import json

    # (NaN != NaN: compared as JSON text)
    assert json.dumps(again.state.history) == json.dumps(run.state.history)
    assert len(again.state.history) == 4 and again.state.status == "running"
    other = TransientRun(model, settings, checkpoint_dir=ckpt, fingerprint="B")
    assert other.state.step == 0 and not other.state.history
    assert other.form.a_f.Get() != 4.25


@pytest.mark.mutation
def test_transient_windows_by_hand():
    """The summary's mean window covers 3 h of roll travel in whole projection periods, the
    steady test's windows at least 6 periods: h = 0.02 m, dt = h/6 = 1/300 s, U = omega R =
    0.2 pi m/s, 3 h / (U dt) = 0.06 / (0.2 pi / 300) = 28.6 steps -> 3 periods of 10 = 30
    steps; steady window max(6, 3) periods = 60 steps. With checkpoints: the mesh is saved
    once at the start, in the run's checkpoint directory."""
    from hotroll.solvers.transient import TransientRun
    from hotroll.workflows.runner import build_model

    model, settings = build_model(build_case(BASE))
    assert settings.project_every == 10 and settings.dt == pytest.approx(0.02 / 6)
    run = TransientRun(model, settings)
    assert (run.window, run.steady_window) == (30, 60)
    assert run.state.step == 0 and run.ckpt is None
    # a contact set is detected at the start (the plate touches the roll at its head)
    assert run.top.vertex_contact.sum() >= 3


@pytest.mark.mutation
def test_steady_test_looks_at_the_last_two_windows_only():
    """steady_reached compares the last two windows (60 rows each here) and nothing before:
    a start-up transient (force 50 % higher) in the rows before them, or a NaN forward slip
    there (the head not yet past the exit at the start), does not keep a settled run from
    being steady; the same transient inside the windows does."""
    from hotroll.solvers.settling import steady_reached

    def row(f, slip=0.03):
        return {"roll_force": 0.5 * f, "roll_torque": 0.1 * f, "strain_rate_measure": 0.09 * f,
                "forward_slip": slip, "neutral_angle": 0.04 * f}

    settled = [row(1.0) for _ in range(120)]
    early = [row(1.5), row(1.5, slip=math.nan)] + [row(1.5) for _ in range(58)]
    args = (60, 10, 2e-3, 0.39)
    assert steady_reached(early + settled, *args)
    assert not steady_reached(early[:30] + settled[:90], *args)   # the transient in window 1


# --- exit codes -------------------------------------------------------------------------------
@pytest.mark.parametrize("summary, code", [
    ({"converged": True, "status": "steady", "roll_force": 1.0, "roll_torque": 1.0}, 0),
    ({"converged": False, "status": "failed", "failure": "step 3: no direct solver"}, 3),
    ({"converged": False, "status": "failed", "failure": None, "roll_force": 1.0,
      "roll_torque": 1.0}, 4),                        # steady: the last Newton did not converge
    ({"converged": False, "status": "steady", "roll_force": 1.0, "roll_torque": 1.0}, 4),
    ({"converged": False, "status": "end_time", "roll_force": math.nan, "roll_torque": 1.0}, 4),
    ({"converged": False, "status": "end_time", "roll_force": 1.0, "roll_torque": 1.0}, 5),
    ({"converged": False, "status": "unsettled", "roll_force": 1.0, "roll_torque": 1.0}, 5),
    ({"converged": False, "status": "wall_time", "roll_force": 1.0, "roll_torque": 1.0}, 5),
    ({"converged": False, "status": "steady", "outlet_driven": True, "roll_force": 1.0,
      "roll_torque": 1.0}, 6),
    ({"converged": False, "status": "steady", "not_conserved": True, "roll_force": 1.0,
      "roll_torque": 1.0, "failure": "not conserved: mass_flux_error = 0.03 above 0.02"}, 7),
])
@pytest.mark.mutation   # cheap enough for mutmut's selection (pyproject [tool.mutmut])
def test_exit_code_says_what_happened(summary, code):
    assert exit_code(summary) == code
    assert code in EXIT_CODES


def _write_case(tmp_path, name="case", **over):
    path = tmp_path / f"{name}.toml"
    path.write_text(build_case(BASE, **over).to_toml())
    return path


@pytest.fixture(scope=shared_scope)
def cli_run(tmp_path_factory):
    """A real ``hotroll run`` of a coarse steady case, with figures and the VTU file."""
    tmp = tmp_path_factory.mktemp("cli")
    case = _write_case(tmp, **{"solver.method": "steady", "output.figures": True,
                               "output.vtk": True})
    result = CliRunner().invoke(app, ["run", str(case), "--out", str(tmp / "out")])
    return result, tmp / "out"


def test_cli_run_converges_with_exit_code_0(cli_run):
    import json

    result, out = cli_run
    assert result.exit_code == 0, result.output
    s = json.loads((out / "summary.json").read_text())
    assert s["converged"] and s["exit_code"] == 0
    # the printed table carries the figures with their units
    assert "roll_force" in result.output and "N/m" in result.output
    assert f"{s['roll_force']:.6g}" in result.output


def test_cli_exit_codes_of_real_runs(tmp_path, monkeypatch):
    """Not settled: a transient run that reaches its end time first (5). Skids: friction too
    low to draw the strip in (a_f = 0.5, the outlet penalty drives it; 6). Failed: a linear
    solve that fails at a step (3)."""
    runner = CliRunner()
    short = _write_case(tmp_path, "short", **{"solver.end_time": 0.01})
    r = runner.invoke(app, ["run", str(short), "--out", str(tmp_path / "short")])
    assert r.exit_code == 5, r.output
    skid = _write_case(tmp_path, "skid", **{"solver.method": "steady", "friction.a_f": 0.5})
    r = runner.invoke(app, ["run", str(skid), "--out", str(tmp_path / "skid")])
    assert r.exit_code == 6, r.output
    import json

    s = json.loads((tmp_path / "skid" / "summary.json").read_text())
    # the outlet penalty pushes the strip (negative power) instead of the roll pulling it
    assert s["outlet_driven"] and not s["converged"]
    assert s["outlet_penalty_power"] < -0.05 * s["plastic_power"]

    import hotroll.solvers.transient as T
    from hotroll.fem.nonlinear import LinearSolveError

    real, calls = T.solve, {"n": 0}

    def failing(*args, **kw):
        calls["n"] += 1
        if calls["n"] == 3:
            raise LinearSolveError("no direct solver (test)")
        return real(*args, **kw)

    monkeypatch.setattr(T, "solve", failing)
    r = runner.invoke(app, ["run", str(short), "--out", str(tmp_path / "fail")])
    assert r.exit_code == 3, r.output


# --- VTU read back -----------------------------------------------------------------------------
def test_vtu_has_the_fields_of_the_run(cli_run):
    """The VTU's velocity at the plate's entry and exit ends is the summary's entry and exit
    velocity, its pressure and sigma_ef are finite and sigma_ef > 0 where the plate deforms."""
    import json

    _, out = cli_run
    s = json.loads((out / "summary.json").read_text())
    import meshio  # an independent reader of the VTK XML format (what ParaView opens)

    vtu = meshio.read(out / "fields.vtu")
    pts, data = vtu.points, {k: np.asarray(v).reshape(len(vtu.points), -1)
                             for k, v in vtu.point_data.items()}
    assert set(data) >= {"velocity", "pressure", "edot", "sigma_ef"}
    assert len(pts) > 1000 and data["velocity"].shape[1] == 2
    assert all(np.all(np.isfinite(v)) for v in data.values())
    x, vx = pts[:, 0], data["velocity"][:, 0]
    assert vx[x > x.max() - 0.02].mean() == pytest.approx(s["exit_velocity"], rel=3e-3)
    assert vx[x < x.min() + 0.02].mean() == pytest.approx(s["entry_velocity"], rel=3e-3)
    # in the bite the plate deforms: sigma_ef = K sqrt3^(m+1) edot^m there
    bite = (x > 0.8) & (x < 1.0)
    assert np.all(data["sigma_ef"][bite] > 0)
    expect = 3.0 ** 0.6 * data["edot"][bite, 0] ** 0.2
    assert np.allclose(data["sigma_ef"][bite, 0], expect, rtol=1e-6)


# --- figures by their data ---------------------------------------------------------------------
def test_figures_show_finite_data_inside_their_axes(tmp_path, monkeypatch):
    """Every figure of a real run: each axes with data has finite lines inside its limits, and
    the contact figure's curves are the written contact profile."""
    import hotroll.results.figures as P

    s = run_case(build_case(BASE, **{"solver.method": "steady"}), tmp_path)
    figs = {}
    monkeypatch.setattr(P.plt, "close", lambda *a, **k: None)
    from matplotlib.figure import Figure

    real_savefig = Figure.savefig

    def savefig(fig, path, *a, **k):          # every figure, whoever saves it
        figs[re.sub(r"\.tmp\w*\.", ".", Path(path).name)] = fig   # atomic (files.py)
        return real_savefig(fig, path, *a, **k)

    monkeypatch.setattr(Figure, "savefig", savefig)
    P.plot_all(tmp_path)
    assert {"fig_contact.png", "fig_top.png", "fig_velocity.png", "fig_sigma_ef.png",
            "fig_mesh.png", "fig_contact_angle.png"} <= set(figs)
    for name, fig in figs.items():
        drawn = 0
        for ax in fig.axes:
            for line in ax.get_lines():
                xd, yd = (np.asarray(v, dtype=float) for v in line.get_data())
                ok = np.isfinite(xd) & np.isfinite(yd)
                if len(xd) < 2 or not ok.any():
                    continue
                drawn += 1
                x0, x1 = sorted(ax.get_xlim())
                y0, y1 = sorted(ax.get_ylim())
                # the axes show the data (up to the window some figures zoom to)
                assert x0 < np.max(xd[ok]) and np.min(xd[ok]) < x1, (name, line.get_label())
                assert y0 <= np.max(yd[ok]) and np.min(yd[ok]) <= y1, (name, line.get_label())
            drawn += len(ax.collections)
        assert drawn > 0, name
    # the contact figure plots the written profile: slip (first panel) and the contact
    # pressure p = -T_n.n (second panel, positive in compression as in every figure) against
    # x, and the neutral point's vertical line at its x
    contact = np.genfromtxt(tmp_path / "contact.csv", delimiter=",", names=True)
    a_vs, a_sn = figs["fig_contact.png"].axes[:2]

    def has(ax, y):
        return any(len(line.get_xdata()) == len(y)
                   and np.allclose(np.asarray(line.get_xdata(), float), contact["x"])
                   and np.allclose(np.asarray(line.get_ydata(), float), y) for line in ax.get_lines())

    assert has(a_vs, contact["v_slip"]) and has(a_sn, -contact["normal_stress"])
    assert any(np.allclose(np.asarray(line.get_xdata(), float), s["neutral_point"][0])
               for line in a_vs.get_lines())
    assert s["converged"]


@pytest.mark.mutation
def test_exit_figures_wait_for_the_head():
    """The exit face counts as a cross-section of the exit strip once the head is past the bite
    by l_c/4 + 2h (Q.measure): before, the exit velocity, flux, thickness and forward slip are
    NaN; just past it they are the head face's (here the unsolved start: v = 0, so the forward
    slip is -1 and the thickness that of the head face, in the roll gap at the start)."""
    from hotroll.fem import quantities as Q
    from hotroll.solvers.transient import TransientRun
    from hotroll.workflows.runner import build_model

    model, settings = build_model(build_case(BASE))
    run = TransientRun(model, settings)
    rp, h = model.rp, model.h
    threshold = rp.axis_x + 0.25 * rp.contact_length + 2 * h
    keys = ("exit_velocity", "mass_flux_out", "exit_thickness_measured", "forward_slip")
    for head in (rp.axis_x, threshold - 0.5 * h, threshold):
        row = Q.measure(run.form, run.top, run.d, 1.0, h, head)
        assert all(math.isnan(row[k]) for k in keys), head
        assert row["head_x"] == head
    row = Q.measure(run.form, run.top, run.d, 1.0, h, threshold + 1e-9)
    assert row["exit_velocity"] == 0.0 and row["mass_flux_out"] == 0.0
    assert row["forward_slip"] == -1.0
    assert row["exit_thickness_measured"] == pytest.approx(2.0 * rp.half_exit, rel=1e-9)
