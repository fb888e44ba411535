"""Mesh study of Example 1 on the contact meshes of the report's Table 2 (cf. its Figs. 4 and 5).

Each mesh runs into DIR/<mesh>; the results go to DIR/mesh_table.csv and .md (rewritten after
every run, so an interrupted study keeps what it has) and the overlay DIR/mesh_compare.png.
Finished runs are reused and interrupted ones resume from their checkpoint (``--no-resume``
starts afresh).  To steady state, C1 takes about an hour on 2 cores and the finer meshes
longer, so run the full table in the background:

    python scripts/mesh_table.py                          # C1, C2, M1, M2, F1, F2
    python scripts/mesh_table.py --meshes C1,C2 --out results/mesh_table
    python scripts/mesh_table.py --meshes 0.015 --end-time 0.005 --out /tmp/mt   # smoke test
"""
from __future__ import annotations

import argparse
import sys

from _common import (add_common_args, common_overrides, flat, has_output, list_arg,
                     make_case, mesh_arg, mesh_label, print_table, run, write_table)
from hotroll.app.config import MESH_TABLE

COLUMNS = ["mesh", "h", "dofs", "steps", "status", "neutral_x", "neutral_y", "neutral_angle",
           "roll_force", "roll_torque", "forward_slip", "a_f", "mass_flux_error",
           "power_balance_error", "iterations_per_step", "wall_time_s"]

NOTES = [
    "Example 1 (m = 0.2, omega = pi/3, K = 1); SI units, neutral_angle in rad, roll force "
    "and torque per unit width on the (upper) roll.",
    "Scalars are means over the runner's last averaging window; status 'steady' = steady state "
    "reached, 'end_time' = stopped at the end time before that.",
    "wall_time_s is that of the last invocation (a resumed run counts only the resumed part).",
]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--meshes", type=list_arg(mesh_arg), default=list(MESH_TABLE),
                   help="comma-separated Table 2 names and/or sizes h in m "
                        f"(default {','.join(MESH_TABLE)})")
    add_common_args(p, "results/mesh_table")
    args = p.parse_args(argv)

    over = common_overrides(args)
    cases = {mesh_label(m): make_case(p, **over, **{"mesh.h_contact": m}) for m in args.meshes}
    rows, runs = [], {}
    title = "Example 1: mesh study (report Table 2)"
    for label, case in cases.items():
        summary = run(case, args.out / label, label, resume=args.resume)
        rows.append(flat(summary, mesh=label, h=case.mesh.h))
        if has_output(summary):
            name = f"{label} (h = {case.mesh.h:g} m)" if label in MESH_TABLE else f"h = {label} m"
            runs[name] = args.out / label
        csv_path, md_path = write_table(rows, COLUMNS, args.out / "mesh_table", title=title,
                                        notes=NOTES)
    print_table(rows, COLUMNS, title)
    print(f"table: {csv_path}, {md_path}")
    if runs:
        from hotroll.post.plots import plot_compare

        png = plot_compare(runs, args.out / "mesh_compare.png",
                           title="Example 1: contact profiles on the Table 2 meshes")
        print(f"figure: {png}")
    return 0 if len(runs) == len(cases) else 1


if __name__ == "__main__":
    sys.exit(main())
