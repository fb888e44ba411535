"""The same numbers at any thread count and in every run (issue 50, item 3).

NGSolve's coloured assembly (``Apply``, ``AssembleLinearization``, ``Assemble``), its
matrix-vector products and ``InnerProduct``/``Norm`` add in a fixed order whatever the threads.
Two things it does under the task manager do not: ``Integrate`` adds the elements' values with
atomic adds in the order the threads reach them, and ``sparsecholesky`` merges its blocks under
locks and atomic adds in the factorisation and the solves (``shared/notes/unilateral-contact-
exit.md`` section 3: 3 distinct results of 30 ``Integrate`` calls, 10 of 10 factor+solves, on 2
threads). Hence:

- ``integrate``: every integral of hotroll, the elements' values (each written to its own slot,
  ``element_wise=True``) summed in Python (``math.fsum``: correctly rounded, so independent of
  the order too). ``tests/fem/test_reproducible.py`` fails where a module calls NGSolve's
  ``Integrate`` itself.
- ``threaded``: the task manager hotroll runs in, its thread count set (BLAS held to one thread).
- The flow's linear solver is UMFPACK (``forms.LINEAR_SOLVERS``): sequential, the same factors
  in every run. ``sparsecholesky`` is not, even with no task manager at all (15 factorisations
  of a 6.6k-DOF Jacobian gave 10-11 distinct solutions, 1e-16 apart; a Taylor-Hood Stokes
  matrix 8 of 8, with no task manager ever entered). Factorising it outside the task manager
  (leaving and entering it around each factorisation) therefore did not help, and under load
  each re-entry waited for the workers' start (a 0.4 s pass took 3-7 s).
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


def find_points(mesh, x, y):
    """NGSolve's ``mesh(x, y)`` (a MeshPoint array) found in one thread: threaded, a point on
    an edge shared by two elements was found in either, by the thread's last element (a
    thermal pass's strip temperatures then differed in the last bits run to run)."""
    with serial():
        return mesh(x, y)
