"""Run by ``test_spread_3d.py`` under ``mpiexec -n 3``: the free pass of its ``solved`` fixture
(Case R's coarse 2D pass, the stock 10 mm wide, the edge layer 2.5 mm) with its flow solve over
the ranks (``solvers/spread_mpi.py``); rank 0 prints the figures (JSON), every rank a digest of
its velocity vector (the ranks must agree bitwise). Not a test module (no ``test_`` prefix)."""
from __future__ import annotations

import hashlib
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from test_full_strip import _setup  # noqa: E402

from hotroll.fem.mirror import abort_on_error, world  # noqa: E402
from hotroll.solvers.spread_3d import Spread3D  # noqa: E402
from hotroll.solvers.steady import SteadyRun  # noqa: E402

B0 = 0.005


def main() -> None:
    comm = world()
    abort_on_error(comm)
    case, problem, st = _setup()
    run = SteadyRun(problem, st, case.plate.length)
    assert run.run().status == "steady"
    s3 = Spread3D(run, B0, edge=0.5 * B0, comm=comm)
    s3.solve()
    fig = {k: v for k, v in s3.figures().items() if isinstance(v, (bool, int, float))}
    u = s3.form.nonlinear.gf.vec.FV().NumPy()
    digests = comm.gather(hashlib.sha256(u.tobytes()).hexdigest())
    if comm.rank == 0:
        fig["ranks_agree"] = len(set(digests)) == 1
        fig["ranks"] = comm.size
        print("FIGURES " + json.dumps(fig), flush=True)


if __name__ == "__main__":
    main()
