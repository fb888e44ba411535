"""Algebraic study of block preconditioners for the 3D strip's Newton Jacobian (scipy)."""
import sys
HERE = __file__
exec(open(__import__("pathlib").Path(HERE).with_name("system.py")).read())

import pyamg, scipy.linalg as sl
Ssim = (C - B @ sp.diags(1.0 / A.diagonal()) @ Bt).tocsc()
Slu = sla.splu(Ssim)
# near-null space: rigid-body modes on the vertex DOFs (hierarchical P2: bubbles 0)
mesh = f3.mesh
X = np.array([mesh[v].point for v in mesh.vertices])
disp = s3.disp.vec.FV().NumPy()
nd1 = V.ndof // 3
nv = mesh.nv
Xd = X.copy()
for c in range(3):
    Xd[:, c] += disp[c * nd1: c * nd1 + nv]
modes = []
for c in range(3):
    m = np.zeros(V.ndof); m[c * nd1: c * nd1 + nv] = 1.0; modes.append(m)
def rot(a, b):   # velocity (in a) = coordinate b, in b = -coordinate a
    m = np.zeros(V.ndof); m[a * nd1: a * nd1 + nv] = Xd[:, b]; m[b * nd1: b * nd1 + nv] = -Xd[:, a]; return m
modes += [rot(0, 1), rot(0, 2), rot(1, 2)]
Bn = np.array(modes).T[iu]
Bn = Bn[:, np.linalg.norm(Bn, axis=0) > 0]
As = (0.5 * (A + A.T)).tocsr()
# interleaved (node-blocked) velocity: index 3 i + c; fixed DOFs kept as identity rows
Afull = J[:V.ndof][:, :V.ndof].tocsr()
fixed = ~free[:V.ndof]
D = sp.diags(fixed.astype(float))
Keep = sp.diags((~fixed).astype(float))
Ablk = (Keep @ Afull @ Keep + D).tocsr()
perm = np.arange(V.ndof).reshape(3, nd1).T.reshape(-1)   # new k -> old index
Ap = Ablk[perm][:, perm].tocsr()
Bfull = np.array(modes).T
Bp = Bfull[perm] * (~fixed[perm])[:, None]
Aps = (0.5 * (Ap + Ap.T)).tocsr()
inv = np.empty_like(perm); inv[perm] = np.arange(V.ndof)
pos_u = inv[iu]          # free u (old order) -> position in the blocked vector
class BlockedM:
    def __init__(self, ml): self.M = ml.aspreconditioner(cycle="V")
    def __matmul__(self, x):
        z = np.zeros(V.ndof); z[pos_u] = x
        return (self.M @ z)[pos_u]
def test2(name, ml):
    M = BlockedM(ml)
    its = [0]
    def cb(rk): its[0] += 1
    bu = np.random.default_rng(0).standard_normal(nu_)
    Mop = sla.LinearOperator(A.shape, matvec=lambda x: M @ x)
    x, info = sla.gmres(A, bu, M=Mop, rtol=1e-6, restart=300, maxiter=1, callback=cb, callback_type="pr_norm")
    def tri(x):
        y2 = Slu.solve(x[nu_:])
        y1 = M @ (x[:nu_] - Bt @ y2)
        return np.concatenate([y1, y2])
    its2 = [0]
    def cb2(rk): its2[0] += 1
    Wop = sla.LinearOperator(Jf.shape, matvec=lambda x: w * (Jf @ (tri(x / w))))
    t = time.perf_counter()
    x, info2 = sla.gmres(Wop, w * b, rtol=1e-6, restart=300, maxiter=1, callback=cb2, callback_type="pr_norm")
    print(f"{name}: A {its[0]} its; J tri+SIMPLE {its2[0]} its ({time.perf_counter()-t:.1f} s) levels {len(ml.levels)} cx {ml.operator_complexity():.2f}")
Abs = sp.bsr_matrix(Aps, blocksize=(3, 3))
for strength in ("symmetric", "evolution"):
    t = time.perf_counter()
    ml = pyamg.smoothed_aggregation_solver(Abs, B=Bp, strength=strength, smooth="jacobi", max_coarse=500)
    test2(f"blocked SA {strength} (setup {time.perf_counter()-t:.1f}s)", ml)
