"""The roughing pass of benchmarks/bench_3d.py (the bundled roughing_slab: R = 0.6 m, 200 -> 170
mm, C45) across a wide strip, its coarse width grading: the mid-width against plane strain
(the contact pressure's RMS deviation at the same x, the force per width) and the edge zone
(issue 53, docs/validation/spread_3d.md "The mid-width against plane strain"). One JSON line
a run appended to OUT.

    python scripts/spread_3d_roughing.py OUT [--half 0.8] [--zone 0.3] [--levels L.npz]
        [--corner 1]
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

import numpy as np  # noqa: E402
from bench_3d import SIZES, two_d  # noqa: E402

from hotroll.solvers.spread_3d import Spread3D  # noqa: E402
from hotroll.solvers.spread_contact import level_contact, plane_contact  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("out", type=Path)
    ap.add_argument("--half", type=float, default=0.8, help="the half width (m)")
    ap.add_argument("--zone", type=float, default=None, help="the edge zone (m; omit: all)")
    ap.add_argument("--levels", type=Path, default=None,
                    help="also write the contact per width level and the 2D pass's (.npz)")
    ap.add_argument("--corner", type=float, default=16.0,
                    help="mesh.corner_refinement of the 2D mesh (default 16 as a case's; 1: none)")
    a = ap.parse_args()
    run, _, _, _ = two_d("roughing", a.corner)
    h = run.problem.h
    edge, largest = SIZES["coarse"]
    t0 = time.perf_counter()
    s3 = Spread3D(run, a.half, edge=edge * h, largest=largest * h, zone=a.zone)
    s3.solve(progress=lambda r: print(r["message"], flush=True))
    f = s3.figures()
    f.pop("exit_half_width_profile", None)
    if a.levels is not None:         # x, z (m) and the traction over K per level; the 2D's
        two, lev = plane_contact(run), level_contact(s3)
        np.savez(a.levels, x2=two["x"], c2=two["traction"], x3=lev["x"], z=lev["z"],
                 c3=lev["traction"], K=run.problem.material.K)
    rp = run.problem.rp
    f.update(plane_strain_force=run.state.history[-1]["roll_force"],
             wall=time.perf_counter() - t0, half=a.half, zone=a.zone, l_c=rp.contact_length,
             corner=a.corner,
             ends=None if s3.ends is None else s3.ends.ends().tolist())
    print(json.dumps(f))
    with a.out.open("a") as fh:
        fh.write(json.dumps(f) + "\n")


if __name__ == "__main__":
    main()
