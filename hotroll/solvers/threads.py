"""Threads for a solve: NGSolve's task manager, with the BLAS libraries held to one thread.

numpy's OpenBLAS (and the one NGSolve ships) spin-wait on their own threads after every call;
with NGSolve's task manager on the same cores, that doubled the time of assembly, residuals and
refactorisations (Example 1 on C2, 2 cores: 20.5 s -> 9.5-10.9 s of steady solving). Inside a solve
numpy only handles vectors, for which one thread is plenty.

The task manager's own threads wait actively too: two runs of 2 threads each on 2 cores took
114 s each for finishing_mill against 7.5 s alone (one thread each: 8.4-8.7 s; issue 34
session 10). Concurrent runs on the same cores want ``[solver] threads = 1`` (README).
"""
from __future__ import annotations

from contextlib import contextmanager

from hotroll.fem.reproducible import threaded


@contextmanager
def solver_threads(threads: int | None = None):
    """``with solver_threads(n):`` NGSolve's TaskManager with ``n`` threads (None: the count
    as set), BLAS limited to 1 thread; the direct solvers step out of it
    (``fem/reproducible.py``)."""
    with threaded(threads):
        yield
