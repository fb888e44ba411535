"""Step 2: does Distribute work on hotroll's hand-made prism mesh; do the boundary names survive?"""
import sys
sys.path.insert(0, "/tmp/mpispike")
from common import *
from ngsolve import BND, VOL, Integrate, CF, specialcf

mesh, info = distributed_prism_mesh()
say("ranks", comm.size, info)
names = list(mesh.GetBoundaries())
counts = {}
for el in mesh.Elements(BND):
    counts[el.mat] = counts.get(el.mat, 0) + 1
types = {}
for el in mesh.Elements(VOL):
    types[str(el.type)] = types.get(str(el.type), 0) + 1
rows = comm.gather((comm.rank, mesh.ne, mesh.nv, sorted(set(names)), types, counts))
# areas of the named faces (Integrate reduces over ranks)
area = {b: Integrate(CF(1), mesh, BND, definedon=mesh.Boundaries(b)) for b in info["bnd"]}
vol = Integrate(CF(1), mesh, VOL)
if comm.rank == 0:
    for r in rows:
        print("  rank %d: %d VOL elements, %d vertices, boundary names %s, types %s, bnd elements %s" % r)
    print("  areas", {k: round(v, 12) for k, v in area.items()}, "volume", vol)
