"""The parts of a study run (workflows/study.py) that need no study: a case's saved final
state (warm_state.npz) and the run rebuilt from it, a failed case's reason, and a schedule
case's row when its schedule fails. Fast (no FE solve); the studies themselves are in
test_study.py."""
from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from hotroll.config.case import CaseError
from hotroll.fem.free_surface import StripShape
from hotroll.results.outcome import EXIT_CODES
from hotroll.solvers.steady_settings import WarmStart
from hotroll.workflows.estimate import ResourceError

SCHEDULE = Path(__file__).resolve().parents[1] / "data" / "two_pass_schedule.toml"


def _warm(solution: np.ndarray, shape: StripShape) -> WarmStart:
    return WarmStart(solution, shape, 5.0, 0.2, 0.6283, "mesh-abc", "constrained")


def test_a_saved_warm_state_loads_back_unchanged(tmp_path):
    """save_warm then load_warm: every field of the WarmStart back as written (arrays to the
    bit, a_f, m, u_roll, mesh key and free-surface model, the contact's end)."""
    from hotroll.workflows.warm_state import load_warm, save_warm

    shape = StripShape(0.25, np.array([-1.0, 0.0, 0.25]), np.array([0.25, 0.25, 0.24]),
                       np.array([0.5, 0.7, 1.5]), np.array([0.2, 0.201, 0.2015]))
    warm = _warm(np.linspace(-1.0, 2.0, 17), shape)
    save_warm(tmp_path / "warm_state.npz", warm)
    back = load_warm(tmp_path / "warm_state.npz")
    assert np.array_equal(back.solution, warm.solution)
    assert back.shape.x_c == 0.25
    for k in ("entry_x", "entry_y", "exit_x", "exit_y"):
        assert np.array_equal(getattr(back.shape, k), getattr(shape, k)), k
    assert (back.a_f, back.m, back.u_roll) == (5.0, 0.2, 0.6283)
    assert (back.mesh_key, back.free_surface) == ("mesh-abc", "constrained")
    assert back.shape.x_e is None                     # held to the gap: no end of its own
    shape.x_e = 0.97                                   # a strip that left the roll (issue 50)
    save_warm(tmp_path / "warm_state.npz", _warm(warm.solution, shape))
    assert load_warm(tmp_path / "warm_state.npz").shape.x_e == 0.97


def test_restore_run_is_the_cases_steady_run_at_the_saved_state():
    """restore_run (coarse Example 1, about 0.5 s of meshing): the run of the case with the
    case's own steady settings (runner.steady_settings), the saved solution vector in its
    form and a copy of the saved strip shape."""
    from casebuild import EXAMPLE1_COARSE, build_case

    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.runner import build_model, steady_settings
    from hotroll.workflows.warm_state import restore_run

    case = build_case(EXAMPLE1_COARSE)
    fresh = SteadyRun(build_model(case)[0], steady_settings(case), case.plate.length)
    n = len(fresh.form.nonlinear.gf.vec)
    warm = _warm(np.linspace(0.0, 1.0, n), fresh.shape.copy())
    run = restore_run(case, warm)
    assert run.s == steady_settings(case)
    assert np.array_equal(run.form.nonlinear.gf.vec.FV().NumPy(), warm.solution)
    assert run.shape is not warm.shape and run.shape.x_c == warm.shape.x_c
    assert np.array_equal(run.shape.entry_x, warm.shape.entry_x)


def test_a_failed_cases_reason_names_code_status_and_failure():
    """_reason: the exit code's meaning (results/outcome.EXIT_CODES), the status and, when
    the summary has one, the failure; '?' for a code without a meaning."""
    from hotroll.workflows.study import _reason

    assert _reason({"exit_code": 4, "status": "unsettled"}) == "diverged (status unsettled)"
    assert EXIT_CODES[4] == "diverged"
    assert _reason({"exit_code": 3, "status": "failed", "failure": "tangled mesh"}) == \
        "failed (status failed): tangled mesh"
    assert _reason({"exit_code": 99, "status": "x", "failure": ""}) == "? (status x)"


