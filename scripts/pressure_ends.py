"""The contact pressure's ends under refinement (issue 50, docs/validation/contact.md): a pass on
three contact meshes (h, h/2, h/4); per mesh the entry corner's nodal pressure, the next two
vertices', ``entry_pressure`` (the mean over the first 5 % of the contact), the largest vertex
dip over the peak, for the nodal traction (``normal_stress``) and the multiplier's own values
(``normal_stress_multiplier``), the contact's end and its pressure.

    python scripts/pressure_ends.py                       # the issue's lab pass
    python scripts/pressure_ends.py --case hot_strip_finishing --h 0.0005
"""
from __future__ import annotations

import argparse
import sys

import numpy as np

#: the issue's lab pass: S355J2 at 1000 degC, 10 -> 7.5 mm, R 0.1 m, 1 m/s, Coulomb 0.3
LAB = {"pass.roll_radius": 0.1, "pass.entry_thickness": 0.010, "pass.exit_thickness": 0.0075,
       "pass.roll_angular_velocity": 10.0}


def dip(p: np.ndarray) -> float:
    d = np.minimum(p[:-2], p[2:]) - p[1:-1]
    return float(max(d.max(initial=0.0), 0.0) / p.max())


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--case", default="hot_strip_finishing")
    ap.add_argument("--h", type=float, default=0.000625, help="the coarsest contact mesh (m)")
    ap.add_argument("--lab", action=argparse.BooleanOptionalAction, default=None,
                    help="the lab pass's geometry (default: with hot_strip_finishing)")
    args = ap.parse_args(argv)
    import hotroll

    lab = args.case == "hot_strip_finishing" if args.lab is None else args.lab
    print("h_mm corner_MPa v1_MPa v2_MPa entry_MPa dip_nodal dip_multiplier m end_kind")
    for k in range(3):
        h = args.h / 2**k
        over = {**(LAB if lab else {}), "mesh.h_contact": h, "output.figures": False,
                "output.vtk": False}
        res = hotroll.solve(hotroll.example_case(args.case).with_overrides(**over))
        c, s = res.contact, res.summary
        v = np.asarray(c["vertex"]) == 1
        x = np.asarray(c["x"])[v]
        order = np.argsort(x)
        p = -np.asarray(c["normal_stress"])[v][order] / 1e6
        q = -np.asarray(c["normal_stress_multiplier"])[v][order] / 1e6
        print(f"{h * 1e3:.4f} {p[0]:.1f} {p[1]:.1f} {p[2]:.1f} {s['entry_pressure'] / 1e6:.1f} "
              f"{dip(p):.4f} {dip(q):.4f} {s['m']:.4f} {s['contact_end_kind']}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
