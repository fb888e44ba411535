"""The direct steady solver against the report's scheme run to its steady state (issue 3).

For each example case (Example 1; Example 2, omega = pi/6; Example 3 at m = 0.15 and 0.25, its
m = 0.2 being Example 1) and each mesh, runs both methods into DIR/<case>/<mesh>/<method>, then
writes DIR/agreement.csv and .md: each method's neutral angle, roll force, torque and forward
slip, and the differences, transient minus steady (angle in rad, force and torque in % of the
steady value, slip in points).  Finished runs are reused (same physics; threads may differ) and
interrupted transient runs resume from their checkpoint, so a long study can run in pieces.
A transient run to steady state takes 20-25 min on C2 for Examples 1 and 3 and about twice that
for Example 2 (half the roll speed, twice the steps), with 2 threads:

    python scripts/agreement.py --meshes C2                    # all four cases, ~2 h
    python scripts/agreement.py --meshes C2 --cases example2 --threads 1
    python scripts/agreement.py --meshes 0.02 --end-time 0.02 --out /tmp/ag     # smoke test
    python scripts/agreement.py --meshes C2 --cases example1 --free-surface traced,constrained \
        --a-f estimate,5                   # the roll-force issue's table (Example 1)

Runs go to DIR/<case>/<mesh>/<method> for the case file's own model and friction, and to
DIR/<case>/<mesh>/<free_surface>_af<a_f>/<method> when --free-surface or --a-f are given.
"""
from __future__ import annotations

import argparse
import math
import sys

from _common import (
    add_common_args,
    common_overrides,
    has_output,
    list_arg,
    mesh_arg,
    mesh_label,
    print_table,
    run,
    write_table,
)

from hotroll.config.case import CaseError, load_case
from hotroll.examples import example_path

CASES = {"example1": "1", "example2": "2", "example3_m015": "3, m = 0.15",
         "example3_m025": "3, m = 0.25"}
COLUMNS = ["example", "mesh", "free_surface", "a_f", "steady_its", "steady_s", "transient_steps", "transient_status",
           "transient_s", "angle_steady", "angle_transient", "d_angle", "force_steady",
           "force_transient", "d_force_pct", "torque_steady", "torque_transient",
           "d_torque_pct", "slip_steady_pct", "slip_transient_pct", "d_slip_points"]
NOTES = [
    "SI units; angles in rad; roll force N/m and torque N m/m per unit width on the upper roll "
    "(K = 1); transient figures are means over its last averaging window.",
    "d_* = transient minus steady; force and torque in % of the steady value, slip in points.",
    "steady_s and transient_s are wall times of the last invocation (a resumed or reused run "
    "counts only that part).",
    "transient_status 'steady' = the report's scheme reached its steady state; otherwise its "
    "figures are those at the stop, not a steady answer.",
]


def _pct(a, b) -> float:
    return 100.0 * (a - b) / b if b else math.nan


def row(name: str, label: str, steady: dict, transient: dict) -> dict:
    """One table row from the two summaries (missing figures become n/a)."""
    s = steady if has_output(steady) else {}
    t = transient if has_output(transient) else {}
    g = lambda d, k: math.nan if d.get(k) is None else d[k]  # noqa: E731
    out = {"example": CASES.get(name, name), "mesh": label,
           "free_surface": s.get("free_surface"), "a_f": s.get("a_f"),
           "steady_its": s.get("nonlinear_iterations"), "steady_s": g(s, "wall_time_s"),
           "transient_steps": t.get("steps"), "transient_status": transient.get("status"),
           "transient_s": g(t, "wall_time_s")}
    for key, col in (("neutral_angle", "angle"), ("roll_force", "force"),
                     ("roll_torque", "torque")):
        out[f"{col}_steady"], out[f"{col}_transient"] = g(s, key), g(t, key)
    out["d_angle"] = out["angle_transient"] - out["angle_steady"]
    out["d_force_pct"] = _pct(out["force_transient"], out["force_steady"])
    out["d_torque_pct"] = _pct(out["torque_transient"], out["torque_steady"])
    out["slip_steady_pct"] = 100.0 * g(s, "forward_slip")
    out["slip_transient_pct"] = 100.0 * g(t, "forward_slip")
    out["d_slip_points"] = out["slip_transient_pct"] - out["slip_steady_pct"]
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--meshes", type=list_arg(mesh_arg), default=["C2"],
                   help="comma-separated Table 2 names and/or sizes h in m (default C2)")
    p.add_argument("--cases", type=list_arg(str), default=list(CASES),
                   help=f"comma-separated example cases (default {','.join(CASES)})")
    p.add_argument("--free-surface", type=list_arg(str), default=None,
                   help="comma-separated free-surface models (traced, constrained; default: "
                        "the case file's)")
    p.add_argument("--a-f", type=list_arg(str), default=None,
                   help='comma-separated friction parameters: "estimate" or numbers (default: '
                        "the case file's)")
    add_common_args(p, "results/agreement")
    args = p.parse_args(argv)
    for name in args.cases:
        if name not in CASES:
            p.error(f"--cases: unknown case {name!r} (allowed: {', '.join(CASES)})")

    over = common_overrides(args)
    rows, failed = [], 0
    title = "Steady solver against the report's scheme run to its steady state"
    models = [(fs, af) for fs in (args.free_surface or [None]) for af in (args.a_f or [None])]
    for name in args.cases:
        for mesh, (fs, af) in ((m, v) for m in args.meshes for v in models):
            label = mesh_label(mesh)
            summaries, extra, sub = {}, {}, ""
            if fs is not None:
                extra["plate.free_surface"] = fs
            if af is not None:
                extra["friction.a_f"] = af if af == "estimate" else float(af)
            if extra:
                sub = f"{fs or 'case'}_af{af or 'case'}"
            for method in ("steady", "transient"):
                try:
                    case = load_case(example_path(name)).with_overrides(
                        **over, **extra, **{"mesh.h_contact": mesh, "solver.method": method})
                except CaseError as e:
                    p.error(str(e))
                out = args.out / name / label / sub / method
                summaries[method] = run(case, out, f"{name} {label} {method}",
                                        resume=args.resume)
                failed += not has_output(summaries[method])
            rows.append(row(name, label, summaries["steady"], summaries["transient"]))
            csv_path, md_path = write_table(rows, COLUMNS, args.out / "agreement", title=title,
                                            notes=NOTES)
    print_table(rows, COLUMNS, title)
    print(f"table: {csv_path}, {md_path}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
