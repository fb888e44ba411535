"""Threads for a solve: NGSolve's task manager in short parallel regions, BLAS held to one thread.

numpy's OpenBLAS (and the one NGSolve ships) spin-wait on their own threads after every call;
with NGSolve's task manager on the same cores, that doubled the time of assembly, residuals and
refactorisations (Example 1 on C2, 2 cores: 20.5 s -> 9.5-10.9 s of steady solving). Inside a solve
numpy only handles vectors, for which one thread is plenty.

The task manager's own threads wait actively: a whole run inside it, beside one other busy
process, took 4-8x the time of one thread (issue 51: 16.8 s against 3.0 s). So a run enters it
only for short regions (a Newton step, the meshing, the measures: ``fem/reproducible.parallel``)
and only with the cores no other runnable thread wants, sampled at each region's start
(``threads_now``); serial between them and on a busy machine.
"""
from __future__ import annotations

from contextlib import contextmanager

from hotroll.fem.reproducible import parallel, threaded, threads_used  # noqa: F401 (re-exported)


@contextmanager
def solver_threads(threads: int | str | None = None):
    """``with solver_threads(n):`` a solve with up to ``n`` threads in its parallel regions (an int,
    "auto"; None: as set by an outer call, else "auto"), BLAS limited to 1 thread
    (``fem/reproducible.py``)."""
    with threaded(threads):
        yield
