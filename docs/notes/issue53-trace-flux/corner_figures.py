"""The 2D pass with and without the mesh refined at the contact's start (mesh.corner_refinement,
docs/theory.md 4e): the top's and exit top's flux over the inflow, force, torque, forward slip
and unknowns of Case R (h = 1 and 0.5 mm) and the bundled roughing_slab and narrow_bar, at the
ratios given (default 1 and 16). Run from the repository:
``python docs/notes/issue53-trace-flux/corner_figures.py [1 16]``; ``STOL=1e-5``: the surfaces'
tolerance (x h) instead of the settings' 1e-3."""
import dataclasses
import os
import sys

sys.path.insert(0, ".")
sys.path.insert(1, "scripts")
import ngsolve as ng  # noqa: E402
from asymmetric_case_r import case_r  # noqa: E402

from hotroll.config.case import load_case  # noqa: E402
from hotroll.examples import example_path  # noqa: E402
from hotroll.solvers.steady import SteadyRun  # noqa: E402
from hotroll.workflows.build import build_model, steady_settings  # noqa: E402

STOL = float(os.environ.get("STOL", "0"))


def passes(ratio):
    for h in (1e-3, 5e-4):
        case, problem, st = case_r(0.05, h)
        yield f"Case R h={h * 1e3:g} mm", case, replace_corner(problem, ratio), st
    for name in ("roughing_slab", "narrow_bar"):
        case = load_case(example_path(name), {"output.figures": False,
                                              "mesh.corner_refinement": ratio})
        problem, _ = build_model(case)
        yield name, case, problem, steady_settings(case)


def replace_corner(problem, ratio):
    return dataclasses.replace(problem, mesh=dataclasses.replace(problem.mesh, corner=ratio))


for ratio in [float(a) for a in sys.argv[1:]] or [1.0, 16.0]:
    for name, case, problem, st in passes(ratio):
        st = dataclasses.replace(st, surface_tol=STOL) if STOL else st
        run = SteadyRun(problem, st, case.plate.length)
        status = run.run().status
        u, n = run.form.nonlinear.velocity, ng.specialcf.normal(2)
        flux = {b: ng.Integrate(u * n, run.mesh, ng.BND, definedon=run.mesh.Boundaries(b),
                                order=8) for b in ("in", "top", "exit")}
        q = -flux["in"]
        two = run.state.history[-1]
        print(f"{ratio:g}x {name}: {status}, {run.form.fes.ndof} unknowns, top {flux['top'] / q:.2e}, "
              f"exit top {flux['exit'] / q:.2e}, force {two['roll_force']:.6g}, torque "
              f"{two['roll_torque']:.6g}, forward slip {two['forward_slip']:.5f}", flush=True)
