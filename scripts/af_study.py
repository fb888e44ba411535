"""Example 1 with a fixed friction coefficient a_f, beside the run with the a_f estimate.

Each value runs into DIR/af_<a_f> (DIR/af_estimate for the estimate); the results go to
DIR/af_study.csv and .md (rewritten after every run), DIR/af_study.png (neutral angle, forward
slip and roll force against a_f, log x; the estimate run is drawn at the mean a_f it used) and
DIR/af_compare.png (contact and top-boundary profiles of all runs).  Finished runs are reused,
interrupted ones resume from their checkpoint.  Every run to steady state takes about as long
as the mesh's transient run of the mesh table (`hotroll study mesh_table --set
solver.method=transient`; C1: about an hour on 2 cores).

    python scripts/af_study.py --mesh C1
    python scripts/af_study.py --af 1,10,100,estimate --mesh 0.015 --end-time 0.01 --out /tmp/af
"""
from __future__ import annotations

import argparse
import sys

from _common import (add_common_args, common_overrides, flat, has_output, list_arg,
                     make_case, mesh_arg, print_table, run, write_table)

DEFAULT_AF = "1,2,5,10,20,50,100,estimate"
COLUMNS = ["a_f_requested", "a_f_used", "neutral_angle", "neutral_x", "neutral_y",
           "forward_slip", "roll_force", "roll_torque", "status", "converged", "outlet_driven",
           "steps"]


def af_arg(text: str) -> str | float:
    text = text.strip().lower()
    if text == "estimate":
        return text
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: a_f must be a number > 0 or 'estimate'") \
            from None
    if not value > 0:
        raise argparse.ArgumentTypeError(f"{text!r}: a_f must be > 0")
    return value


def label(a_f: str | float) -> str:
    return "estimate" if a_f == "estimate" else f"{a_f:g}"


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--af", type=list_arg(af_arg), default=list_arg(af_arg)(DEFAULT_AF),
                   help=f"comma-separated a_f values and/or 'estimate' (default {DEFAULT_AF})")
    p.add_argument("--mesh", type=mesh_arg, default=None,
                   help="contact mesh: Table 2 name or h in m (default: the example's, C2)")
    add_common_args(p, "results/af_study")
    args = p.parse_args(argv)

    over = common_overrides(args)
    if args.mesh is not None:
        over["mesh.h_contact"] = args.mesh
    cases = {label(a): make_case(p, **over, **{"friction.a_f": a}) for a in args.af}
    mesh = next(iter(cases.values())).mesh
    named = f"mesh {mesh.h_contact}, " if isinstance(mesh.h_contact, str) else ""
    title = f"Example 1: fixed a_f vs estimate ({named}h = {mesh.h:g} m)"
    notes = ["a_f in m^-m; a_f_used is the mean over the last averaging window (the estimate "
             "is updated every step). neutral_angle in rad; force and torque per unit width.",
             "converged = steady state reached with a converged solver and not outlet-driven."]
    rows, runs = [], {}
    for name, case in cases.items():
        out = args.out / f"af_{name}"
        summary = run(case, out, f"a_f = {name}", resume=args.resume)
        rows.append(flat(summary, a_f_requested=case.friction.a_f, a_f_used=summary.get("a_f")))
        if has_output(summary):
            used = summary.get("a_f")
            runs[f"estimate (a_f = {used:.3g})" if name == "estimate" and used is not None
                 else f"a_f = {name}"] = out
        csv_path, md_path = write_table(rows, COLUMNS, args.out / "af_study", title=title,
                                        notes=notes)
    print_table(rows, COLUMNS, title)
    print(f"table: {csv_path}, {md_path}")
    if runs:
        from hotroll.post.plots import plot_compare, plot_series

        png = plot_series([r for r in rows if has_output(r)], "a_f_used",
                          ["neutral_angle", "forward_slip", "roll_force"],
                          args.out / "af_study.png", title=title, logx=True,
                          xlabel="a_f [m^-m] (estimate run at its mean a_f)")
        png2 = plot_compare(runs, args.out / "af_compare.png", title=title)
        print(f"figures: {png}, {png2}")
    return 0 if len(runs) == len(cases) else 1


if __name__ == "__main__":
    sys.exit(main())