@pytest.mark.parametrize("error,row", [
    (lambda: ResourceError("mesh.h_contact: too fine"),
     {"status": "too_large", "exit_code": 8, "reason": "mesh.h_contact: too fine",
      "resumed": False}),
    (lambda: CaseError(["pass[2].exit_thickness: too thick", "plate.temperature: too hot"]),
     {"status": "bad_input", "exit_code": 2,
      "reason": "pass[2].exit_thickness: too thick; plate.temperature: too hot",
      "resumed": False}),
])
def test_a_schedule_case_that_cannot_run_is_a_row_with_its_reason(tmp_path, monkeypatch,
                                                                   error, row):
    """run_schedule_item when its schedule is refused (memory estimate: exit code 8) or a
    later pass's case is invalid (exit code 2): the row says so, with the refusal's text or
    the problems joined by '; ', and nothing was resumed (the schedule itself is faked)."""
    import hotroll.workflows.study as study

    def refuse(*args, **kw):
        raise error()

    monkeypatch.setattr(study, "run_schedule", refuse)
    item = {"schedule": tomllib.loads(SCHEDULE.read_text())}
    assert study.run_schedule_item(item, tmp_path) == row


def _study_case(index: int, h: float):
    from casebuild import build_case, example1_coarse

    from hotroll.config.study import StudyCase

    case = build_case(example1_coarse(f"c{index}"), **{"mesh.h_contact": h})
    return StudyCase(index, f"c{index}", {"mesh.h_contact": h}, case)


def test_groups_put_the_cases_on_one_mesh_next_to_each_other():
    """groups: four valid cases on two meshes, alternating, and a refused one (no case), for
    one worker (two groups): each group holds the cases of one mesh, in their order; the
    refused one is in none."""
    from hotroll.config.study import StudyCase
    from hotroll.workflows.study import groups

    cases = [_study_case(i, h) for i, h in enumerate((0.02, 0.03, 0.02, 0.03))]
    cases.append(StudyCase(4, "bad", {"mesh.h_contact": -1.0}, None, "mesh.h_contact: > 0"))
    got = [[c.index for c in g] for g in groups(cases, 1)]
    assert sorted(got) == [[0, 2], [1, 3]]


def test_run_group_rows_and_the_sweep_its_cases_share(tmp_path, monkeypatch):
    """run_group with the runs faked: a row per case with its index, label, varied values and
    the summary's scalars; a failed run's reason is _reason's; with warm starts one Sweep is
    handed to every run, one that maps the last pass onto a new mesh (``similar``, module
    docstring: "else from the last one mapped onto its mesh"); without, none."""
    import hotroll.workflows.study as study
    from hotroll.workflows.sweep import Sweep

    seen = []

    def fake_run_case(case, out, *, resume, sweep):
        seen.append(sweep)
        bad = len(seen) == 2
        return {"exit_code": 4 if bad else 0, "status": "unsettled" if bad else "steady",
                "roll_force": float(len(seen)), "contact": [1, 2]}

    monkeypatch.setattr(study, "run_case", fake_run_case)
    items = [{"index": c.index, "label": c.label, "values": c.values, "case": c.case.to_dict()}
             for c in (_study_case(0, 0.02), _study_case(1, 0.03))]
    rows = study.run_group(items, str(tmp_path), True)
    assert [(r["index"], r["case"], r["mesh.h_contact"]) for r in rows] == [
        (0, "c0", 0.02), (1, "c1", 0.03)]
    assert (rows[0]["status"], rows[0]["exit_code"], rows[0]["reason"]) == ("done", 0, None)
    assert (rows[1]["status"], rows[1]["exit_code"], rows[1]["reason"]) == (
        "not_converged", 4, "diverged (status unsettled)")
    assert [r["roll_force"] for r in rows] == [1.0, 2.0] and "contact" not in rows[0]
    assert isinstance(seen[0], Sweep) and seen[0] is seen[1] and seen[0].similar is True
    seen.clear()
    study.run_group(items, str(tmp_path / "cold"), False)
    assert seen == [None, None]


def test_column_units_of_a_schedule_study(tmp_path):
    """column_units: a pass's column (``R1.roll_force``) has its key's unit from the first
    finished case's schedule.json, a schedule total its own, a varied key the unit given."""
    from hotroll.results.output import write_json
    from hotroll.workflows.study import column_units

    (tmp_path / "cases" / "a").mkdir(parents=True)
    write_json(tmp_path / "cases" / "a" / "schedule.json",
               {"units": {"roll_force": "N/m", "exit_thickness": "m"}})
    rows = [{"index": 0, "case": "a", "status": "done", "strip.temperature": 1373.15,
             "R1.roll_force": 1.0, "R2.roll_force": 2.0, "exit_thickness": 0.065}]
    units = column_units(tmp_path, rows, {"strip.temperature": "K"})
    assert units["R1.roll_force"] == units["R2.roll_force"] == "N/m"
    assert units["exit_thickness"] == "m" and units["strip.temperature"] == "K"


