"""Algebraic study of block preconditioners for the 3D strip's Newton Jacobian (scipy)."""
import sys
HERE = __file__
exec(open(__import__("pathlib").Path(HERE).with_name("system.py")).read())
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
