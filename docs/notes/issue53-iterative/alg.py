"""Algebraic study of block preconditioners for the 3D strip's Newton Jacobian (scipy)."""
import sys
HERE = __file__
exec(open(__import__("pathlib").Path(HERE).with_name("system.py")).read())
t = time.perf_counter(); Alu = sla.splu(A); print("A lu", time.perf_counter() - t)
P = precond_form(f3, gf, 1.0, 1.0, "vfbmt"); P.Assemble()
Pm = tosp(P.mat)[allf][:, allf].tocsc()
Sdiag = Pm[nu_:, nu_:].tocsc()
def run_gmres(name, prec):
    its = [0]
    def cb(rk): its[0] += 1
    Wop = sla.LinearOperator(Jf.shape, matvec=lambda x: w * (Jf @ (prec(x / w))))   # weighted rows
    x, info = sla.gmres(Wop, w * b, rtol=1e-6, restart=300, maxiter=1, callback=cb, callback_type="pr_norm")
    print(f"{name}: {its[0]} its, info {info}")
def blockdiag(S_lu):
    def f(x):
        return np.concatenate([Alu.solve(x[:nu_]), S_lu.solve(x[nu_:])])
    return f
def blocktri(S_lu):
    def f(x):
        y2 = S_lu.solve(x[nu_:])
        y1 = Alu.solve(x[:nu_] - Bt @ y2)
        return np.concatenate([y1, y2])
    return f
run_gmres("P exact (umfpack-like splu)", lambda x, lu=sla.splu(Pm): lu.solve(x))
Slu = sla.splu(Sdiag)
run_gmres("exact A, mass S, diag", blockdiag(Slu))
run_gmres("exact A, mass S, tri", blocktri(Slu))
# exact Schur complement (dense), for the pressure+multiplier block
t = time.perf_counter()
AiBt = Alu.solve(Bt.toarray())
S = C.toarray() - B @ AiBt
print("exact S", time.perf_counter() - t, S.shape)
import scipy.linalg as sl
Sf = sl.lu_factor(S)
class D:  # dense lu wrapper
    def solve(self, x): return sl.lu_solve(Sf, x)
run_gmres("exact A, exact S, tri", blocktri(D()))
# Schur complement's pressure part only exact, lambda part mass
Spp = S[:np_, :np_]; Sll = S[np_:, np_:]
print("S_pp vs mass: ", np.linalg.norm(Spp) , np.linalg.norm(Sdiag[:np_, :np_].toarray()))
print("S_ll vs mass: ", np.linalg.norm(Sll) , np.linalg.norm(Sdiag[np_:, np_:].toarray()))
from scipy.linalg import block_diag
Sbd = block_diag(Spp, Sll); Sbf = sl.lu_factor(Sbd)
class D2:
    def solve(self, x): return sl.lu_solve(Sbf, x)
run_gmres("exact A, S blockdiag(S_pp, S_ll) exact, tri", blocktri(D2()))
Sm = Sdiag.toarray(); S3 = Sm.copy(); S3[:np_, :np_] = Spp; S3f = sl.lu_factor(S3)
class D3:
    def solve(self, x): return sl.lu_solve(S3f, x)
run_gmres("exact A, S_pp exact + mass lam, tri", blocktri(D3()))
S4 = Sm.copy(); S4[np_:, np_:] = Sll; S4f = sl.lu_factor(S4)
class D4:
    def solve(self, x): return sl.lu_solve(S4f, x)
run_gmres("exact A, mass p + S_ll exact, tri", blocktri(D4()))
# SIMPLE-type approximations: S ~ C - B diag(A)^-1 Bt
dA = A.diagonal()
Ssim = (C - B @ sp.diags(1.0 / dA) @ Bt).toarray()
print("S_simple norms pp ll", np.linalg.norm(Ssim[:np_, :np_]), np.linalg.norm(Ssim[np_:, np_:]))
for name, M in (("simple both", Ssim),
                ("mass p + simple lam", np.block([[Sm[:np_, :np_], np.zeros((np_, nl_))], [np.zeros((nl_, np_)), Ssim[np_:, np_:]]])),
                ("mass p + simple lam full coupling", np.block([[Sm[:np_, :np_], Ssim[:np_, np_:]], [Ssim[np_:, :np_], Ssim[np_:, np_:]]])),
                ):
    Mf = sl.lu_factor(M)
    class DD:
        def solve(self, x, Mf=Mf): return sl.lu_solve(Mf, x)
    run_gmres("exact A, " + name + ", tri", blocktri(DD()))
# BDDC of the velocity block: alg2.py
