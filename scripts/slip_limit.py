"""The forward slip against slab theory in the thin-gap limit (issue 50 item 4).

A sequence of passes approaching l/h -> infinity (l = sqrt(R dh), h = (h0 + h1)/2) at a fixed
reduction, Coulomb mu = the bite angle alpha (so mu ~ h/l: the friction hill stays O(1), the
shear O(h/l) against k), Norton-Hoff K = 4e7 Pa s^m, m = 0.15, R = 0.4 m, U = 3 m/s; h0 from
l/h. Each pass: the steady FE (default settings, automatic mesh, rigid roll; bilateral and
unilateral contact) and the slab (Orowan) solution of the same law (``map_case``: the local
Norton-Hoff rate along the bite, Coulomb with the FE's rounded kinks). Printed and written as
markdown: f_FE, f_slab, their difference, the observed rate, the derived leading-order term
(``hotroll.theory.profile_slip_offset``) and bound, the neutral angles, and the slab with the
sharp Coulomb law (what the FE's rounding adds). ``--mesh-check``: f_FE at the finest l/h on
the automatic mesh and half of it.

    python scripts/slip_limit.py                       # -> results/slip_limit.md
    python scripts/slip_limit.py --lh 4,8,16 --contact bilateral --no-mesh-check
"""
from __future__ import annotations

import argparse
import math
import subprocess
import time
from pathlib import Path

from _common import list_arg

import hotroll
from hotroll.config.case import Case, case_from_dict
from hotroll.theory import Coulomb, profile_slip_offset, slip_error_bound, solve_pass
from hotroll.workflows.compare import map_case

R, U, TEMPERATURE = 0.4, 3.0, 1373.15
MATERIAL = {"law": "norton-hoff", "K": 4e7, "m": 0.15}


def thin_gap_case(lh: float, reduction: float = 0.3, mu_over_alpha: float = 1.0, *,
                  unilateral: bool = False, h_contact: str | float = "auto") -> Case:
    """The pass with sqrt(R dh)/h_mean = lh, dh/h0 = reduction, Coulomb mu = mu_over_alpha x
    the bite angle."""
    h0 = R * reduction / (lh ** 2 * (1.0 - reduction / 2.0) ** 2)
    h1 = h0 * (1.0 - reduction)
    alpha = math.acos(1.0 - (h0 - h1) / (2.0 * R))
    return case_from_dict({
        "name": f"thin_gap_lh{lh:g}",
        "pass": {"roll_radius": R, "entry_thickness": h0, "exit_thickness": h1,
                 "roll_angular_velocity": U / R},
        "plate": {"length": 4.0 * math.sqrt(R * (h0 - h1)), "temperature": TEMPERATURE},
        "material": dict(MATERIAL),
        "friction": {"law": "coulomb", "mu": mu_over_alpha * alpha},
        "contact": {"unilateral": unilateral},
        "mesh": {"h_contact": h_contact},
        "solver": {"method": "steady", "threads": 1},
        "output": {"figures": False, "vtk": False},
    })


def slab(case: Case, sharp: bool = False):
    s = map_case(case)
    friction = Coulomb(s.friction.mu) if sharp else s.friction
    return solve_pass(s.roll_radius, s.h0, s.h1, s.roll_speed, friction, s.flow_stress,
                      s.temperature)


def one(lh: float, args, unilateral: bool, h_contact="auto") -> dict:
    case = thin_gap_case(lh, args.reduction, args.mu_over_alpha, unilateral=unilateral,
                         h_contact=h_contact)
    sl, sharp = slab(case), slab(case, sharp=True)
    t0 = time.perf_counter()
    res = hotroll.solve(case)
    wall = time.perf_counter() - t0
    S = res.summary
    geo = (R, sl.neutral_thickness, sl.neutral_angle, sl.forward_slip)
    return {"lh": lh, "contact": "unilateral" if unilateral else "bilateral",
            "h_contact": case.mesh.h, "dofs": S["dofs"], "exit_code": S["exit_code"],
            "f_fe": S["forward_slip"], "f_slab": sl.forward_slip, "f_sharp": sharp.forward_slip,
            "diff": S["forward_slip"] - sl.forward_slip, "profile": profile_slip_offset(*geo),
            "bound": slip_error_bound(*geo), "phi_fe": S["neutral_angle"],
            "phi_slab": sl.neutral_angle, "mass_flux_error": S["mass_flux_error"], "wall": wall}


def rates(rows: list[dict]) -> None:
    for a, b in zip(rows, rows[1:]):
        b["rate"] = (math.log(abs(a["diff"]) / abs(b["diff"])) / math.log(b["lh"] / a["lh"])
                     if a["diff"] and b["diff"] else float("nan"))


HEAD = ("| l/h | contact | f FE % | f slab % | FE - slab | rate | profile term | bound | "
        "phi_n FE mrad | phi_n slab mrad | f slab sharp % | DOFs | FE s |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|")


def md_row(r: dict) -> str:
    rate = r.get("rate")
    return (f"| {r['lh']:g} | {r['contact']} | {100 * r['f_fe']:.4f} | {100 * r['f_slab']:.4f} | "
            f"{r['diff']:+.3e} | {'' if rate is None else f'{rate:.2f}'} | "
            f"{r['profile']:+.3e} | {r['bound']:.2e} | {1e3 * r['phi_fe']:.4f} | "
            f"{1e3 * r['phi_slab']:.4f} | {100 * r['f_sharp']:.4f} | {r['dofs']} | "
            f"{r['wall']:.1f} |")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--lh", type=list_arg(float), default=[2.0, 4.0, 8.0, 16.0, 32.0])
    p.add_argument("--reduction", type=float, default=0.3)
    p.add_argument("--mu-over-alpha", type=float, default=1.0)
    p.add_argument("--contact", choices=("both", "bilateral", "unilateral"), default="both")
    p.add_argument("--no-mesh-check", dest="mesh_check", action="store_false")
    p.add_argument("--out", default="results/slip_limit.md")
    args = p.parse_args()
    code = subprocess.run(["git", "rev-parse", "--short", "HEAD"], text=True,
                          capture_output=True, cwd=Path(__file__).parent).stdout.strip()
    kinds = {"both": (False, True), "bilateral": (False,), "unilateral": (True,)}[args.contact]
    lines = [f"# The forward slip in the thin-gap limit (hotroll {code})", "",
             f"reduction {args.reduction:g}, Coulomb mu = {args.mu_over_alpha:g} x bite angle, "
             "Norton-Hoff K = 4e7 Pa s^m, m = 0.15, R = 0.4 m, U = 3 m/s, rigid roll, steady "
             "FE on the automatic mesh. rate: -d ln|FE - slab| / d ln(l/h) (derived: 2). "
             "profile term: (1 + f)(h_n/(6R cos^3 phi_n) - (2/3) tan^2 phi_n). "
             "f slab sharp: the slab with Coulomb's kinks not rounded.", "", HEAD]
    for unilateral in kinds:
        rows = []
        for lh in args.lh:
            rows.append(one(lh, args, unilateral))
            rates(rows)
            print(md_row(rows[-1]), flush=True)
        lines += [md_row(r) for r in rows]
    if args.mesh_check:
        lh = max(args.lh)
        lines += ["", f"Mesh check at l/h = {lh:g} (bilateral): automatic mesh and half of it.",
                  "", HEAD]
        auto = thin_gap_case(lh, args.reduction, args.mu_over_alpha).mesh.h
        for h in (auto, auto / 2.0):
            r = one(lh, args, False, h_contact=h)
            print(md_row(r), flush=True)
            lines.append(md_row(r))
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("\n".join(lines) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
