"""The ``[spread]`` section's 3D pass (issue 53): after the plane-strain pass, the same pass on
the 3D quarter strip across the case's width (``solvers/spread_3d.py``), its record for the
results (``model/spread_result.py``)."""
from __future__ import annotations

from hotroll.config.case import Case
from hotroll.config.spread import entry_section
from hotroll.fem.mirror import world
from hotroll.model.spread_result import SpreadResult
from hotroll.solvers.spread_3d import Spread3D
from hotroll.solvers.spread_record import spread_record


def solve_spread(case: Case, run, progress=None) -> SpreadResult:
    """The 3D pass of the solved half-strip ``SteadyRun`` ``run`` over ``case.pass_.width``,
    its width layers, edge zone and rounds from ``case.spread``; ``progress`` gets a report
    per round. Started by ``mpiexec -n N`` (``fem/mirror.world``), its flow solve runs over
    the ranks (``solvers/spread_mpi.py``)."""
    half = 0.5 * case.pass_.width
    edge, growth, largest = case.spread.layers(half, case.mesh.h)
    s3 = Spread3D(run, half, edge=edge, growth=growth, largest=largest,
                  zone=case.spread.edge_zone and case.spread.modelled(half),
                  strain=case.spread.strain, entry_temperature=entry_section(case),
                  linear_solver=case.spread.linear_solver, comm=world())
    s3.solve(max_rounds=case.spread.max_rounds, progress=progress)
    return spread_record(s3)
