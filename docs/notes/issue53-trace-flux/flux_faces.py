"""The 2D pass's flux through each face of Case R (R = 250 mm, 10 -> 8 mm, Tresca 0.3,
m = 0.05) at the mesh sizes given (m), as fractions of the inflow; ``STOL``: the surfaces'
tolerance (x h; default the settings'). Run from the repository: ``python
docs/notes/issue53-trace-flux/flux_faces.py 1e-3 5e-4`` (with trace_flux.patch applied: the
zero-flux trace)."""
import sys, os
sys.path.insert(0, "scripts")
from asymmetric_case_r import case_r
from hotroll.solvers.steady import SteadyRun
import ngsolve as ng, dataclasses
TOL = float(os.environ.get("STOL", "0"))
for h in [float(a) for a in sys.argv[1:]]:
    case, problem, st = case_r(0.05, h)
    st = dataclasses.replace(st, surface_tol=TOL) if TOL else st
    run = SteadyRun(problem, st, case.plate.length)
    r = run.run()
    mesh = run.mesh
    u = run.form.nonlinear.velocity
    n = ng.specialcf.normal(2)
    fl = {b: ng.Integrate(u * n, mesh, ng.BND, definedon=mesh.Boundaries(b), order=8) for b in ("in", "top", "exit", "arc", "out")}
    q = -fl["in"]
    two = run.state.history[-1]
    print(h, r.status, {k: f"{v/q:.3e}" for k, v in fl.items()}, "force", two["roll_force"], "slip", two["forward_slip"], "torque", two["roll_torque"], "x_c", run.shape.x_c, flush=True)
