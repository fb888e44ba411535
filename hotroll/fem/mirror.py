"""NGSolve's MPI for a serial model's flow solve (issue 53): the serial mesh and its fields on
every rank, the Newton system's assembly and linear solves on a distributed copy of the mesh.

Every rank runs the serial model (the 2D pass, the 3D strip's surfaces, the figures: the same
deterministic code on the same data, so the same bits on every rank); what Newton asks of its
system (``fem/nonlinear.NonlinearSystem``: the residual, the Jacobian and its solves) is done
on the mesh distributed over the ranks (``distribute``, netgen's METIS split) by a second form
built there on mirrored fields (``FieldMirror``). A vector crosses between the two numberings
through ``DofMap``: the DOFs of each element of the distributed mesh are those of the same
element of the serial one, in the same order (the element found by its vertices' reference
coordinates, which ``Distribute`` copies bitwise; its vertices keep their order). A gathered
vector is assembled on every rank from all ranks' parts in rank order, so the serial side's
Newton makes the same decisions everywhere. The linear solves are NGSolve's on the
distributed matrix: a direct solver's name gives its ``MasterInverse`` (the matrix gathered
to rank 0 and factorised there: the serial figures to rounding, no speed-up of the
factorisation; docs/notes/issue53-mpi-spike/README.md).
netgen's rank 0 keeps no elements: ``mpiexec -n N`` has N - 1 ranks that assemble.
"""
from __future__ import annotations

import os

import numpy as np

from hotroll.fem.krylov import numpy_operator

#: environment variables an MPI launcher (MPICH's hydra, Open MPI) sets in every rank
LAUNCHED = ("PMI_SIZE", "OMPI_COMM_WORLD_SIZE")


def world():
    """mpi4py's COMM_WORLD where this process is one of several ranks started by an MPI
    launcher (``mpiexec -n N``, N > 1), else None (a serial run; mpi4py is not imported)."""
    size = next((os.environ[k] for k in LAUNCHED if k in os.environ), "1")
    if int(size) <= 1:
        return None
    try:
        from mpi4py import MPI
    except ImportError as e:      # every rank would run the whole case alone, and write it
        raise RuntimeError(f"started by an MPI launcher ({size} ranks) without mpi4py: "
                           "pip install mpi4py mpich (scripts/setup.sh installs them)") from e
    return MPI.COMM_WORLD


def abort_on_error(comm) -> None:
    """An exception on one rank ends every rank (the others would wait in a collective call):
    the traceback printed, then ``comm.Abort(1)``."""
    import sys

    hook = sys.excepthook

    def handler(kind, value, tb):
        hook(kind, value, tb)
        sys.stderr.flush()
        comm.Abort(1)

    sys.excepthook = handler


def distribute(mesh, comm):
    """The undeformed copy of the serial NGSolve ``mesh`` (the same on every rank) distributed
    over ``comm``'s ranks (rank 0 splits and sends, the others receive)."""
    import netgen.meshing
    import ngsolve as ng

    if comm.rank == 0:
        ngm = mesh.ngmesh.Copy()
        ngm.Distribute(comm)
    else:
        ngm = netgen.meshing.Mesh.Receive(comm)
    return ng.Mesh(ngm)


def _elements(mesh) -> dict:
    """{(VOL or BND, the vertices' reference coordinates sorted): (element, in its order)}."""
    from ngsolve import BND, VOL

    points = [tuple(v.point) for v in mesh.vertices]
    out = {}
    for vb in (VOL, BND):
        for el in mesh.Elements(vb):
            xs = tuple(points[v.nr] for v in el.vertices)
            out[(vb == VOL, tuple(sorted(xs)))] = (el, xs)
    return out


class DofMap:
    """The DOFs of the space ``dist`` on the distributed mesh in the numbering of the same
    space ``serial`` on the serial mesh (module docstring), over ``comm``."""

    def __init__(self, serial, dist, comm, elements: tuple | None = None):
        """``elements``: ``_elements`` of the serial and the distributed mesh, where known."""
        es, ed = elements or (_elements(serial.mesh), _elements(dist.mesh))
        index = np.full(dist.ndof, -1, dtype=np.int64)
        for key, (el, xs) in ed.items():
            found = es.get(key)
            if found is None or found[1] != xs:
                raise RuntimeError("DofMap: an element of the distributed mesh is not the "
                                   "serial one's (vertices moved or reordered)")
            for a, b in zip(dist.GetDofNrs(el), serial.GetDofNrs(found[0])):
                if a >= 0:
                    if index[a] >= 0 and index[a] != b:
                        raise RuntimeError("DofMap: a DOF is two serial DOFs")
                    index[a] = b
        if (index < 0).any():
            raise RuntimeError(f"DofMap: {(index < 0).sum()} DOFs of rank {comm.rank} unmapped")
        self.index, self.comm, self.ndof = index, comm, serial.ndof
        #: every rank's index array, in rank order (``gather``)
        self.parts = comm.allgather(index)
        covered = np.zeros(self.ndof, dtype=bool)
        for part in self.parts:
            covered[part] = True
        if not covered.all():
            raise RuntimeError(f"DofMap: {(~covered).sum()} serial DOFs on no rank")

    def scatter(self, values: np.ndarray, vec) -> None:
        """The serial ``values`` into the distributed vector ``vec`` (cumulated)."""
        from ngsolve.la import PARALLEL_STATUS

        vec.FV().NumPy()[:] = values[self.index]
        vec.SetParallelStatus(PARALLEL_STATUS.CUMULATED)

    def gather(self, vec, out: np.ndarray) -> None:
        """The distributed vector ``vec`` into the serial ``out``, the same bits on every rank
        (its cumulated values, every rank's in rank order)."""
        vec.Cumulate()
        for idx, values in zip(self.parts, self.comm.allgather(vec.FV().NumPy().copy())):
            out[idx] = values


