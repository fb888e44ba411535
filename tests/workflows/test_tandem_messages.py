"""The tension search's progress lines (workflows/tandem.py) on the log-linear mill of
tests/workflows/test_tandem.py (no FE): the first line gives the starting tensions in MPa and
the largest flux difference, here ln(1.025/1.01) = 1.474e-2 at zero tension (by hand)."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from hotroll.workflows.tandem import solve_tensions


def test_the_first_line_is_the_start_in_mpa_and_its_largest_flux_difference():
    a = np.log([1.0, 1.01, 1.025, 1.04])
    b, c = np.array([2.0, 2.5, 3.0, 3.5]) * 1e-9, np.array([3.0, 3.5, 4.0, 4.5]) * 1e-9
    sch = SimpleNamespace(
        passes=[SimpleNamespace(front_tension=0.0, back_tension=0.0) for _ in range(4)],
        mill=SimpleNamespace(flux_tolerance=1e-6), pass_name=lambda k: f"F{k + 1}")

    def roll(t, quiet):
        tt = np.r_[0.0, t, 0.0]
        out = [float(np.exp(a[k] - b[k] * tt[k] + c[k] * tt[k + 1])) for k in range(4)]
        return [{"mass_flux_out": q, "mass_flux": q, "mean_flow_stress": 1e8, "fe_solves": 1}
                for q in out], [{}] * 4

    said = []
    solve_tensions(sch, roll, None, said.append)
    assert said[0] == "tensions [0.000, 0.000, 0.000] MPa: largest flux difference 1.47e-02"
    assert len(said) >= 2 and all(s.startswith("tensions [") and "] MPa: " in s for s in said)
