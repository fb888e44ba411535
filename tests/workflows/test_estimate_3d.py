"""The pre-run estimate of the [spread] 3D pass (hotroll/workflows/estimate.py): its memory
and seconds laws against the six benchmark runs they were fitted to
(benchmarks/bench_3d.py, docs/validation/spread_3d.md "The roughing pass").

[snap] The measured figures below are earlier runs' (a snapshot), not an independent
reference: the test guards the fitted constants against a slip (a constant scaled by 1.1
leaves its band), not the estimate's truth for other cases."""
from __future__ import annotations

import pytest

from hotroll.workflows import estimate as E

#: (3D unknowns, 3D set-up + solve s, peak resident GB of the process): the narrow bar's
#: coarse, medium, fine (the ends moving from the first round) and the roughing pass's
#: coarsest, coarse, medium (c47ee5e-ac7ef0e)
RUNS = [(18075, 10.9, 0.35), (32399, 24.5, 0.73), (46723, 49.3, 1.20),
        (68613, 198.6, 1.72), (100817, 531.7, 3.27), (173276, 1907.1, 6.92)]
#: the process's own peak before the 3D pass (the fit's constant)
BASE_GB = 0.137


@pytest.mark.parametrize("dofs, seconds, gb", RUNS)
def test_the_3d_fits_reproduce_the_benchmark_runs(dofs, seconds, gb):
    """Memory within 10 % of each run (measured 0.94-1.09), seconds within 0.69-1.52 x
    (the roughing pass takes more Newton iterations per unknown than the bar)."""
    memory = BASE_GB * 1024**3 + E.BYTES_3D_COEF * dofs**E.BYTES_3D_EXP
    assert memory / (gb * 1024**3) == pytest.approx(1.0, abs=0.10)
    assert 0.69 <= E.SECONDS_3D_COEF * dofs**E.SECONDS_3D_EXP / seconds <= 1.52
