"""``solver.max_iterations`` with the direct steady solver (issue 51 item 7): a value below 30
was raised to 30 without a word (``workflows/build.py: steady_settings``,
``max(sv.max_iterations, 30)``). Given, it is the limit of each Newton solve at a continuation
stage (the coupled solve at the target m adds 3 per a_f / free-surface update, ``max_outer``);
omitted, the steady solver keeps its own 30 and the report's scheme its 20 a step.
"""
from __future__ import annotations

import pytest
from casebuild import EXAMPLE1_COARSE, build_case, steady_run

from hotroll.workflows.build import steady_settings


@pytest.mark.parametrize("given", [1, 5, 29])
def test_a_limit_below_30_reaches_the_steady_solver(given):
    case = build_case(EXAMPLE1_COARSE, **{"solver.max_iterations": given})
    assert steady_settings(case).max_it == given


@pytest.mark.parametrize("given", [30, 45])
def test_a_limit_of_30_or_more_reaches_the_steady_solver(given):
    case = build_case(EXAMPLE1_COARSE, **{"solver.max_iterations": given})
    assert steady_settings(case).max_it == given


def test_the_newton_solves_stop_at_the_limit_given():
    """Example 1 on the coarse mesh needs more than 2 Newton iterations from the kinematic
    guess; with ``max_iterations = 2`` and no coupling rounds (``max_outer = 0``: the coupled
    solve's limit is then max_iterations itself) no solve of the run, the direct one nor the
    continuation stages after it, takes more than 2."""
    run = steady_run(build_case(EXAMPLE1_COARSE, **{"solver.max_iterations": 2}))
    run.record = False
    run.s.max_outer = 0
    res = run.solve()
    iterations = [st.iterations for st in res.stats]
    assert iterations and max(iterations) <= 2, iterations
    assert not res.stats[-1].converged         # 2 iterations do not solve it: the limit acts


def test_left_out_the_steady_solver_keeps_30_and_the_report_scheme_20():
    """Omitted, the limits stay what each solver needs: 30 a continuation stage (Example 1's
    direct solve takes 9 from the kinematic guess; the thin strip's 92 over its couplings), 20
    a time step (the report's Picard and Newton)."""
    from hotroll.workflows.build import build_model

    case = build_case(EXAMPLE1_COARSE)
    assert steady_settings(case).max_it == 30
    transient = build_case(EXAMPLE1_COARSE, **{"solver.method": "transient",
                                                 "contact.method": "penalty"})
    assert build_model(transient)[1].max_it == 20
