"""The same numbers at any thread count and in every run (issue 50, item 3).

NGSolve's coloured assembly (``Apply``, ``AssembleLinearization``, ``Assemble``, ``Set``), its
matrix-vector products and ``InnerProduct``/``Norm`` add in a fixed order whatever the threads,
given the space's colouring of its elements. Three things it does under the task manager do
not: a space colours its elements in parallel when it is made (``FESpace::FinalizeUpdate``:
each thread locks the DOFs of the element it colours, so the colours, and the order in which
the elements' values are added into a shared DOF, differ from run to run); ``Integrate`` adds
the elements' values with atomic adds in the order the threads reach them; ``sparsecholesky``
merges its blocks under locks and atomic adds in the factorisation and the solves
(``shared/notes/unilateral-contact-exit.md`` section 3: 3 distinct results of 30 ``Integrate``
calls, 10 of 10 factor+solves, on 2 threads). Hence:

- ``fe_space``: every space of hotroll made in one thread (the colours of the element order).
  ``tests/fem/test_reproducible.py`` fails where a module makes a space itself.
- ``integrate``: every integral of hotroll, the elements' values (each written to its own slot,
  ``element_wise=True``) summed in Python (``math.fsum``: correctly rounded, so independent of
  the order too). ``tests/fem/test_reproducible.py`` fails where a module calls NGSolve's
  ``Integrate`` itself.
- ``threaded``: a run's thread count (BLAS held to one thread); ``parallel``: the task manager
  around a short region of work (a Newton step, the meshing, the measures) with the threads no
  other busy process wants (``threads_now``), serial between the regions.
- The flow's linear solver is UMFPACK (``forms.LINEAR_SOLVERS``): sequential, the same factors
  in every run. ``sparsecholesky`` is not with 2 threads: with no task manager it starts one of
  its own (``SparseCholeskyTM::FactorSPD1``: ``RunWithTaskManager``) with ``SetNumThreads``'s
  count (a Taylor-Hood Stokes matrix: 8 distinct solutions of 8 with 2 threads, 1 of 8 with
  one). ``threaded`` sets that count to 1 and only ``parallel`` raises it. The flow's
  ``sparsecholesky+gmres`` (the 2D fallback when UMFPACK fails, a choice of the 3D strip) runs
  inside a Newton step's region but factorises and solves in ``one_thread``: the same bits at
  any thread count (``tests/solvers/test_spread_3d.py``; 2 threads' runs differed before).
"""
from __future__ import annotations

import math
import os
from contextlib import contextmanager

#: the task manager ``parallel`` entered, while it runs
_running: list = []
#: the thread count of each open parallel region (outermost first; 1: a serial region)
_regions: list = []
#: the thread count the run asked for (``threaded``): an int, or "auto"
_requested: list = ["auto"]
#: set while ``threaded`` runs (the outer one holds)
_threaded: list = []
#: the thread counts ``parallel`` used in this process (``threads_used``)
_used: set = set()
#: "auto": at most this many threads. The 2D assembly of a pass has a few 10^4 elements; more
#: threads than this were not measured (a 2-core machine, [E]) and cost a thread start each
AUTO_MAX = 4


def integrate(f, mesh, vb=None, order: int = 5, definedon=None) -> float:
    """NGSolve's ``Integrate(f, mesh, vb, order, definedon)`` of a scalar coefficient function
    (or of a ``SumOfIntegrals`` over volume elements, ``dx(element_boundary=True)`` included)
    summed over the elements in a fixed order: the same float at any thread count."""
    from ngsolve import VOL, Integrate
    from ngsolve.comp import SumOfIntegrals

    with parallel():
        if isinstance(f, SumOfIntegrals):
            values = Integrate(f, mesh, element_wise=True)
        else:
            values = Integrate(f, mesh, VOL if vb is None else vb, order=order,
                               definedon=definedon, element_wise=True)
    return math.fsum(values.NumPy())


def cores() -> int:
    """The cores this process may run on: its affinity (``os.cpu_count`` elsewhere), capped by
    a cgroup v2 CPU quota where one is set (``/sys/fs/cgroup/cpu.max``: a container limited to
    2 CPUs on a larger host)."""
    try:
        n = len(os.sched_getaffinity(0))
    except AttributeError:          # not Linux
        n = os.cpu_count() or 1
    try:
        with open("/sys/fs/cgroup/cpu.max") as f:
            quota, period = f.read().split()[:2]
        if quota != "max":
            n = min(n, max(1, int(float(quota) / float(period))))
    except (OSError, ValueError):
        pass
    return n


def others_running() -> int:
    """How many other threads want a core now: the kernel's count of runnable threads
    (``/proc/loadavg``'s fourth field, this thread included; read in about 10 us) minus one;
    elsewhere the one-minute load average (it lags by about a minute) minus one."""
    try:
        with open("/proc/loadavg", "rb") as f:
            running = int(f.read().split()[3].split(b"/")[0])
    except (OSError, IndexError, ValueError):
        try:
            running = round(os.getloadavg()[0])
        except (AttributeError, OSError):
            return 0
    return max(0, running - 1)


