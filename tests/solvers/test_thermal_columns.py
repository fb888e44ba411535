"""The thermal strip's column values (solvers/thermal_coupling.py ``_column_values``: the P2
fields' nodal interpolants at the columns' points, spaces.P2PointValues) against NGSolve's own
evaluation of the current positions and the velocity on the deformed mechanics mesh."""
from __future__ import annotations

import numpy as np
from casebuild import solved_steady_run


def test_column_positions_and_velocities_are_ngsolves():
    from ngsolve import CF, x, y

    run = solved_steady_run("thermal_pass")
    th = run.thermal
    # the traced tops moved the mesh: the positions carry a displacement to check
    assert np.max(np.abs(run.d)) > 1e-6 * run.problem.rp.half_exit
    u = run.form.nonlinear.velocity
    theirs = th._at(CF((x, y, u[0], u[1])), th._col_pts).reshape(len(th._fine),
                                                                  len(th.strip.X), 4)
    ours = th._column_values()
    scale = np.max(np.abs(theirs.reshape(-1, 4)), axis=0)
    assert np.all(np.max(np.abs(ours - theirs).reshape(-1, 4), axis=0) <= 1e-12 * scale)
    # ... and the displacement's own part: positions minus the reference points
    moved = theirs[..., :2].reshape(-1, 2) - th._col_ref
    assert np.max(np.abs(moved)) > 1e-9 * scale[0]
    assert np.max(np.abs(ours[..., :2].reshape(-1, 2) - th._col_ref - moved)) <= (
        1e-6 * np.max(np.abs(moved)))
