"""Where the 3D strip's mid-width stress leaves plane strain's (issue 53, the check "stresses on
the mid-width plane at W/h0 >= 8 within 1 % of 2D"): the roughing pass of
scripts/spread_3d_roughing.py (R 0.6 m, 200 -> 170 mm, C45, coarse grading) at a half width;
the stress's L2 deviation (spread_checks.midplane_stress_parts) split into ahead of the bite,
the bite and after it, per component. One JSON line appended to OUT, the fields to OUT.npz.

    python docs/notes/issue53-midplane/midplane_stress.py OUT --half 0.8
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "benchmarks"))

import numpy as np  # noqa: E402
from bench_3d import SIZES, two_d  # noqa: E402

from hotroll.solvers.spread_3d import Spread3D  # noqa: E402
from hotroll.solvers.spread_checks import (  # noqa: E402
    STRESS_COMPONENTS,
    bite_regions,
    midplane_stress_parts,
)
from hotroll.solvers.threads import solver_threads  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("out", type=Path)
    ap.add_argument("--half", type=float, default=0.8)
    a = ap.parse_args()
    with solver_threads("auto"):
        run, _, _, _ = two_d("roughing")
        h = run.problem.h
        edge, largest = SIZES["coarse"]
        t0 = time.perf_counter()
        s3 = Spread3D(run, a.half, edge=edge * h, largest=largest * h)
        s3.solve(progress=lambda r: print(r["message"], flush=True))
        wall = time.perf_counter() - t0
        fig = s3.figures()
        K = run.problem.material.K
        regions = bite_regions(s3)
        stress = {}
        diff, norm = midplane_stress_parts(s3, regions, stress)
        nv = run.mesh.nv
        P = np.asarray(run.mesh.ngmesh.Coordinates())[:, :2]
        d = run.disp.vec.FV().NumPy()
        fields = {"x": P[:, 0] + d[:nv], "y": P[:, 1] + d[d.size // 2:d.size // 2 + nv]}
        for name, (v2, v3) in stress.items():     # the vertex values (Pa)
            fields[f"s2_{name}"], fields[f"s3_{name}"] = K * v2[:nv], K * v3[:nv]
    names = [n for n, _ in STRESS_COMPONENTS]
    whole = sum(norm.values())
    rows = {f"{p}_{c}": float(np.sqrt(diff[p, c] / whole)) for (p, c) in diff}
    parts = {p: float(np.sqrt(sum(diff[p, c] for c in names) / whole)) for p in regions}
    own = {p: float(np.sqrt(sum(diff[p, c] for c in names) / sum(norm[p, c] for c in names)))
           for p in regions}
    share = {p: float(sum(norm[p, c] for c in names) / whole) for p in regions}
    res = dict(half=a.half, wall=wall, dofs=fig["dofs"], spread=fig["spread"], K=K,
               whole=fig["midplane_stress_l2_deviation"],
               bite=fig["midplane_bite_stress_l2_deviation"],
               contact_l2=fig["midplane_contact_pressure_l2_deviation"],
               parts_over_whole=parts, parts_over_own=own, norm_share=share,
               components_over_whole=rows)
    print(json.dumps(res))
    with a.out.open("a") as fh:
        fh.write(json.dumps(res) + "\n")
    np.savez(str(a.out) + f".{a.half}.npz", **fields)


if __name__ == "__main__":
    main()
