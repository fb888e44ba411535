"""The solver's tolerance on every bundled case's figures, measured: each case solved with the
default tolerances and again with every tolerance ten times tighter (the Newton update, a_f,
the strain, the temperature, the free tops, the roll); the relative difference of each figure
is the band within which the default solve's figures are known (docs/validation/speed.md).

    python scripts/tolerance_band.py [--cases example1,hot_strip_finishing] [--out band.json]

The golden comparison of a solver change (``scripts/summary_diff.py``) asks that no figure
moves by more than this band.
"""
from __future__ import annotations

import argparse
import json
import sys
from dataclasses import replace
from pathlib import Path

FIGURES = ("roll_force", "roll_torque", "forward_slip", "neutral_angle", "exit_temperature_mean",
           "exit_temperature_surface")


def solve(name: str, tighter: float) -> tuple[dict, int, bool]:
    from hotroll.config.case import load_case
    from hotroll.examples import HERE
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.build import build_model, steady_settings

    case = load_case(HERE / "cases" / f"{name}.toml")
    model, _ = build_model(case)
    s = steady_settings(case)
    if tighter != 1.0:
        s = replace(s, tol=s.tol / tighter, a_f_rtol=s.a_f_rtol / tighter,
                    strain_rtol=s.strain_rtol / tighter, thermal_rtol=s.thermal_rtol / tighter,
                    surface_tol=s.surface_tol / tighter, roll_tol=s.roll_tol / tighter,
                    max_it=2 * s.max_it, max_outer=2 * s.max_outer)
    run = SteadyRun(model, s, case.plate.length)
    run.record = False
    res = run.solve()
    row = run.measure(res.stats[-1], 0)
    return {k: float(row[k]) for k in FIGURES if k in row}, res.iterations, res.converged


def main(argv=None) -> int:
    from hotroll.examples import EXAMPLES

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cases", default=",".join(sorted({c for v in EXAMPLES.values() for c in v})))
    p.add_argument("--out", type=Path, default=None)
    args = p.parse_args(argv)
    out = {}
    for name in args.cases.split(","):
        a, ia, ca = solve(name, 1.0)
        b, ib, cb = solve(name, 10.0)
        band = {k: abs(a[k] - b[k]) / max(abs(b[k]), 1e-300) for k in a}
        out[name] = {"default": a, "tight": b, "band": band, "iterations": [ia, ib],
                     "converged": [ca, cb]}
        print(f"{name:28s} it {ia:3d}/{ib:3d} conv {ca}/{cb} "
              + " ".join(f"{k} {v:.1e}" for k, v in band.items()), flush=True)
    if args.out:
        args.out.write_text(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
