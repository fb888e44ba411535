import sys, numpy as np, ngsolve as ng
sys.path[:0] = ["."]
from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.solvers.steady import SteadyRun
from hotroll.workflows.build import build_model, steady_settings
for ratio in (16.0, 64.0):
    case = load_case(example_path("roughing_slab"), {"output.figures": False, "mesh.corner_refinement": ratio})
    problem, _ = build_model(case)
    run = SteadyRun(problem, steady_settings(case), case.plate.length)
    run.run()
    u, n = run.form.nonlinear.velocity, ng.specialcf.normal(2)
    mesh = run.mesh
    q = -ng.Integrate(u * n, mesh, ng.BND, definedon=mesh.Boundaries("in"), order=8)
    per = ng.Integrate(u * n, mesh, ng.BND, definedon=mesh.Boundaries("top|exit"), order=8, element_wise=True).NumPy()
    xs = []
    for el in mesh.Elements(ng.BND):
        xs.append(np.mean([mesh[v].point[0] for v in el.vertices]))
    xs = np.array(xs); nz = np.abs(per) > 0
    xc = run.shape.x_c
    print("ratio", ratio, "x_c", xc, "total top+exit", per.sum() / q, "h", problem.h)
    order = np.argsort(xs[nz])
    xx, ff = xs[nz][order], per[nz][order] / q
    for lo, hi in ((-1e9, -0.1), (-0.1, -0.02), (-0.02, -0.002), (-0.002, 0.0), (0.0, 1e9)):
        sel = (xx - xc >= lo) & (xx - xc < hi)
        print(f"  x - x_c in [{lo}, {hi}): {ff[sel].sum():.2e}  ({sel.sum()} edges)")
