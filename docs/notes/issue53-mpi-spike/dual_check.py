"""hotroll's primal-dual Newton keeps nu on an IntegrationRuleSpace (Interpolate) and the
friction's d by Set(..., BND, definedon=...) of a P2 VectorH1: do both give the serial values on
the distributed mesh? (compared through integrals, which reduce over the ranks)"""
import sys
sys.path.insert(0, "/tmp/mpispike")
from common import *
import ngsolve as ng
from ngsolve import CF, x, y, z, sin, exp, BND, VOL, Integrate, dx
from ngsolve.comp import IntegrationRuleSpace
mesh, info = distributed_prism_mesh()
S = IntegrationRuleSpace(mesh, order=2)
g = ng.GridFunction(S ** 2)
f = CF((sin(5 * x) * y + z, exp(x * y * z)))
g.Interpolate(f)
# the dual's value used in a form: integrate with the rule of the space (the default P2-P1 one)
A = ng.BilinearForm(ng.H1(mesh, order=1)); 
V = ng.VectorH1(mesh, order=2)
d = ng.GridFunction(V)
d.Set(CF((sin(7 * x) * z, y * y, exp(z))), BND, definedon=mesh.Boundaries("top"))
u, v = V.TnT()
lf = ng.LinearForm(V); lf += (g[0] * v[0] + g[1] * v[1]) * dx
lf.Assemble()
one = ng.GridFunction(V); one.Set(CF((1, 1, 1)))
val_ir = ng.InnerProduct(lf.vec, one.vec)                  # = int g0 + g1 on the rule
val_set = Integrate(d * d, mesh, BND, definedon=mesh.Boundaries("top"))
val_set_all = Integrate(d * d, mesh, BND)
say(f"ranks {comm.size}: IntegrationRuleSpace via a LinearForm {val_ir!r}; "
    f"Set on BND top: int_top |d|^2 {val_set!r}, int_allbnd |d|^2 {val_set_all!r}, "
    f"IRSpace ndofglobal {S.ndofglobal}")