def threads_now(requested: int | str | None = None) -> int:
    """The threads to assemble with now: ``requested`` (an int, or "auto": ``AUTO_MAX``; None:
    what ``threaded`` set) capped by the cores no other runnable thread wants. NGSolve's
    workers wait actively and every parallel loop waits for all of them: a worker that shares
    its core with another busy process made a pass 4-8x slower than one thread (issue 51), so a
    core another process wants is never taken."""
    req = _requested[0] if requested is None else requested
    n = AUTO_MAX if req == "auto" else int(req)
    n = min(n, cores())
    if n <= 1:
        return 1
    return max(1, min(n, cores() - others_running()))


def threads_used() -> list[int]:
    """The thread counts ``parallel`` assembled with in this process, sorted (1 when it never
    went parallel)."""
    return sorted(_used) or [1]


@contextmanager
def threaded(threads: int | str | None = None):
    """``with threaded(n):`` a run with up to ``n`` threads (an int, "auto"; None: as set).
    Outside ``parallel`` NGSolve runs serially (``SetNumThreads(1)``: no task manager, whose
    idle workers spin, and ``sparsecholesky`` starts none of its own); BLAS held to one
    thread. Nested: the outer one holds."""
    if _threaded:
        yield
        return
    import ngsolve
    from threadpoolctl import threadpool_limits

    previous, count = _requested[0], ngsolve.GetNumThreads()
    if threads is not None:
        _requested[0] = threads
    _used.clear()
    ngsolve.SetNumThreads(1)
    _threaded.append(threads)
    try:
        with threadpool_limits(limits=1, user_api="blas"):
            yield
    finally:
        _threaded.pop()
        _requested[0] = previous
        ngsolve.SetNumThreads(count)     # NGSolve's count as the caller had it


@contextmanager
def parallel():
    """``with parallel():`` one parallel region: NGSolve's task manager with ``threads_now()``
    threads, sampled at the region's start, or serial where another process wants the cores.
    The regions (issue 51): each Newton or Picard step (``fem/nonlinear.py``: its assembly,
    solve, line search and the couplings it calls), the meshing and the forms' set-up, the
    measures (``workflows/runner.py``), and any assembly or ``integrate`` outside them.
    Idle workers spin while the main thread runs Python or a sequential factorisation, so a
    region is short and started only on free cores. Inside a region (parallel or serial)
    another is a no-op: the outer region's count holds for its whole duration.
    Coloured assembly, mat-vecs and inner products give the same bits at any thread count
    (``fe_space``, ``integrate``). Entering and leaving cost 0.1 ms on a quiet machine."""
    if _regions:                      # inside a region: its count holds
        yield
        return
    n = threads_now()
    _used.add(n)
    _regions.append(n)
    if n == 1:
        try:
            yield
        finally:
            _regions.pop()
        return
    import ngsolve

    ngsolve.SetNumThreads(n)
    tm = ngsolve.TaskManager()
    tm.__enter__()
    _running.append(tm)
    try:
        yield
    finally:
        _running.pop().__exit__(None, None, None)
        ngsolve.SetNumThreads(1)
        _regions.pop()


@contextmanager
def serial():
    """``with serial():`` the code inside runs without the task manager ``parallel`` started
    (left and entered again: 0.1 ms on a quiet machine; for rare calls only)."""
    if not _running:
        yield
        return
    tm = _running.pop()
    tm.__exit__(None, None, None)
    try:
        yield
    finally:
        tm.__enter__()
        _running.append(tm)


@contextmanager
def one_thread():
    """``with one_thread():`` the code inside runs in this thread alone: out of the task manager
    (``serial``) and with NGSolve's thread count 1, so that ``sparsecholesky``, which starts a
    task manager of its own with that count, factorises and solves sequentially: the same bits
    in every run (2 threads: 8 distinct solutions of 8; its factorisation is no faster with 2,
    ``../shared/notes/3d-steady.md``)."""
    import ngsolve

    count = ngsolve.GetNumThreads()
    with serial():
        ngsolve.SetNumThreads(1)
        try:
            yield
        finally:
            ngsolve.SetNumThreads(count)


def fe_space(make, *args, **kwargs):
    """The finite element space ``make(*args, **kwargs)`` (an NGSolve space class, or
    ``operator.mul`` of spaces: their product) made outside the task manager. A space colours
    its elements when it is made (``FESpace::FinalizeUpdate``): elements of one colour share no
    DOF, and assembly (``Apply``, ``AssembleLinearization``, ``Assemble``, ``Set``) adds the
    elements' values into a shared DOF or matrix entry colour by colour. Under the task manager
    the colouring runs in parallel, the elements taken by whichever thread locks their DOFs
    first: another colouring in each run, the sums in another order, the last bits different
    (Example 1's first residual differed run to run from the same iterate). Made in one thread
    the colours are those of the element order, the same in every run and at any thread count,
    and then so is every assembled number (each colour's elements write disjoint entries)."""
    with serial():
        return make(*args, **kwargs)


def find_points(mesh, x, y):
    """NGSolve's ``mesh(x, y)`` (a MeshPoint array) found in one thread: threaded, a point on
    an edge shared by two elements was found in either, by the thread's last element (a
    thermal pass's strip temperatures then differed in the last bits run to run)."""
    with serial():
        return mesh(x, y)
