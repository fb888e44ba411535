"""The typed stages (hotroll/solvers/problem.py): both solvers implement the ``Solver``
interface that the results layer reads, and their ``run`` returns a ``Solution``. Plumbing: a
guard that the two stay interchangeable for ``solvers/record.py``, which makes the
``Solution`` record that ``results/run_summary.py`` reads."""
from __future__ import annotations

import typing

import pytest
from casebuild import EXAMPLE1_COARSE, build_case

from hotroll.solvers.problem import Problem, Solution, Solver
from hotroll.solvers.steady import SteadyRun
from hotroll.solvers.transient import TransientRun
from hotroll.workflows.runner import build_model, steady_settings

MEMBERS = [n for n in typing.get_type_hints(Solver) if not n.startswith("_")] + ["run", "head_x", "solution_record"]


@pytest.mark.parametrize("method", ["steady", "transient"])
def test_both_solvers_implement_the_solver_interface(method, tmp_path):
    case = build_case(EXAMPLE1_COARSE, **{"solver.method": method, "solver.max_steps": 3})
    problem, settings = build_model(case)
    assert isinstance(problem, Problem)
    if method == "steady":
        run = SteadyRun(problem, steady_settings(case), case.plate.length)
    else:
        run = TransientRun(problem, settings, checkpoint_dir=tmp_path / "ckpt")
    assert run.time_stepping is (method == "transient")
    solution = run.run()
    assert isinstance(solution, Solution) and solution is run.state
    assert solution.history and solution.status in ("steady", "unsettled", "max_steps")
    missing = [m for m in MEMBERS if not hasattr(run, m)]
    assert not missing, f"{type(run).__name__} lacks {missing}"
    assert run.problem is problem


def test_the_case_mesh_reaches_the_problem():
    """mesh.h_contact, h_far and grading of the case are the problem's mesh spec (h_far given:
    the far size is the user's, not the automatic one)."""
    case = build_case(EXAMPLE1_COARSE, **{"mesh.h_far": 0.03, "mesh.grading": 0.4})
    spec = build_model(case)[0].mesh
    assert (spec.h, spec.h_far, spec.grading) == (0.02, 0.03, 0.4)
    assert spec.far(case.pass_.roll_pass()) == 0.03
    auto = build_model(build_case(EXAMPLE1_COARSE))[0].mesh
    assert auto.h_far is None and auto.far(case.pass_.roll_pass()) != 0.03
