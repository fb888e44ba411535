"""Step 1: Poisson -Delta u = 1 on the unit cube, H1 order 2, BDDC + CG; serial (python) or
mpiexec -n 2. Rank 0 makes the mesh and distributes it."""
import time
from mpi4py import MPI
import netgen.meshing
from netgen.csg import unit_cube
from ngsolve import *
from ngsolve.krylovspace import CGSolver

comm = MPI.COMM_WORLD
t0 = time.perf_counter()
if comm.rank == 0:
    ngmesh = unit_cube.GenerateMesh(maxh=0.12)
    if comm.size > 1:
        ngmesh.Distribute(comm)
else:
    ngmesh = netgen.meshing.Mesh.Receive(comm)
mesh = Mesh(ngmesh)
import sys
wbe = "--noedges" not in sys.argv
fes = H1(mesh, order=2, dirichlet=".*", wb_withedges=wbe)
u, v = fes.TnT()
a = BilinearForm(grad(u) * grad(v) * dx)
pre = Preconditioner(a, "bddc")
a.Assemble()
f = LinearForm(1 * v * dx).Assemble()
gfu = GridFunction(fes)
inv = CGSolver(a.mat, pre.mat, tol=1e-12, maxiter=500)
gfu.vec.data = inv * f.vec
ip = InnerProduct(gfu.vec, f.vec)
val = gfu(mesh(0.5, 0.5, 0.5)) if mesh.GetNE(VOL) and mesh.Contains(0.5, 0.5, 0.5) else None
vals = comm.allgather(val)
l2 = Integrate(gfu * gfu, mesh)   # does Integrate reduce over the ranks?
l2_local = sum(Integrate(gfu * gfu, mesh, element_wise=True).NumPy())
l2_sum = comm.allreduce(l2_local)
if comm.rank == 0:
    print(f"ranks {comm.size} ndof(global) {fes.ndofglobal} (u,f)={ip:.15e} u(centre)={[x for x in vals if x is not None]} "
          f"int u^2={l2:.15e} local elementwise sum={l2_local:.6e} allreduced={l2_sum:.15e} CG its {inv.iterations} time {time.perf_counter()-t0:.2f}s", flush=True)
print(f"  rank {comm.rank}: local VOL elements {mesh.GetNE(VOL)}, local ndof {fes.ndof}", flush=True)
