"""The shared set-up of the study scripts (exec'd by them with HERE = their path): the bench's
case (argv[1]: narrow | roughing) at a width grading (argv[2]), its first 3D Newton system
as scipy blocks: J, the free velocity / pressure / multiplier rows, A, B, Bt, C, b, w."""
import sys, time
ROOT = __import__("pathlib").Path(HERE).resolve().parents[3]
sys.path.insert(0, str(ROOT / "scripts")); sys.path.insert(0, str(ROOT / "benchmarks"))
import numpy as np, scipy.sparse as sp, scipy.sparse.linalg as sla
import ngsolve as ng
from bench_3d import two_d, SIZES
from hotroll.solvers.spread_3d import Spread3D
from hotroll.fem.nonlinear import _Workspace
exec(open(__import__("pathlib").Path(HERE).with_name("pform.py")).read())   # precond_form(f3, gf, cmul, cp, parts)

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
