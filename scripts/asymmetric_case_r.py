"""Case R of ../shared/notes/asymmetric-rolling.md through the full-thickness strip: the FE
against the slab closed form (theory/asymmetric.py) over speed ratios and meshes, and the
exit curvature's well-posedness checks (outlet distance, v_reg, eps0). One JSON line a run
(appended to OUT, resumed: a run already in OUT is skipped).

    python scripts/asymmetric_case_r.py OUT [--m 0.05] [--h 1e-3,6.67e-4] [--ratios 1,1.02]
        [--checks] [--h0 0.01 --h1 0.008]
"""
from __future__ import annotations

import argparse
import json
import math
import time
from dataclasses import replace
from pathlib import Path

from hotroll.config.case import load_case
from hotroll.solvers.full_steady import FullSteadyRun
from hotroll.solvers.steady import SteadyRun
from hotroll.theory.asymmetric import tresca_closed_form
from hotroll.workflows.build import build_model, steady_settings

R, H0, H1, MF = 0.25, 0.01, 0.008, 0.3     # Case R; --h0/--h1: another pass of the same roll


def case_r(m: float, h: float, exit_length: float | None = None, friction: float = MF):
    over = {"pass.roll_radius": R, "pass.entry_thickness": H0, "pass.exit_thickness": H1,
            "pass.roll_angular_velocity": 4.0, "material.m": m, "friction.law": "tresca",
            "friction.factor": friction, "friction.a_f": None, "mesh.h_contact": h,
            "solver.method": "steady", "plate.length": 0.2}
    if exit_length:
        over["solver.steady_exit_length"] = exit_length
    case = load_case(Path(__file__).resolve().parents[1] / "hotroll/examples/cases/example1.toml",
                     over)
    problem, _ = build_model(case)
    return case, problem, steady_settings(case)


def run(m, h, ratio, check="", exit_length=None):
    case, problem, st = case_r(m, h, exit_length)
    if check == "v_reg/2":
        problem = replace(problem, friction=replace(problem.friction,
                                                    v_reg=0.5 * problem.friction.v_reg))
    if check == "eps0/10":
        problem = replace(problem, material=replace(problem.material,
                                                    eps0=0.1 * problem.material.eps0))
    rp = problem.rp
    t0 = time.perf_counter()
    if ratio is None:
        half = SteadyRun(problem, st, case.plate.length)
        sol = half.run()
        row = sol.history[-1]
        return {"model": "half", "status": sol.status, "wall_s": time.perf_counter() - t0,
                "roll_force": row["roll_force"], "roll_torque": row["roll_torque"],
                "forward_slip": row["forward_slip"]}
    rolls = {1: replace(rp, omega=rp.omega * ratio), -1: rp}
    full = FullSteadyRun(problem, st, case.plate.length, rolls,
                         {1: problem.friction, -1: problem.friction})
    sol = full.run()
    row = sol.history[-1]
    out = {k: v for k, v in row.items() if isinstance(v, (int, float)) and math.isfinite(v)}
    out.update({"model": "full", "status": sol.status, "wall_s": time.perf_counter() - t0,
                "dofs": full.form.fes.ndof})
    return out


def slab(ratio):
    s = tresca_closed_form(h0=H0, h1=H1, k=1.0, R1=R, R2=R, U1=ratio, U2=1.0, m1=MF, m2=MF)
    return {"x_n1/L": s.x_n1 / s.contact_length, "x_n2/L": s.x_n2 / s.contact_length,
            "force": s.force, "torque1": s.torque1, "torque2": s.torque2}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("out", type=Path)
    ap.add_argument("--m", type=float, default=0.05)
    ap.add_argument("--h", default="1e-3,6.67e-4")
    ap.add_argument("--ratios", default="1,1.01,1.02,1.05,1.1,1.2")
    ap.add_argument("--checks", action="store_true")
    ap.add_argument("--h0", type=float, default=H0, help="entry thickness, m")
    ap.add_argument("--h1", type=float, default=H1, help="exit thickness, m")
    a = ap.parse_args()
    globals().update(H0=a.h0, H1=a.h1)
    done = set()
    if a.out.exists():
        done = {json.loads(line)["key"] for line in a.out.read_text().splitlines() if line}
    jobs = []
    for h in (float(v) for v in a.h.split(",")):
        jobs.append((h, None, "", None))
        jobs += [(h, float(r), "", None) for r in a.ratios.split(",")]
    if a.checks:
        h = float(a.h.split(",")[0])
        for r in (1.005, 1.01, 1.02):
            jobs.append((h, r, "", None))
            jobs.append((h, r, "outlet x3", 3 * math.sqrt(R * (H0 - H1))))
            jobs.append((h, r, "v_reg/2", None))
            jobs.append((h, r, "eps0/10", None))
    for h, r, check, exit_length in jobs:
        key = f"h0={H0:g} h1={H1:g} m={a.m} h={h:g} r={r} {check}".strip()
        if key in done:
            continue
        row = run(a.m, h, r, check, exit_length)
        row.update({"key": key, "m": a.m, "h": h, "ratio": r, "check": check, "h0": H0,
                    "h1": H1})
        if r is not None:
            row["slab"] = slab(r)
        with a.out.open("a") as f:
            f.write(json.dumps(row) + "\n")
        print(key, row["status"], f"{row['wall_s']:.1f} s", flush=True)


if __name__ == "__main__":
    main()
