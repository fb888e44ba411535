"""Can rank 0 send the 2D pass's mesh and a GridFunction to the other ranks (mpi4py pickle)?"""
import sys
sys.path.insert(0, "/tmp/mpispike")
from common import *
import ngsolve as ng
from ngsolve import CF, x, y
obj = None
if comm.rank == 0:
    m2 = mesh2d(0.025)
    g = ng.GridFunction(ng.VectorH1(m2, order=2)); g.Set(CF((x * y, x + y)))
    obj = (m2, g)
t = time.perf_counter()
m2, g = comm.bcast(obj)
print(f"rank {comm.rank}: 2D mesh nv {m2.nv} ne {m2.ne} comm size {m2.comm.size}, "
      f"g ndof {g.space.ndof} g(0.2,0.05) {g(m2(0.2, 0.05))} {time.perf_counter() - t:.3f}s", flush=True)
