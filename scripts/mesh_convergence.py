"""Mesh convergence of the steady solver: roll force, torque, forward slip, neutral angle.

Example 1 on the contact meshes of the report's Table 2 and finer ones, for each free-surface
model and friction parameter asked for. Per series: the band of each figure over M1 and finer
(max - min over the mean, %), the observed order of convergence of the roll force from the
three finest meshes, p = log(|F3 - F2| / |F2 - F1|) / log(h3/h2) (meshes refined by a constant
ratio are not needed: the formula uses the actual ratios, h1 < h2 < h3, when they are equal;
otherwise p solves |F3 - F2| / |F2 - F1| = (h3^p - h2^p) / (h2^p - h1^p)), and the Richardson
value F1 + (F1 - F2) / ((h2/h1)^p - 1). Runs go to DIR/<model>_af<a_f>/<mesh>; finished ones are
reused. Table: DIR/mesh_convergence.csv and .md.

    python scripts/mesh_convergence.py                                  # traced, a_f 5 + estimate
    python scripts/mesh_convergence.py --meshes C2,M2 --a-f 5 --free-surface constrained
"""
from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np
from _common import (
    add_common_args,
    common_overrides,
    has_output,
    list_arg,
    make_case,
    mesh_arg,
    mesh_label,
    print_table,
    run,
    write_table,
)
from scipy.optimize import brentq

from hotroll.config.case import CaseError, load_case

MESHES = ["C1", "C2", "M1", "M2", "F1", "F2", 0.0015]
BANDS = {"roll_force": ("force_band_pct", lambda d, v: 100.0 * d / abs(v.mean())),
         "roll_torque": ("torque_band_pct", lambda d, v: 100.0 * d / abs(v.mean())),
         "forward_slip": ("slip_band_points", lambda d, v: 100.0 * d),
         "neutral_angle": ("angle_band_rad", lambda d, v: d)}
COLUMNS = ["free_surface", "a_f", "mesh", "h", "dofs", "status", "nonlinear_iterations",
           "coupling_updates", "wall_time_s", "roll_force", "roll_torque", "forward_slip",
           "neutral_angle", "contact_start_x", "a_f_value", "balance_error"]
SUMMARY = ["free_surface", "a_f", "band_from", "force_band_pct", "torque_band_pct",
           "slip_band_points", "angle_band_rad", "force_order", "force_extrapolated",
           "finest_force_vs_extrapolated_pct"]


def observed_order(h: list[float], f: list[float]) -> float:
    """Order p with |f3 - f2| / |f2 - f1| = (h3^p - h2^p) / (h2^p - h1^p), h1 < h2 < h3."""
    (h1, h2, h3), (f1, f2, f3) = h, f
    ratio = abs(f3 - f2) / max(abs(f2 - f1), 1e-300)

    def g(p):
        return (h3**p - h2**p) / (h2**p - h1**p) - ratio

    try:
        return float(brentq(g, 0.05, 8.0))
    except ValueError:       # not monotone in this range: no asymptotic order
        return math.nan


def series_summary(rows: list[dict], band_from: float) -> dict:
    ok = sorted((r for r in rows if r.get("status") == "steady"), key=lambda r: r["h"])
    out = {"band_from": f"h <= {band_from:g} m"}
    band = [r for r in ok if r["h"] <= band_from * (1 + 1e-9)]
    for key, (col, scale) in BANDS.items():
        vals = np.array([r[key] for r in band], dtype=float)
        spread = vals.max() - vals.min() if len(vals) >= 2 else math.nan
        out[col] = scale(spread, vals)
    if len(ok) >= 3:
        h = [r["h"] for r in ok[:3]]
        f = [r["roll_force"] for r in ok[:3]]
        p = observed_order(h, f)
        out["force_order"] = p
        if math.isfinite(p):
            ext = f[0] + (f[0] - f[1]) / ((h[1] / h[0]) ** p - 1.0)
            out["force_extrapolated"] = ext
            out["finest_force_vs_extrapolated_pct"] = 100.0 * (f[0] - ext) / ext
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--meshes", type=list_arg(mesh_arg), default=MESHES,
                   help="comma-separated Table 2 names and/or sizes h in m")
    p.add_argument("--free-surface", type=list_arg(str), default=["traced"])
    p.add_argument("--a-f", type=list_arg(str), default=["5", "estimate"])
    p.add_argument("--case", type=Path, default=None,
                   help="case file to study instead of Example 1 (its own mesh is replaced)")
    p.add_argument("--band-from", type=float, default=3.7e-3,
                   help="bands over meshes with h at most this (m; default M1's 3.7e-3)")
    add_common_args(p, "results/mesh_convergence")
    args = p.parse_args(argv)
    over = common_overrides(args)
    rows, summaries, failed = [], [], 0
    name = "Example 1" if args.case is None else str(args.case)

    def build(**kw):
        if args.case is None:
            return make_case(p, **kw)
        try:
            return load_case(args.case).with_overrides(**kw)
        except CaseError as e:
            p.error(str(e))

    for fs in args.free_surface:
        for af in args.a_f:
            series = []
            for mesh in args.meshes:
                case = build(**over, **{
                    "mesh.h_contact": mesh, "solver.method": "steady",
                    "plate.free_surface": fs,
                    "friction.a_f": af if af == "estimate" else float(af)})
                label = mesh_label(mesh)
                s = run(case, args.out / f"{fs}_af{af}" / label, f"{fs} a_f={af} {label}",
                        resume=args.resume)
                failed += not has_output(s)
                row = dict(s, free_surface=fs, a_f=af, mesh=label, h=case.mesh.h,
                           a_f_value=s.get("a_f"),
                           contact_start_x=(s.get("contact_start") or [math.nan])[0])
                series.append(row)
                rows.append(row)
                write_table(rows, COLUMNS, args.out / "mesh_convergence",
                            title=f"Steady solver: mesh convergence ({name})")
            summaries.append(dict(series_summary(series, args.band_from), free_surface=fs,
                                  a_f=af))
    notes = ["SI units: force N/m, torque N m/m per unit width of the upper roll (K = 1), "
             "slip in points of %, angle in rad; h the contact mesh size.",
             "Bands: (max - min) over the meshes with h <= band_from; order and extrapolation "
             "from the three finest converged meshes."]
    write_table(summaries, SUMMARY, args.out / "mesh_convergence_summary",
                title="Mesh convergence: bands, observed order, extrapolated force", notes=notes)
    print(f"tables: {args.out / 'mesh_convergence.md'}, {args.out / 'mesh_convergence_summary.md'}")
    print_table(rows, COLUMNS, f"Steady solver: mesh convergence ({name})")
    print_table(summaries, SUMMARY, "Bands, order, extrapolation")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
