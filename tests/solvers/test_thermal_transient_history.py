"""history.csv of the report's transient scheme with a temperature carried along
(solvers/thermal_lagrangian.py): every step's row has the carried field's Newton iterations
(at least one: each implicit step solves once; none in the entry state's row, step 0) and
its unknowns (the plate's vertices, as in thermal.npz); the adiabatic pass of
tests/solvers/test_thermal_transient.py."""
from __future__ import annotations

import csv

import numpy as np

from tests.solvers.test_thermal_transient import adiabatic_run  # noqa: F401 (the fixture)


def test_every_step_records_the_thermal_iterations_and_unknowns(adiabatic_run):  # noqa: F811
    _, out = adiabatic_run
    with open(out / "history.csv") as fh:
        rows = list(csv.DictReader(fh))
    with np.load(out / "thermal.npz") as f:
        n = len(f["temperature"])
    assert len(rows) > 10
    iterations = {int(r["step"]): int(float(r["thermal_iterations"])) for r in rows}
    assert iterations[0] == 0                      # the entry state: nothing solved yet
    assert all(it >= 1 for step, it in iterations.items() if step > 0)
    assert {int(float(r["thermal_dofs"])) for r in rows} == {n}
