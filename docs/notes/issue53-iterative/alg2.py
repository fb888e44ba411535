"""Algebraic study of block preconditioners for the 3D strip's Newton Jacobian (scipy)."""
import sys, time
sys.path.insert(0, "/work/main/scripts"); sys.path.insert(0, "/work/main/benchmarks")
import numpy as np, scipy.sparse as sp, scipy.sparse.linalg as sla
import ngsolve as ng
from bench_3d import two_d, SIZES
from hotroll.solvers.spread_3d import Spread3D
from hotroll.fem.nonlinear import _Workspace
exec(open(__import__("pathlib").Path(__file__).with_name("pform.py")).read())   # precond_form(f3, gf, cmul, cp, parts)

ng.SetNumThreads(1)
case = sys.argv[1]; size = sys.argv[2]
run, half, status, wall = two_d(case)
h = run.problem.h; e, l = SIZES[size]
s3 = Spread3D(run, half, edge=e * h, largest=l * h)
f3 = s3.form; nl = f3.nonlinear; gf = nl.gf
if "--solved" in sys.argv: s3.solve()
ws = _Workspace(nl)
f3._prepare_duals(2)
nl.a_newton.Apply(gf.vec, ws.r)
nl.a_jacobian.Assemble()
def tosp(m):
    r, c, v = m.COO(); n = m.height
    return sp.csr_matrix((np.array(v), (np.array(r), np.array(c))), shape=(n, n))
J = tosp(nl.a_jacobian.mat)
free = np.array(list(nl.freedofs), dtype=bool)
nu = f3.fes.components[0].ndof if hasattr(f3.fes.components[0], "ndof") else None
# the product space ((V x Q) x L): offsets
comps = f3.fes.components; print([c.ndof for c in comps]); V, Q = comps[0], comps[1]
nV, nQ = V.ndof, Q.ndof
idx = np.arange(J.shape[0])
iu = idx[:nV][free[:nV]]; ip = idx[nV:nV + nQ][free[nV:nV + nQ]]; il = idx[nV + nQ:][free[nV + nQ:]]
print("ndof", J.shape[0], "free u p lam", len(iu), len(ip), len(il))
allf = np.concatenate([iu, ip, il])
Jf = J[allf][:, allf].tocsc()
b = ws.r.FV().NumPy()[allf].copy()
w = ws.weights()[allf]
nu_, np_, nl_ = len(iu), len(ip), len(il)
A = Jf[:nu_, :nu_].tocsc(); B = Jf[nu_:, :nu_].tocsc(); Bt = Jf[:nu_, nu_:].tocsc(); C = Jf[nu_:, nu_:].tocsc()
Ssim = (C - B @ sp.diags(1.0 / A.diagonal()) @ Bt).toarray()
import scipy.linalg as sl
# BDDC of the velocity block (the form with the exact friction tangent)
from ngsolve import Preconditioner
for parts in sys.argv[3].split(","):
    PF = precond_form(f3, gf, 1.0, 1.0, parts)
    pre = Preconditioner(PF, "bddc", coarsetype="direct")
    try:
        PF.Assemble()
    except Exception as ex:
        print("fail", ex); continue
    PFs = tosp(PF.mat)[allf][:, allf].tocsc()
    print(parts, "velocity block equal to J's:", sla.norm(PFs[:nu_, :nu_] - A) / sla.norm(A))
    xv = gf.vec.CreateVector(); yv = gf.vec.CreateVector()
    def bddc_u(x):
        a = xv.FV().NumPy(); a[:] = 0.0; a[iu] = x
        yv.data = pre * xv
        return yv.FV().NumPy()[iu].copy()
    its = [0]
    def cb(rk): its[0] += 1
    Aop = sla.LinearOperator(A.shape, matvec=lambda x: A @ bddc_u(x))
    bu = np.random.default_rng(0).standard_normal(nu_)
    x, info = sla.gmres(Aop, bu, rtol=1e-6, restart=300, maxiter=1, callback=cb, callback_type="pr_norm")
    print(f"A with BDDC: {its[0]} its")
    Au = PFs[:nu_, :nu_]
    its = [0]
    x, info = sla.gmres(sla.LinearOperator(A.shape, matvec=lambda x: Au @ bddc_u(x)), bu, rtol=1e-6, restart=300, maxiter=1, callback=cb, callback_type="pr_norm")
    print(f"its own block with BDDC: {its[0]} its")
    Mf = sl.lu_factor(Ssim)
    def tri_bddc(x):
        y2 = sl.lu_solve(Mf, x[nu_:])
        y1 = bddc_u(x[:nu_] - Bt @ y2)
        return np.concatenate([y1, y2])
    

g0 = f3.tangent_points.gf.components[0].vec.FV().NumPy()
print("viscosity at the points: min %.3g max %.3g ratio %.3g" % (g0.min(), g0.max(), g0.max() / g0.min()))
print("mu_ref", f3.mu_ref, "m", f3.m.Get() if hasattr(f3.m, 'Get') else f3.m)
