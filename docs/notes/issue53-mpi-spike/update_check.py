"""Does a kept direct inverse of the distributed matrix follow the matrix's new values on
Update() (hotroll's nonlinear._update_and_solve refactorises kept inverses that way)?"""
import sys
sys.path.insert(0, "/tmp/mpispike")
from common import *
import ngsolve as ng
from ngsolve import dx, grad, InnerProduct, CF, x, Parameter
mesh, info = distributed_prism_mesh()
V = ng.H1(mesh, order=2, dirichlet="in")
u, v = V.TnT()
c = Parameter(1.0)
a = ng.BilinearForm((c * (1 + x) * grad(u) * grad(v) + u * v) * dx).Assemble()
f = ng.LinearForm(v * dx).Assemble()
name = sys.argv[1]
inv = a.mat.Inverse(V.FreeDofs(), inverse=name)
sol, r = f.vec.CreateVector(), f.vec.CreateVector()
def res():
    sol.data = inv * f.vec
    r.data = f.vec - a.mat * sol
    r.data = ng.Projector(V.FreeDofs(), True) * r
    return ng.Norm(r) / ng.Norm(f.vec)
r1 = res()
c.Set(5.0); a.Assemble()
r2 = res()            # stale factors
err = None
try:
    inv.Update()
except Exception as e:   # noqa
    err = f"{type(e).__name__}: {e}"
r3 = res()
say(f"{name} ranks={comm.size}: rel. residual fresh {r1:.1e}, after the matrix changed {r2:.1e}, after Update() {r3:.1e} {err or ''} type {type(inv).__name__}")
