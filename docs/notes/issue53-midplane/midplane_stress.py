"""Where the 3D strip's mid-width stress leaves plane strain's (issue 53, the check "stresses on
the mid-width plane at W/h0 >= 8 within 1 % of 2D"): the roughing pass of
scripts/spread_3d_roughing.py (R 0.6 m, 200 -> 170 mm, C45, coarse grading) at a half width;
the stress's L2 deviation (spread_checks.midplane_stress_deviation's measure) split into ahead
of the bite, the bite and after it, per component; sigma_xx on the outlet face across the
width. One JSON line appended to OUT, the fields to OUT.npz.

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

import ngsolve as ng  # noqa: E402
import numpy as np  # noqa: E402
from bench_3d import SIZES, two_d  # noqa: E402

from hotroll.fem.reproducible import fe_space, integrate  # noqa: E402
from hotroll.solvers.spread_3d import Spread3D  # noqa: E402
from hotroll.solvers.spread_checks import _stress  # noqa: E402
from hotroll.solvers.spread_contact import plane_contact  # noqa: E402
from hotroll.solvers.threads import solver_threads  # noqa: E402

NAMES = ("xx", "yy", "zz", "xy")


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
        mesh2 = run.mesh
        V2, V3 = fe_space(ng.H1, mesh2, order=2), fe_space(ng.H1, s3.mesh, order=2)
        g2, g3, mid = ng.GridFunction(V2), ng.GridFunction(V3), ng.GridFunction(V2)
        two = plane_contact(run)
        xs, xe = float(np.min(two["x"])), float(np.max(two["x"]))
        regions = {"ahead": ng.IfPos(xs - ng.x, 1.0, 0.0),
                   "bite": ng.IfPos(ng.x - xs, 1.0, 0.0) * ng.IfPos(xe - ng.x, 1.0, 0.0),
                   "after": ng.IfPos(ng.x - xe, 1.0, 0.0)}
        diff, norm, fields = {}, {}, {}
        P = np.asarray(mesh2.ngmesh.Coordinates())[:, :2]
        d = run.disp.vec.FV().NumPy()
        n = d.size // 2
        nv = mesh2.nv
        fields["x"] = P[:, 0] + d[:nv]
        fields["y"] = P[:, 1] + d[n:n + nv]
        out_face = s3.mesh.Boundaries("out")
        for w, name, c2, c3 in zip((1.0, 1.0, 1.0, 2.0), NAMES, _stress(run.form, True),
                                   _stress(s3.form, False)):
            g2.Set(c2)
            g3.Set(c3)
            mid.vec[:] = 0.0
            s3.copy.take(0, V3, g3.vec.FV().NumPy(), V2, mid.vec.FV().NumPy())
            fields[f"s2_{name}"] = K * g2.vec.FV().NumPy()[:nv].copy()
            fields[f"s3_{name}"] = K * mid.vec.FV().NumPy()[:nv].copy()
            for part, chi in regions.items():
                diff[(part, name)] = w * integrate(chi * (mid - g2) ** 2, mesh2, ng.VOL)
                norm[(part, name)] = w * integrate(chi * g2 ** 2, mesh2, ng.VOL)
            if name == "xx":      # the outlet face: sigma_xx's mean and its RMS over the face
                area = integrate(ng.CF(1.0), s3.mesh, ng.BND, definedon=out_face)
                mean = integrate(g3, s3.mesh, ng.BND, definedon=out_face) / area
                rms = np.sqrt(integrate(g3 ** 2, s3.mesh, ng.BND, definedon=out_face) / area)
                X3 = np.asarray(s3.mesh.ngmesh.Coordinates())
                fields["s3_xx_3d"] = K * g3.vec.FV().NumPy()[:len(X3)].copy()
                fields["X3"] = X3
    whole = sum(norm.values())
    rows = {f"{p}_{c}": float(np.sqrt(diff[(p, c)] / whole)) for (p, c) in diff}
    parts = {p: float(np.sqrt(sum(diff[(p, c)] for c in NAMES) / whole))
             for p in regions}
    own = {p: float(np.sqrt(sum(diff[(p, c)] for c in NAMES)
                            / sum(norm[(p, c)] for c in NAMES))) for p in regions}
    share = {p: float(sum(norm[(p, c)] for c in NAMES) / whole) for p in regions}
    res = dict(half=a.half, wall=wall, dofs=fig["dofs"], spread=fig["spread"],
               x_start=xs, x_end=xe, K=K,
               whole=fig["midplane_stress_l2_deviation"],
               bite=fig["midplane_bite_stress_l2_deviation"],
               contact_l2=fig["midplane_contact_pressure_l2_deviation"],
               parts_over_whole=parts, parts_over_own=own, norm_share=share,
               components_over_whole=rows, out_sxx_mean=K * mean, out_sxx_rms=K * rms)
    print(json.dumps(res))
    with a.out.open("a") as fh:
        fh.write(json.dumps(res) + "\n")
    np.savez(str(a.out) + f".{a.half}.npz", **fields)


if __name__ == "__main__":
    main()