class FieldMirror:
    """GridFunctions of the serial mesh and their copies on the distributed one, copied over
    by ``sync``."""

    def __init__(self, serial_mesh, dist_mesh, comm):
        self.mesh, self.comm, self.pairs = dist_mesh, comm, []
        self.elements = (_elements(serial_mesh), _elements(dist_mesh))

    def dof_map(self, serial_space, dist_space) -> DofMap:
        return DofMap(serial_space, dist_space, self.comm, self.elements)

    def mirror(self, gf, into=None):
        """``gf``'s copy on the distributed mesh (``into``, or a new GridFunction of the same
        kind of space and order), kept for ``sync``, copied now."""
        import ngsolve as ng

        from hotroll.fem.reproducible import fe_space

        if into is None:
            into = ng.GridFunction(fe_space(type(gf.space), self.mesh,
                                            order=gf.space.globalorder))
        dmap = self.dof_map(gf.space, into.space)
        self.pairs.append((gf, into, dmap))
        dmap.scatter(gf.vec.FV().NumPy(), into.vec)
        return into

    def sync(self) -> None:
        for gf, into, dmap in self.pairs:
            dmap.scatter(gf.vec.FV().NumPy(), into.vec)


def _operator(system, apply, inverse=None, update=None):
    """``apply(x, y)`` (distributed vectors: y = op x) in the serial numbering as an NGSolve
    matrix (``krylov.numpy_operator``) through ``system``'s ``DofMap``; ``inverse``,
    ``update``: its ``Inverse`` and ``Update``."""
    dist = system.dist.gf.vec
    xd, yd = dist.CreateVector(), dist.CreateVector()

    def serial(x: np.ndarray) -> np.ndarray:
        system.dmap.scatter(x, xd)
        apply(xd, yd)
        out = np.empty_like(x)
        system.dmap.gather(yd, out)
        return out

    return numpy_operator(serial, system.gf.vec, inverse, update)


class MirroredSystem:
    """``fem/nonlinear.newton``'s system (``NonlinearSystem``): the serial problem ``serial``
    (its unknown, free DOFs, norms and kept inverses: Newton's state and decisions, the same
    on every rank) with the residual, the Jacobian and the linear solves of the distributed
    problem ``dist`` (the same form on the distributed mesh, its data mirrored by
    ``FieldMirror``), over ``comm``."""

    def __init__(self, serial, dist, comm):
        self.serial, self.dist, self.comm = serial, dist, comm
        self.gf = serial.gf
        self.dmap = DofMap(serial.fes, dist.fes, comm)
        self.a_newton = _Form(self, dist.a_newton)
        self.a_jacobian = None if dist.a_jacobian is None else _Form(self, dist.a_jacobian)
        if getattr(dist, "prepare", None) is not None:
            self.prepare = self._prepare

    def __getattr__(self, name):        # the serial problem's state: free DOFs, norms, ...
        return getattr(self.serial, name)

    @property
    def inverses(self) -> dict:         # the serial problem's: its set_free clears them
        return self.serial.inverses

    def sync(self) -> None:
        """The distributed unknown set to the serial one."""
        self.dmap.scatter(self.gf.vec.FV().NumPy(), self.dist.gf.vec)

    def _prepare(self, iteration: int) -> bool:
        self.sync()
        return self.dist.prepare(iteration)

    def inverse(self, form, freedofs, name: str):
        """The inverse of the distributed ``form``'s matrix by the NGSolve solver ``name`` on
        the serial ``freedofs`` (a direct solver's name: its MasterInverse), as an operator
        whose ``Update`` factorises the matrix's new values; every rank raises where one
        failed."""
        from ngsolve import BitArray

        local = BitArray(np.array(list(freedofs), dtype=bool)[self.dmap.index].tolist())
        held = {}

        def factorise():
            failure = ""
            try:
                held["inv"] = form.mat.Inverse(local, inverse=name)
            except Exception as e:  # noqa: BLE001 - NGSolve raises plain exceptions
                failure = str(e) or type(e).__name__
            failures = [f for f in self.comm.allgather(failure) if f]
            if failures:
                raise RuntimeError(f"{name} on the distributed matrix: {failures[0]}")

        factorise()
        return _operator(self, lambda x, y: _mult(held["inv"], x, y),
                         update=factorise)


def _mult(op, x, y) -> None:
    y.data = op * x


class _Form:
    """A distributed form seen in the serial numbering: ``Apply``, ``AssembleLinearization``,
    ``Assemble`` and its matrix ``mat`` (an operator whose ``Inverse`` is
    ``MirroredSystem.inverse``)."""

    def __init__(self, system, form):
        self.system, self.form = system, form
        self._x, self._y = system.dist.gf.vec.CreateVector(), system.dist.gf.vec.CreateVector()
        self.mat = _operator(system, lambda x, y: _mult(form.mat, x, y),
                             inverse=lambda free, name: system.inverse(form, free, name))

    def Apply(self, x, y) -> None:                     # noqa: N802
        s = self.system
        s.sync()
        s.dmap.scatter(x.FV().NumPy(), self._x)
        self.form.Apply(self._x, self._y)
        s.dmap.gather(self._y, y.FV().NumPy())

    def AssembleLinearization(self, x) -> None:        # noqa: N802
        s = self.system
        s.sync()
        s.dmap.scatter(x.FV().NumPy(), self._x)
        self.form.AssembleLinearization(self._x)

    def Assemble(self) -> None:                        # noqa: N802
        self.system.sync()
        self.form.Assemble()
