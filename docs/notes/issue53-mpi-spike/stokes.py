"""Step 3: 3D Stokes, Taylor-Hood P2/P1 (hotroll's taylor_hood spaces: VectorH1 order 2 with
component-wise Dirichlet x H1 order 1) on hotroll's extruded prism mesh, distributed.
Duct-like test: u = (g, 0, 0) on `in` (g vanishes on the walls), walls `top`, `edge` (u = 0),
`sym` u_y = 0, `zsym` u_z = 0, `out` natural.
usage: [mpiexec -n N] python stokes.py METHOD [maxh layers]
METHOD: block  - separate V, Q; BlockMatrix; diag(BDDC(a_u), Jacobi(M_p)) + MINRES
        prod   - hotroll's layout: one product space X = V x Q; BDDC of the block-diagonal
                 form a_u + M_p on X + MINRES
        direct:NAME - K.Inverse(X.FreeDofs(), inverse=NAME) on the product space
                 (umfpack, masterinverse, mumps, sparsecholesky, pardiso); +reg: -1e-10 p q
options: --wbe (keep NGSolve's default wb_withedges=True for the velocity)
"""
import sys
sys.path.insert(0, "/tmp/mpispike")
from common import *
import ngsolve as ng
from ngsolve import (CF, BND, VOL, x, y, z, dx, ds, Integrate, InnerProduct, Sym, grad, div,
                     GridFunction, BilinearForm, LinearForm, Preconditioner)
from ngsolve.krylovspace import MinResSolver

args = [a for a in sys.argv[1:] if not a.startswith("--")]
method = args[0]
maxh = float(args[1]) if len(args) > 1 else 0.025
layers = int(args[2]) if len(args) > 2 else 4
wbe = "--wbe" in sys.argv
TOL = float(next((a[6:] for a in sys.argv if a.startswith("--tol=")), 1e-10))
mesh, info = distributed_prism_mesh(maxh, layers)
T = {"mesh": info["t_mesh"]}
walls = "in|top|edge"
Vargs = dict(order=2, dirichletx=walls, dirichlety=walls + "|sym", dirichletz=walls + "|zsym")
if not wbe:
    Vargs["wb_withedges"] = False
V = ng.VectorH1(mesh, **Vargs)
Q = ng.H1(mesh, order=1)
g = CF(((1 - (y / H) ** 2) * (1 - (z / W) ** 2), 0, 0))
eps = lambda w: Sym(grad(w))
nrm = ng.specialcf.normal(3)
t0 = time.perf_counter()
res = {}


def figures(u, p):
    ux = u.components[0].vec.FV().NumPy() if hasattr(u, "components") and len(u.components) else None
    out = {"flux_out": Integrate(u * nrm, mesh, BND, definedon=mesh.Boundaries("out")),
           "flux_in": -Integrate(u * nrm, mesh, BND, definedon=mesh.Boundaries("in")),
           "dissipation": Integrate(2 * InnerProduct(eps(u), eps(u)), mesh),
           "p_in_mean": Integrate(p, mesh, BND, definedon=mesh.Boundaries("in")) / (H * W),
           "p_out_mean": Integrate(p, mesh, BND, definedon=mesh.Boundaries("out")) / (H * W)}
    return out


if method == "block":
    u, v = V.TnT(); p, q = Q.TnT()
    a = BilinearForm(2 * InnerProduct(eps(u), eps(v)) * dx)
    pre_a = Preconditioner(a, "bddc")
    a.Assemble()
    b = BilinearForm(trialspace=V, testspace=Q)
    b += -div(u) * q * dx
    b.Assemble()
    m = BilinearForm(p * q * dx)
    pre_m = Preconditioner(m, "local")
    m.Assemble()
    T["assemble+bddc"] = time.perf_counter() - t0
    K = ng.BlockMatrix([[a.mat, b.mat.T], [b.mat, None]])
    C = ng.BlockMatrix([[pre_a.mat, None], [None, pre_m.mat]])
    gu, gp = GridFunction(V), GridFunction(Q)
    gu.Set(g, definedon=mesh.Boundaries("in"))
    sol = ng.BlockVector([gu.vec, gp.vec])
    rhs = sol.CreateVector()
    rhs.data = -K * sol
    du = sol.CreateVector(); du[:] = 0
    t1 = time.perf_counter()
    solver = MinResSolver(mat=K, pre=C, tol=TOL, maxiter=1000, printrates=False)
    solver.Solve(rhs=rhs, sol=du, initialize=False)
    sol.data += du
    T["solve"] = time.perf_counter() - t1
    res["iterations"] = solver.iterations
    U, P = gu, gp
    ndof = V.ndofglobal + Q.ndofglobal
else:
    X = V * Q
    (u, p), (v, q) = X.TnT()
    k = (2 * InnerProduct(eps(u), eps(v)) - div(u) * q - div(v) * p) * dx
    if method.endswith("+reg"):
        k += -1e-10 * p * q * dx
    K = BilinearForm(k)
    gf = GridFunction(X)
    gf.components[0].Set(g, definedon=mesh.Boundaries("in"))
    if method == "prod":
        A = BilinearForm(X)
        A += (2 * InnerProduct(eps(u), eps(v)) + p * q) * dx
        pre = Preconditioner(A, "bddc")
        A.Assemble()
    K.Assemble()
    T["assemble(+bddc)"] = time.perf_counter() - t0
    rhs = gf.vec.CreateVector()
    rhs.data = -K.mat * gf.vec
    du = gf.vec.CreateVector(); du[:] = 0
    t1 = time.perf_counter()
    if method == "prod":
        solver = MinResSolver(mat=K.mat, pre=pre.mat, tol=TOL, maxiter=1000, printrates=False)
        solver.Solve(rhs=rhs, sol=du, initialize=False)
        res["iterations"] = solver.iterations
    else:
        name = method.split(":")[1].replace("+reg", "")
        try:
            inv = K.mat.Inverse(X.FreeDofs(), inverse=name)
            T["factor"] = time.perf_counter() - t1
            du.data = inv * rhs
        except Exception as e:  # noqa
            say(f"direct solver {name!r} FAILED: {type(e).__name__}: {e}")
            raise SystemExit(0)
    gf.vec.data += du
    T["solve"] = time.perf_counter() - t1
    # the true residual on the free dofs (MPI-safe: a Projector and Norm)
    r = gf.vec.CreateVector()
    r.data = K.mat * gf.vec
    proj = ng.Projector(X.FreeDofs(), True)
    r.data = proj * r
    res["residual_free"] = ng.Norm(r)
    U, P = gf.components
    ndof = X.ndofglobal
res.update(figures(U, P))
loc = np.abs(U.vec.FV().NumPy()[: len(U.vec) // 3]) if len(U.vec) else np.zeros(1)
res["max_ux_coef"] = comm.allreduce(float(loc.max()) if loc.size else 0.0, op=MPI.MAX)
T["total"] = time.perf_counter() - t0 + info["t_mesh"]
say(f"STOKES method={method} wb_withedges={wbe} ranks={comm.size} ndof={ndof} "
    f"prisms={info['prisms']}")
for kk, vv in res.items():
    say(f"   {kk:14s} {vv!r}")
say("   times " + ", ".join(f"{k} {v:.2f}s" for k, v in T.items()))