def test_study_figures_are_written_where_named(tmp_path, monkeypatch):
    """figures: study.png and, with [plot] profiles, study_profiles.png in the study's
    directory (the drawing itself faked); no [plot], no figures."""
    from types import SimpleNamespace

    import hotroll.workflows.study as study

    drawn = []
    monkeypatch.setattr(study, "plot_table", lambda rows, plot, png, **kw: drawn.append(png)
                        or png)
    monkeypatch.setattr(study, "plot_profiles", lambda rows, out, png, **kw: drawn.append(png)
                        or png)
    st = SimpleNamespace(name="s", plot=SimpleNamespace(profiles=True))
    made = study.figures(st, tmp_path, [], {})
    assert made == drawn == [tmp_path / "study.png", tmp_path / "study_profiles.png"]
    assert study.figures(SimpleNamespace(name="s", plot=None), tmp_path, [], {}) == []


def test_a_dask_worker_estimates_with_its_own_memory_limit(monkeypatch):
    """Inside a dask worker (``distributed`` imported), the memory a case may use is the
    worker's limit (a local cluster splits the machine among its workers); a worker without a
    limit, or no worker, falls back to the machine's available memory."""
    import sys
    from types import SimpleNamespace

    from hotroll.workflows import estimate as E

    machine = E.available_bytes()
    assert machine > 0
    worker = SimpleNamespace(memory_manager=SimpleNamespace(memory_limit=123e6))
    monkeypatch.setitem(sys.modules, "distributed", SimpleNamespace(get_worker=lambda: worker))
    assert E.available_bytes() == 123e6
    worker.memory_manager.memory_limit = 0
    assert E.available_bytes() == pytest.approx(machine, rel=0.5)

    def no_worker():
        raise ValueError("No worker found")

    monkeypatch.setitem(sys.modules, "distributed", SimpleNamespace(get_worker=no_worker))
    assert E.available_bytes() == pytest.approx(machine, rel=0.5)


def test_the_triangle_count_of_a_uniform_flat_strip_by_hand():
    """An equilateral mesh of size h has one triangle per sqrt3/4 h^2: over a flat stretch of the
    strip upstream of the bite (height = the entry half-thickness), uniform sizes (core factor 1,
    no grading) give (x1 - x0) h0/2 / (sqrt3/4 h^2) triangles."""
    import math

    from hotroll.model.geometry import RollPass
    from hotroll.workflows.estimate import triangles

    rp = RollPass(0.3, 0.01, 0.008, 10.0, axis_x=0.0)
    h, x0, x1 = 0.002, -0.5, -0.3                      # well before x_touch (-0.077 m)
    n = triangles(rp, h, h, x0, x1, x0, x1, 1.0, 0.0)
    assert n == pytest.approx((x1 - x0) * 0.01 / (math.sqrt(3.0) / 4.0 * h * h), rel=1e-12)


@pytest.mark.parametrize("method", ["steady", "transient"])
def test_the_estimate_does_not_depend_on_where_the_roll_axis_is(method):
    """The frame's invariance: the same pass with its roll axis at x = -3, 0 or 1.7 m has the
    same estimated mesh (the triangle density integrated over the strip moves with the roll),
    to the integer the count is rounded to."""
    import tomllib

    from hotroll.config.case import case_from_dict
    from hotroll.examples import example_path
    from hotroll.workflows import estimate as E

    with open(example_path("example1"), "rb") as fh:
        d = tomllib.load(fh)
    d.setdefault("solver", {})["method"] = method
    tri = []
    for x in (-3.0, 0.0, 1.7):
        d["pass"]["roll_axis_x"] = x
        tri.append(E.estimate(case_from_dict(d)).triangles)
    assert abs(tri[0] - tri[1]) <= 1 and abs(tri[2] - tri[1]) <= 1


def test_the_report_schemes_time_is_steps_times_its_cost_per_unknown():
    """The transient estimate: (end time / dt) steps, each STEP_SECONDS_PER_DOF per unknown."""
    import tomllib

    from hotroll.config.case import case_from_dict
    from hotroll.examples import example_path
    from hotroll.workflows import estimate as E

    with open(example_path("example1"), "rb") as fh:
        d = tomllib.load(fh)
    d.setdefault("solver", {}).update(method="transient", end_time=0.5)
    case = case_from_dict(d)
    est = E.estimate(case)
    # (est.dofs is the count rounded down to an integer: 1e-4 relative at most here)
    assert est.dofs > 1e4
    assert est.seconds == pytest.approx(0.5 / case.dt * E.STEP_SECONDS_PER_DOF * est.dofs,
                                        rel=1e-4)
