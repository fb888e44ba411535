"""The 3D strip's spread (issue 53 stage 2, solvers/spread_3d.py) on Case R's geometry (R = 250
mm, 10 -> 8 mm, Tresca 0.3, Norton-Hoff m = 0.05) against the empirical formulas of Hill,
Sparling and Wusatowski (theory/spread.py, PyRolL's plugins, correction factors 1), over the
stock's width b0/h0 and two width gradings. One JSON line a run (appended to OUT, resumed: a
run already in OUT is skipped); a markdown table of OUT at the end.

    python scripts/spread_3d_study.py OUT [--ratios 0.5,1,2] [--h 1e-3]
        [--gradings coarse,fine]
    python scripts/spread_3d_study.py OUT --ratios 2,4,8,16 --gradings coarse   # the 1/W limit
    python scripts/spread_3d_study.py OUT --ratios 8 --gradings coarse --zones 2,3,none
        [--interior 1]
        # the edge zone (its width in h0; none: the whole half width): moving the cut;
        # --interior: its interior's width layers (generalized plane strain)
    python scripts/spread_3d_study.py OUT --ratios 8 --gradings coarse --friction 0.8
        # a rougher pass (the Tresca factor; default Case R's 0.3)

Gradings: ``coarse`` the edge layer h thick, x1.2 inwards up to 4h; ``fine`` h/2, up to 2h.
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from asymmetric_case_r import H0, H1, MF, R, case_r

from hotroll.solvers.spread_3d import Spread3D
from hotroll.solvers.steady import SteadyRun
from hotroll.theory.spread import hill, sparling, wusatowski

GRADINGS = {"coarse": (1.0, 4.0), "fine": (0.5, 2.0)}     # (edge, largest) in h


def one(ratio: float, h: float, grading: str, two_d: dict, zone: float | None = None,
        friction: float = MF, interior: int = 1) -> dict:
    b0 = ratio * H0
    edge, largest = GRADINGS[grading]
    run = two_d["run"]
    t0 = time.perf_counter()
    s3 = Spread3D(run, 0.5 * b0, edge=min(edge * h, 0.5 * b0), largest=largest * h,
                  zone=None if zone is None else min(zone * H0, 0.5 * b0),
                  interior_layers=interior)
    s3.solve()
    fig = s3.figures()
    fig.pop("exit_half_width_profile", None)
    return {"b0_over_h0": ratio, "h": h, "grading": grading, "zone_h0": zone,
            "interior_layers": interior if zone is not None else 0,
            "friction": friction, "layers": len(s3.z) - 1,
            "wall": time.perf_counter() - t0, "plane_strain_force": two_d["force"],
            "hill": hill(b0, H0, H1, R) - b0, "sparling": sparling(b0, H0, H1, R) - b0,
            "wusatowski": wusatowski(b0, H0, H1, R) - b0, **fig}


def table(rows: list[dict]) -> str:
    out = ["| b0/h0 | Tresca | grading | zone h0 | layers | DOFs | spread mm | Hill | Sparling | Wusatowski | "
           "inside | force/width / plane strain | (out-in)/in | cut/mid-width p RMS | "
           "cut/mid-width contact p RMS | Newton its | rounds | wall s |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lo, hi = (min(r[k] for k in ("hill", "sparling", "wusatowski")),
                  max(r[k] for k in ("hill", "sparling", "wusatowski")))
        out.append(
            f"| {r['b0_over_h0']:g} | {r.get('friction', MF):g} | {r['grading']} | {r.get('zone_h0') or 'all'} | "
            f"{r['layers']} | {r['dofs']} | "
            f"{r['spread'] * 1e3:.3f} | {r['hill'] * 1e3:.3f} | {r['sparling'] * 1e3:.3f} | "
            f"{r['wusatowski'] * 1e3:.3f} | {'yes' if lo <= r['spread'] <= hi else 'no'} | "
            f"{r['roll_force_per_width'] / r['plane_strain_force']:.4f} | "
            f"{(r['flux_out'] + r.get('flux_edge', 0.0) - r['flux_in']) / r['flux_in']:.1e} | "
            f"{r.get('midplane_pressure_rms_deviation', float('nan')):.2e} | "
            f"{r.get('midplane_contact_pressure_rms_deviation', float('nan')):.2e} | "
            f"{r['newton_iterations']} | "
            f"{r['rounds']} | {r['wall']:.0f} |")
    return "\n".join(out)


def plane_strain_limit(rows: list[dict], grading: str = "coarse") -> str:
    """The force per width against h0/b0 (1/W) over the runs with b0/h0 >= 2 of ``grading``,
    a straight line extrapolated to an infinitely wide strip, against the 2D pass; and the
    mid-width plane's deviation from the 2D pass at each width."""
    import numpy as np

    pts = sorted((1.0 / r["b0_over_h0"], r["roll_force_per_width"] / r["plane_strain_force"],
                  r.get("midplane_pressure_deviation"), r["b0_over_h0"],
                  r.get("midplane_pressure_rms_deviation"))
                 for r in rows if r["grading"] == grading and r["b0_over_h0"] >= 2.0
                 and r.get("zone_h0") is None and r.get("friction", MF) == MF)
    if len(pts) < 2:
        return "(1/W: fewer than two widths with b0/h0 >= 2)"
    x, y = np.array([p[0] for p in pts]), np.array([p[1] for p in pts])
    slope, intercept = np.polyfit(x, y, 1)
    lines = [f"force per width / plane strain = {intercept:.5f} + {slope:.4f} h0/b0 "
             f"(fit over b0/h0 = {', '.join(f'{p[3]:g}' for p in pts)}): the wide limit is "
             f"{intercept:.5f} of the 2D pass's"]
    for p in pts:
        if p[2] is not None:
            rms = "" if p[4] is None else f", root mean square {p[4]:.2e} of the 2D's"
            lines.append(f"b0/h0 = {p[3]:g}: mid-width pressure {p[2]:.2e} of its peak off the "
                         f"2D{rms}")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("out", type=Path)
    ap.add_argument("--ratios", default="0.5,1,2")
    ap.add_argument("--h", type=float, default=1e-3)
    ap.add_argument("--gradings", default="coarse,fine")
    ap.add_argument("--friction", type=float, default=MF, help="the Tresca factor")
    ap.add_argument("--zones", default="none", help="edge zones in h0, comma separated "
                    "(none: the whole half width)")
    ap.add_argument("--interior", type=int, default=1,
                    help="an edge zone's interior: width layers in generalized plane strain")
    a = ap.parse_args()
    zones = [None if z == "none" else float(z) for z in a.zones.split(",")]
    done = set()
    if a.out.exists():
        for line in a.out.read_text().splitlines():
            r = json.loads(line)
            done.add((r["b0_over_h0"], r["h"], r["grading"], r.get("zone_h0"),
                      r.get("friction", MF), r.get("interior_layers", 1)))
    case, problem, st = case_r(0.05, a.h, friction=a.friction)
    run = SteadyRun(problem, st, case.plate.length)
    assert run.run().status == "steady"
    two_d = {"run": run, "force": run.state.history[-1]["roll_force"]}
    for ratio in map(float, a.ratios.split(",")):
        for grading in a.gradings.split(","):
            for zone in zones:
                key = (ratio, a.h, grading, zone, a.friction,
                       a.interior if zone is not None else 0)
                if key in done or (zone is None and key[:5] + (1,) in done):
                    continue
                row = one(ratio, a.h, grading, two_d, zone, a.friction, a.interior)
                with a.out.open("a") as fh:
                    fh.write(json.dumps(row) + "\n")
                print(f"b0/h0 {ratio:g} {grading} zone {zone}: spread "
                      f"{row['spread'] * 1e3:.3f} mm, {row['wall']:.0f} s", flush=True)
    rows = [json.loads(line) for line in a.out.read_text().splitlines()]
    print(table(rows))
    print(plane_strain_limit(rows))


if __name__ == "__main__":
    main()
