"""Step 4: Norton-Hoff-like flow, eta = (eps:eps + 1e-6)^((m-1)/2), m = 0.1, Taylor-Hood on the
distributed extruded prism mesh; Newton (AssembleLinearization of a residual form, hotroll's
way, or of a Variation) with backtracking on the residual's norm; each step solved by MINRES
with BDDC of the block-diagonal form 2 eta_k eps:eps + (1/eta_k) p q on the product space
(eta_k frozen at the iterate), or by a direct solver (umfpack serial / masterinverse MPI).
Same duct problem as stokes.py.
usage: [mpiexec -n N] python newton.py [residual|variation] [krylov|direct] [maxh layers]
       --tangent: precondition with the Newton tangent's velocity block (AssembleLinearization
       of the viscous energy) instead of the frozen-viscosity form
       --multiplier: u.n = 0 on `top` by a P1 multiplier on top's vertices (hotroll's
       taylor_hood(multiplier_on=...): a Compress space), slip along it; direct solver only"""
import sys
sys.path.insert(0, "/tmp/mpispike")
from common import *
import ngsolve as ng
from ngsolve import (CF, BND, x, y, z, dx, ds, Integrate, InnerProduct, Sym, grad, div,
                     GridFunction, BilinearForm, Preconditioner, Variation, Norm, Projector)
from ngsolve.krylovspace import MinResSolver, GMResSolver

args = [a for a in sys.argv[1:] if not a.startswith("--")]
kind = args[0] if args else "residual"
solver_kind = args[1] if len(args) > 1 else "krylov"
maxh = float(args[2]) if len(args) > 2 else 0.025
layers = int(args[3]) if len(args) > 3 else 4
tangent = "--tangent" in sys.argv
LTOL = float(next((a_[7:] for a_ in sys.argv if a_.startswith("--ltol=")), 1e-8))
mult = "--multiplier" in sys.argv
m_exp, delta = ng.Parameter(1.0), 1e-6
STAGES = [float(s_) for s_ in next((a_[9:] for a_ in sys.argv if a_.startswith("--stages=")), "1,0.4,0.1").split(",")]  # continuation in m: Stokes first (hotroll starts from the 2D pass)
mesh, info = distributed_prism_mesh(maxh, layers)
t_start = time.perf_counter()
walls = "in|edge" if mult else "in|top|edge"
V = ng.VectorH1(mesh, order=2, dirichletx=walls, dirichlety=walls + "|sym",
                dirichletz=walls + "|zsym", wb_withedges=False)
Q = ng.H1(mesh, order=1)
if mult:
    full = ng.H1(mesh, order=1)
    Lm = ng.Compress(full, active_dofs=full.GetDofs(mesh.Boundaries("top")))
    X = V * Q * Lm
    (u, p, lam), (v, q, mu) = X.TnT()
else:
    X = V * Q
    (u, p), (v, q) = X.TnT()
gf = GridFunction(X)
g = CF(((1 - (y / H) ** 2) * (1 - (z / W) ** 2), 0, 0))
if mult:     # the wall `top` is now a slip wall: inflow profile vanishing at the edge only
    g = CF(((1 - (z / W) ** 2), 0, 0))
gf.components[0].Set(g, definedon=mesh.Boundaries("in"))
eps = lambda w: Sym(grad(w))
ee = lambda w: InnerProduct(eps(w), eps(w)) + delta
eta = lambda w: ee(w) ** ((m_exp - 1) / 2)
nrm = ng.specialcf.normal(3)
a = BilinearForm(X)
if kind == "variation":
    a += Variation((2 / (m_exp + 1) * ee(u) ** ((m_exp + 1) / 2) - div(u) * p) * dx)
    if mult:
        a += Variation(lam * (u * nrm) * ds("top"))
else:
    a += (2 * eta(u) * InnerProduct(eps(u), eps(v)) - div(u) * q - div(v) * p) * dx
    if mult:
        a += (lam * (v * nrm) + mu * (u * nrm)) * ds("top")
frozen = GridFunction(X)                   # the iterate the preconditioner's eta is taken at
uf = frozen.components[0]
if solver_kind == "krylov":
    P = BilinearForm(X)
    if tangent:
        P += Variation(2 / (m_exp + 1) * ee(u) ** ((m_exp + 1) / 2) * dx)
        P += (1 / eta(uf)) * p * q * dx
    else:
        P += (2 * eta(uf) * InnerProduct(eps(u), eps(v)) + (1 / eta(uf)) * p * q) * dx
    pre = Preconditioner(P, "bddc")
proj = Projector(X.FreeDofs(), True)
r, du, w = (gf.vec.CreateVector() for _ in range(3))


def rnorm():
    a.Apply(gf.vec, r)
    r.data = proj * r
    return Norm(r)


def vmax(vec):
    """max |coefficient| of the velocity block (MPI: max over the ranks)."""
    n = V.ndof
    loc = vec.FV().NumPy()[:n]
    return comm.allreduce(float(np.abs(loc).max()) if n else 0.0, op=MPI.MAX)


def figures():
    U, Pp = gf.components[0], gf.components[1]
    return {"flux_out": Integrate(U * nrm, mesh, BND, definedon=mesh.Boundaries("out")),
            "plastic_power": Integrate(2 * eta(U) * InnerProduct(eps(U), eps(U)), mesh),
            "p_in_mean": Integrate(Pp, mesh, BND, definedon=mesh.Boundaries("in")) / (H * W),
            "max_u_coef": vmax(gf.vec)}


say(f"NEWTON kind={kind} solver={solver_kind} tangent_pre={tangent} multiplier={mult} "
    f"ranks={comm.size} ndof={X.ndofglobal} prisms={info['prisms']}")
total_its, newton_its = 0, 0
for stage in STAGES:
  m_exp.Set(stage)
  r0 = rnorm()
  say(f"   m = {stage}: it 0 |r| {r0:.3e}")
  for it in range(1, 31):
    newton_its += 1
    t0 = time.perf_counter()
    a.AssembleLinearization(gf.vec)
    if solver_kind == "krylov":
        frozen.vec.data = gf.vec
        if tangent:
            P.AssembleLinearization(gf.vec)
        else:
            P.Assemble()
        t1 = time.perf_counter()
        sol = MinResSolver(mat=a.mat, pre=pre.mat, tol=LTOL, maxiter=3000, printrates=False)
        du[:] = 0
        sol.Solve(rhs=r, sol=du, initialize=False)
        lin = sol.iterations
        total_its += lin
    else:
        t1 = time.perf_counter()
        name = "umfpack" if comm.size == 1 else "masterinverse"
        inv = a.mat.Inverse(X.FreeDofs(), inverse=name)
        du.data = inv * r
        lin = name
    t2 = time.perf_counter()
    w.data = gf.vec
    alpha = 1.0
    while True:
        gf.vec.data = w - alpha * du
        r1 = rnorm()
        if r1 <= (1 - 1e-4 * alpha) * r0 or alpha < 1 / 64:
            break
        alpha /= 2
    upd = vmax(du)
    say(f"   it {it} |r| {r1:.3e} step {alpha:g} max|du| {upd:.3e} linear {lin} "
        f"(assemble {t1 - t0:.2f}s, solve {t2 - t1:.2f}s)")
    r0 = r1
    if upd < (1e-9 if stage == STAGES[-1] else 1e-3) and alpha == 1.0:
        break
res = figures()
for k, v_ in res.items():
    say(f"   {k:14s} {v_!r}")
say(f"   newton its {newton_its}, MINRES its total {total_its}, time {time.perf_counter() - t_start:.2f}s")
