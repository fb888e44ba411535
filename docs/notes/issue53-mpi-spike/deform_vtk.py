"""SetDeformation (Spread3D moves the mesh by a P2 VectorH1 field) and VTKOutput
(spread_record.write_vtk_3d) on the distributed mesh."""
import sys, os, glob
sys.path.insert(0, "/tmp/mpispike")
from common import *
import ngsolve as ng
from ngsolve import CF, x, y, z, sin, VOL, BND, Integrate
mesh, info = distributed_prism_mesh()
V = ng.VectorH1(mesh, order=2)
d = ng.GridFunction(V)
d.Set(CF((0.01 * sin(10 * x), 0.02 * y * x, 0.1 * z * x * (1 - y))))
mesh.SetDeformation(d)
vol = Integrate(CF(1), mesh)
edge = Integrate(CF(1), mesh, BND, definedon=mesh.Boundaries("edge"))
say(f"ranks {comm.size}: deformed volume {vol!r}, edge area {edge!r}")
out = f"/tmp/mpispike/vtk_{comm.size}"
try:
    ng.VTKOutput(mesh, coefs=[d], names=["d"], filename=out, subdivision=0).Do()
    comm.Barrier()
    say("VTK files:", sorted(os.path.basename(f) for f in glob.glob(out + "*")))
except Exception as e:  # noqa
    print(f"rank {comm.rank} VTKOutput failed: {type(e).__name__}: {e}", flush=True)
mesh.UnsetDeformation()
