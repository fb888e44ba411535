"""Exact scalings on a slow lab pass (R 0.1 m, 10 -> 7.5 mm, 0.02 m/s): Norton-Hoff m = 0.2,
Coulomb 0.3, steady; roll speed x100 (eps0 x100 as well, and eps0 kept), K x1000, the roll
axis moved; and the same lab pass thermo-mechanical (the bundled thermal pass's grade and
thermal data) with the axis moved.

    python scripts/exact_scalings.py

Uses the lab pass and the helpers of tests/solvers/test_contact.py. A check run after a solver
change (docs/validation/speed.md), not a test: the suite's exact-scaling tests are
``test_contact.py::test_slow_lab_pass_scales_exactly`` and the flattening roll's.
"""
from __future__ import annotations

import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
M = 0.2


def main() -> int:
    sys.path[:0] = [str(ROOT / "tests" / "solvers"), str(ROOT / "tests")]
    from test_contact import LAB, solve, with_

    from hotroll.config.case import load_case
    from hotroll.examples import example_path
    from hotroll.workflows.runner import run_case

    base = with_(LAB, **{"material.m": M, "material.eps0": 1e-4, "friction.law": "coulomb",
                         "friction.mu": 0.3})
    del base["friction"]["factor"]
    b, _ = solve(base)
    print(f"base: exit {b['exit_code']}, {b['nonlinear_iterations']} it., force "
          f"{b['roll_force']:.6g} N/m, forward slip {b['forward_slip']:.6f}")
    variants = (
        ("speed x100, eps0 x100", {"pass.roll_angular_velocity": 20.0, "material.eps0": 1e-2},
         100.0**M),
        ("speed x100, eps0 kept", {"pass.roll_angular_velocity": 20.0}, 100.0**M),
        ("K x1000", {"material.K": 1e11}, 1000.0),
        ("roll axis moved 5 m", {"pass.roll_axis_x": 5.0}, 1.0))
    for name, change, factor in variants:
        s, _ = solve(with_(base, **change))
        print(f"{name:22s} exit {s['exit_code']}, {s['nonlinear_iterations']} it.: "
              f"force / (base x {factor:.4g}) {s['roll_force'] / b['roll_force'] / factor:.10f}, "
              f"torque {s['roll_torque'] / b['roll_torque'] / factor:.10f}, "
              f"slip {s['forward_slip'] - b['forward_slip']:+.2e}, "
              f"neutral angle {s['neutral_angle'] - b['neutral_angle']:+.2e} rad")

    thermal = load_case(example_path("hot_strip_finishing_thermal")).with_overrides(**{
        "pass.roll_radius": 0.1, "pass.entry_thickness": 0.01, "pass.exit_thickness": 0.0075,
        "pass.roll_angular_velocity": 0.2, "plate.length": 0.1, "solver.threads": 1,
        "output.figures": False, "output.vtk": False})
    out = []
    for case in (thermal, thermal.with_overrides(**{"pass.roll_axis_x": 5.0})):
        with tempfile.TemporaryDirectory() as tmp:
            out.append(run_case(case, Path(tmp) / "run", resume=False))
    a, moved = out
    print(f"thermal lab pass: exit {a['exit_code']} / {moved['exit_code']}, "
          f"{a['nonlinear_iterations']} / {moved['nonlinear_iterations']} it.; axis moved:")
    for key in ("roll_force", "roll_torque", "forward_slip", "exit_temperature_mean",
                "exit_temperature_surface"):
        rel = abs(moved[key] - a[key]) / abs(a[key])
        print(f"  {key} {a[key]:.10g} -> {moved[key]:.10g} (rel. {rel:.1e})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
