"""Step 5 probe: getting a distributed solution back to rank 0 in the serial numbering.
(1) GridFunction.Save(file, parallel=True) -> a serial process Load(file, parallel=True)
(2) rank 0 keeps a serial copy of the mesh (ngmesh.Copy() before Distribute): can it build a
    space on it while the others hold the distributed mesh?
(3) in memory: each rank sends its DOFs' node keys (sorted *global* vertex numbers are not
    exposed in Python; the node's coordinates are) and values; rank 0 maps them onto the
    serial space's DOFs."""
import sys
sys.path.insert(0, "/tmp/mpispike")
from common import *
import ngsolve as ng
from ngsolve import CF, x, y, z, VOL, NodeId, VERTEX, EDGE, FACE

maxh, layers = 0.025, 4
mode = sys.argv[1]
serial_copy = None
if comm.rank == 0:
    from hotroll.fem.extruded_mesh import extrude
    m3 = extrude(mesh2d(maxh), np.linspace(0, W, layers + 1))
    ngm = m3.ngmesh
    if mode == "copy":
        serial_copy = ngm.Copy()
        print("serial copy comm size:", serial_copy.comm.size, flush=True)
    if comm.size > 1:
        ngm.Distribute(comm)
else:
    ngm = netgen.meshing.Mesh.Receive(comm)
mesh = ng.Mesh(ngm)
V = ng.VectorH1(mesh, order=2)
f = CF((x * x + y * z, y * y * x, z * z + x * y))          # P2-exact? (degree 2: yes)
gf = GridFunction = ng.GridFunction(V)
gf.Set(f)
if mode == "save":
    gf.Save("/tmp/mpispike/gf_%d.sol" % comm.size, parallel=True)
    say("saved")
elif mode == "load":      # a serial process: load what a run of N ranks saved
    n = int(sys.argv[2])
    g2 = ng.GridFunction(V)
    g2.Load("/tmp/mpispike/gf_%d.sol" % n, parallel=True)
    d = g2.vec.FV().NumPy() - gf.vec.FV().NumPy()
    print("loaded file of", n, "ranks into the serial space: max |diff| to serial Set:", np.abs(d).max())
elif mode == "copy":
    if comm.rank == 0:
        t = time.perf_counter()
        ms = ng.Mesh(serial_copy)
        Vs = ng.VectorH1(ms, order=2)
        print("rank 0 serial space on the copy: ndof", Vs.ndof, "%.3fs" % (time.perf_counter() - t), flush=True)
    comm.Barrier()
    say("done")
elif mode == "coords":
    # node key: the node's vertices' coordinates, sorted and rounded (exact copies of rank 0's)
    def keys(m, space):
        P = np.array([v.point for v in m.vertices])
        out = []
        for comp in range(1):   # scalar component 0's DOFs; the others are offset blocks
            pass
        S = space.components[0] if hasattr(space, "components") and len(space.components) else space
        n = S.ndof
        key = [None] * n
        for typ, nodes in ((VERTEX, m.vertices), (EDGE, m.edges), (FACE, m.faces)):
            for node in nodes:
                vs = [node.nr] if typ == VERTEX else [v.nr for v in node.vertices]
                k = tuple(sorted(tuple(np.round(P[i], 12)) for i in vs))
                for j, dof in enumerate(S.GetDofNrs(NodeId(typ, node.nr))):
                    if dof >= 0:
                        key[dof] = (k, j)
        return key, n
    t = time.perf_counter()
    k_loc, n_loc = keys(mesh, V)
    v_loc = gf.vec.FV().NumPy().reshape(3, -1) if n_loc else np.zeros((3, 0))
    parts = comm.gather((k_loc, v_loc))
    if comm.rank == 0:
        from hotroll.fem.extruded_mesh import extrude
        ser = extrude(mesh2d(maxh), np.linspace(0, W, layers + 1)) if comm.size > 1 else mesh
        Vs = ng.VectorH1(ser, order=2)
        ks, ns = keys(ser, Vs)
        index = {k: i for i, k in enumerate(ks)}
        out = np.full((3, ns), np.nan)
        for kl, vl in parts:
            idx = np.array([index[k] for k in kl], dtype=int)
            out[:, idx] = vl
        ref = ng.GridFunction(Vs); ref.Set(f)
        print("gathered by coordinates: missing", int(np.isnan(out).sum()), "max |diff|",
              np.nanmax(np.abs(out.ravel() - ref.vec.FV().NumPy())), "%.3fs" % (time.perf_counter() - t))
