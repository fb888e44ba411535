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
- ``threaded``: the task manager hotroll runs in, its thread count set (BLAS held to one thread).
- The flow's linear solver is UMFPACK (``forms.LINEAR_SOLVERS``): sequential, the same factors
  in every run. ``sparsecholesky`` is not with 2 threads, and it cannot be made so from
  outside: with no task manager it starts one of its own with every core
  (``SparseCholeskyTM::FactorSPD1``: ``RunWithTaskManager``), so factorising outside the task
  manager did not help (a Taylor-Hood Stokes matrix: 8 distinct solutions of 8 with no task
  manager, 8 of 8 in a 2-thread one, 1 of 8 in a 1-thread one), and under load each re-entry
  waited for the workers' start (a 0.4 s pass took 3-7 s).
"""
from __future__ import annotations

import math
from contextlib import contextmanager

#: the task manager ``threaded`` entered, while it runs
_running: list = []


def integrate(f, mesh, vb=None, order: int = 5, definedon=None) -> float:
    """NGSolve's ``Integrate(f, mesh, vb, order, definedon)`` of a scalar coefficient function
    (or of a ``SumOfIntegrals`` over volume elements, ``dx(element_boundary=True)`` included)
    summed over the elements in a fixed order: the same float at any thread count."""
    from ngsolve import VOL, Integrate
    from ngsolve.comp import SumOfIntegrals

    if isinstance(f, SumOfIntegrals):
        values = Integrate(f, mesh, element_wise=True)
    else:
        values = Integrate(f, mesh, VOL if vb is None else vb, order=order, definedon=definedon,
                           element_wise=True)
    return math.fsum(values.NumPy())


@contextmanager
def threaded(threads: int | None = None):
    """``with threaded(n):`` NGSolve's task manager with ``n`` threads (the count set before it
    starts; None: as it stands), BLAS held to one thread. Nested: the outer one holds."""
    if _running:
        yield
        return
    import ngsolve
    from threadpoolctl import threadpool_limits

    if threads is not None:
        ngsolve.SetNumThreads(int(threads))
    with threadpool_limits(limits=1, user_api="blas"):
        tm = ngsolve.TaskManager()
        tm.__enter__()
        _running.append(tm)
        try:
            yield
        finally:
            _running.pop().__exit__(None, None, None)


@contextmanager
def serial():
    """``with serial():`` the code inside runs without the task manager ``threaded`` started
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
