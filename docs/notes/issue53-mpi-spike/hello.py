from mpi4py import MPI
import netgen.config, ngsolve
c = MPI.COMM_WORLD
print(c.rank, c.size, MPI.Get_library_version().splitlines()[0], netgen.config.USE_MPI, ngsolve.__version__, flush=True)
