"""Step 5 probe: hotroll's own pieces on the distributed mesh (imported, not modified).
- fem.spaces.taylor_hood (with the contact multiplier: a Compress space)
- fem.reproducible.integrate (element_wise values, math.fsum): rank-local
- fem.extruded_mesh.LayerCopy: global vertex numbering k * nv + i
- a numpy norm of a vector (fem/nonlinear._Workspace.norm) against NGSolve's Norm"""
import sys, math
sys.path.insert(0, "/tmp/mpispike")
from common import *
import ngsolve as ng
from ngsolve import CF, x, y, z, sin, VOL, Integrate
from hotroll.fem.spaces import taylor_hood
from hotroll.fem.reproducible import integrate

mesh, info = distributed_prism_mesh()
X = taylor_hood(mesh, dirichletx="in", dirichlety="in|sym", dirichletz="in|zsym",
                multiplier_on="top")
say("taylor_hood(multiplier_on='top') ndofglobal", X.ndofglobal,
    "components", [c.ndofglobal for c in X.components])
f = sin(3 * x) * y * (1 + z) + x * x
loc = integrate(f, mesh)                     # hotroll's: fsum of this rank's element values
ngs = Integrate(f, mesh, order=5)            # NGSolve's: reduced over the ranks
vals = Integrate(f, mesh, VOL, order=5, element_wise=True).NumPy().copy()
allv = comm.gather(vals)
locs = comm.gather(loc)
if comm.rank == 0:
    everything = np.concatenate(allv)
    print(f"hotroll integrate per rank {locs}; NGSolve Integrate {ngs!r}; "
          f"gather+fsum {math.fsum(everything)!r}; sum of rank fsums {math.fsum(locs)!r}")
    np.save(f"/tmp/mpispike/elvals_{comm.size}.npy", np.sort(everything))
# a vector's norm: hotroll's numpy way vs NGSolve's
gf = ng.GridFunction(X)
gf.components[0].Set(CF((x, y, z)))
a = gf.vec.FV().NumPy()
n_local = float(np.linalg.norm(a))
n_sumsq = math.sqrt(comm.allreduce(float(a @ a)))
say(f"|vec|: NGSolve Norm {ng.Norm(gf.vec)!r}; sqrt(allreduce of local numpy sums) {n_sumsq!r} "
    f"(shared DOFs counted on every rank that holds them)")
rows = comm.gather((comm.rank, n_local, mesh.nv, X.ndof))
if comm.rank == 0:
    for r in rows:
        print("   rank %d: local numpy norm %.6f, local nv %d, local ndof %d" % r)
# LayerCopy: a 2D mesh on every rank (cheap), the distributed 3D mesh
from hotroll.fem.extruded_mesh import LayerCopy
m2 = mesh2d(0.025)
try:
    lc = LayerCopy(m2, mesh)
    msg = f"built: layers {lc.layers} (expected 4)"
except Exception as e:   # noqa
    msg = f"{type(e).__name__}: {e}"
msgs = comm.gather(msg)
if comm.rank == 0:
    for i, m_ in enumerate(msgs):
        print(f"   LayerCopy on rank {i}: {m_}")
