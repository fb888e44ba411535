"""The flattening rolls of the full strip against the half model on a thin strip (issue 52).

    python scripts/full_strip_flattening.py hitchcock 1.0 1.05
    python scripts/full_strip_flattening.py elastic 1.0

The bundled thin_strip (2.4 -> 2.0 mm, R 0.35 m, 10 m/s, Coulomb 0.3) with its strip's
elasticity off (the full strip has none yet) and both rolls flattening by the model given: the
half model, then the full strip at each speed ratio (upper over lower) given, and the full
strip with rigid rolls. Prints status, wall seconds, each roll's force and torque, the forward
slip, the exit curvature, each roll's updates and the Newton iterations.
"""
from __future__ import annotations

import argparse
import time
from dataclasses import replace

from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.model.roll_elastic import RollElasticity
from hotroll.solvers.full_steady import FullSteadyRun
from hotroll.solvers.steady import SteadyRun
from hotroll.workflows.build import build_model, steady_settings


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("model", choices=("hitchcock", "elastic"))
    ap.add_argument("ratios", nargs="*", type=float, default=[1.0])
    a = ap.parse_args()
    over = {"contact.strip_youngs_modulus": "off", "roll.model": a.model,
            "pass.mill_modulus": None}
    case = load_case(example_path("thin_strip"), over)
    problem, _ = build_model(case)
    st = steady_settings(case)
    t = time.perf_counter()
    half = SteadyRun(problem, st, case.plate.length)
    sol = half.run()
    h = sol.history[-1]
    print(f"half model: {sol.status}, {time.perf_counter() - t:.1f} s, force {h['roll_force']:.7g} "
          f"N/m, torque {h['roll_torque']:.7g} N m/m, forward slip {h['forward_slip']:.6g}, "
          f"roll updates {problem.roll.updates}, "
          f"{sum(s.iterations for s in half.result.stats)} Newton iterations")
    rigid = replace(problem, roll=None, rp=case.pass_.roll_pass())
    rp = rigid.rp
    el = RollElasticity(case.roll.youngs_modulus, case.roll.poissons_ratio)
    models = {s: (a.model, el, case.roll.relaxation, 1e-3 * rp.half_exit) for s in (1, -1)}
    frictions = {1: problem.friction, -1: problem.friction}
    for r in a.ratios:
        t = time.perf_counter()
        run = FullSteadyRun(rigid, st, case.plate.length,
                            {1: replace(rp, omega=rp.omega * r), -1: rp}, frictions,
                            roll_models=models)
        sol = run.run()
        f = sol.history[-1]
        print(f"full strip, r = {r:g}: {sol.status}, {time.perf_counter() - t:.1f} s, force "
              f"{f['upper_roll_force']:.7g} / {f['lower_roll_force']:.7g} N/m, torque "
              f"{f['upper_roll_torque']:.7g} / {f['lower_roll_torque']:.7g} N m/m, forward slip "
              f"(upper) {f['upper_forward_slip']:.6g}, curvature {f['exit_curvature']:.4g} 1/m, "
              f"roll updates {[fr.updates for fr in run.flattening.values()]}, "
              f"{sum(s.iterations for s in run.result.stats)} Newton iterations")
    run = FullSteadyRun(rigid, st, case.plate.length, {1: rp, -1: rp}, frictions)
    sol = run.run()
    print(f"full strip, rigid rolls: {sol.status}, force "
          f"{sol.history[-1]['upper_roll_force']:.7g} N/m")


if __name__ == "__main__":
    main()
