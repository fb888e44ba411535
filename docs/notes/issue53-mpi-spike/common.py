"""Shared set-up of the spike: hotroll's extruded prism mesh made on rank 0 and distributed."""
import time
import numpy as np
from mpi4py import MPI
import netgen.meshing

comm = MPI.COMM_WORLD
L, H, W = 0.4, 0.1, 0.2      # x length, y half thickness, z half width (m)


def mesh2d(maxh):
    from netgen.geom2d import SplineGeometry
    import ngsolve
    g = SplineGeometry()
    p = [g.AppendPoint(*q) for q in [(0, 0), (L, 0), (L, H), (0, H)]]
    # outward normal on the right of a -> b: counter-clockwise polygon, like hotroll's
    for a, b, name in [(0, 1, "sym"), (1, 2, "out"), (2, 3, "top"), (3, 0, "in")]:
        g.Append(["line", p[a], p[b]], bc=name)
    return ngsolve.Mesh(g.GenerateMesh(maxh=maxh))


def distributed_prism_mesh(maxh=0.025, layers=4):
    """(ngsolve Mesh, info). Rank 0: the 2D mesh, hotroll's extrude, Distribute; others Receive."""
    import ngsolve
    t0 = time.perf_counter()
    info = {}
    if comm.rank == 0:
        from hotroll.fem.extruded_mesh import extrude, width_axis
        m2 = mesh2d(maxh)
        z = np.linspace(0.0, W, layers + 1)
        m3 = extrude(m2, z)
        info = {"triangles": m2.ne, "prisms": m3.ne, "nv": m3.nv,
                "bnd": sorted(set(m3.GetBoundaries()))}
        ng = m3.ngmesh
        if comm.size > 1:
            ng.Distribute(comm)
    else:
        ng = netgen.meshing.Mesh.Receive(comm)
    info = comm.bcast(info)
    mesh = ngsolve.Mesh(ng)
    info["t_mesh"] = time.perf_counter() - t0
    return mesh, info


def say(*a):
    if comm.rank == 0:
        print(*a, flush=True)
