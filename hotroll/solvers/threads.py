"""Threads for a solve: NGSolve's task manager, with the BLAS libraries held to one thread.

numpy's OpenBLAS (and the one NGSolve ships) spin-wait on their own threads after every call;
with NGSolve's task manager on the same cores, that doubled the time of assembly, residuals and
refactorisations (Example 1 on C2, 2 cores: 20.5 s -> 9.5-10.9 s of steady solving). Inside a solve
numpy only handles vectors, for which one thread is plenty.
"""
from __future__ import annotations

from contextlib import contextmanager


@contextmanager
def solver_threads():
    """``with solver_threads():`` NGSolve's TaskManager, BLAS limited to 1 thread."""
    from ngsolve import TaskManager
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"), TaskManager():
        yield
