"""The bundled narrow bar's top leak in the two outer width bands against x from the edge level's contact start
(docs/validation/spread_3d.md, "Mass flux"). From the repository root: PYTHONPATH=. python THIS."""
import sys
sys.argv = [sys.argv[0]] + sys.argv[1:]
exec(open(__import__("pathlib").Path(__file__).with_name("narrow_bar_fluxes.py")).read().split("m = s3.mesh")[0])
m = s3.mesh; u = s3.form.nonlinear.velocity; nn = ng.specialcf.normal(3)
fin = -integrate(u * nn, m, ng.BND, definedon=m.Boundaries("in"))
zs = s3.z
xc = s3.tops.contact_starts()
print("starts", np.round(xc * 1e3 - 1000, 3))
lo, hi = zs[-2], zs[-1] + 0.01
edges = xc[-1] + np.array([-0.5, -0.02, -0.01, -0.005, -0.0026, -0.0013, 0.0])
for a, b in zip(edges[:-1], edges[1:]):
    band = ng.IfPos((ng.z - lo) * (hi - ng.z), 1.0, 0.0) * ng.IfPos((ng.x - a) * (b - ng.x), 1.0, 0.0)
    f = integrate(band * (u * nn), m, ng.BND, definedon=m.Boundaries("top"))
    print(f"edge band, x from start {(a - xc[-1])*1e3:+8.2f} .. {(b - xc[-1])*1e3:+8.2f} mm: {f / fin:+.2e}")
lo, hi = zs[-3], zs[-2]
for a, b in zip(edges[:-1], edges[1:]):
    band = ng.IfPos((ng.z - lo) * (hi - ng.z), 1.0, 0.0) * ng.IfPos((ng.x - a) * (b - ng.x), 1.0, 0.0)
    f = integrate(band * (u * nn), m, ng.BND, definedon=m.Boundaries("top"))
    print(f"next band, x from edge start {(a - xc[-1])*1e3:+8.2f} .. {(b - xc[-1])*1e3:+8.2f} mm: {f / fin:+.2e}")
