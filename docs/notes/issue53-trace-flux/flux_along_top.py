"""Where Case R's 2D top leaks: the flux through the top ahead of x_c + d h, as a fraction of
the inflow (the surfaces settled to 1e-5 h). Run from the repository."""
import sys, dataclasses
import numpy as np
sys.path.insert(0, "scripts")
from asymmetric_case_r import case_r
from hotroll.solvers.steady import SteadyRun
import ngsolve as ng
for h in (1e-3, 5e-4):
    case, problem, st = case_r(0.05, h)
    st = dataclasses.replace(st, surface_tol=1e-5)
    run = SteadyRun(problem, st, case.plate.length)
    r = run.run()
    mesh = run.mesh
    u = run.form.nonlinear.velocity
    n = ng.specialcf.normal(2)
    q = -ng.Integrate(u * n, mesh, ng.BND, definedon=mesh.Boundaries("in"), order=8)
    xc = run.shape.x_c
    print("h", h, "x_c", xc)
    for d in (-50, -20, -10, -5, -3, -2, -1, -0.5, 0, 0.5, 1, 5):
        a = xc + d * h
        f = ng.Integrate(ng.IfPos(a - ng.x, 1.0, 0.0) * u * n, mesh, ng.BND, definedon=mesh.Boundaries("top"), order=8)
        print(f"  x < x_c {d:+} h: {f/q:.3e}")
