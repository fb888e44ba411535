"""The seam between the steady solve and the strip's discretisation (solvers/discretisation.py):
the solve's loop reaches the strip only through ``StripDiscretisation``, and both strips (the
half strip, the full strip between two rolls) provide it. A check of the code's structure, not
of a figure."""
from __future__ import annotations

import ast
import inspect
import textwrap

from hotroll.solvers import steady, steady_solve
from hotroll.solvers.discretisation import StripDiscretisation
from hotroll.solvers.full_steady import FullSteadyRun

#: the steady solve's loop (solvers/steady_solve.py: SteadySolve, every method of it)
LOOP = tuple(n for n, v in vars(steady_solve.SteadySolve).items() if callable(v)
             or isinstance(v, property))
#: the loop's own state (set and read by the loop itself)
STATE = {"couplings", "last_changes", "record", "result", "state", "_roll_start"}


def _protocol_members() -> set[str]:
    own = set(vars(StripDiscretisation)) | set(StripDiscretisation.__annotations__)
    return {n for n in own if not n.startswith(("__", "_abc", "_is_"))}


def test_the_solve_loop_reaches_the_strip_only_through_the_protocol():
    tree = ast.parse(textwrap.dedent(inspect.getsource(steady_solve.SteadySolve)))
    used = set()
    assert {"run", "solve", "_follow"} <= set(LOOP)
    for node in tree.body[0].body:
        if isinstance(node, ast.FunctionDef) and node.name in LOOP:
            for n in ast.walk(node):
                if (isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name)
                        and n.value.id == "self"):
                    used.add(n.attr)
    outside = used - set(LOOP) - STATE - _protocol_members()
    assert not outside, f"the solve loop reads {sorted(outside)} beyond the Protocol"


def test_both_strips_provide_the_protocol():
    for cls in (steady.SteadyRun, FullSteadyRun):
        missing = [n for n in _protocol_members() if not hasattr(cls, n)
                   and n not in cls.__init__.__code__.co_names]
        assert not missing, (cls.__name__, missing)


def test_a_strip_without_the_surface_update_is_not_one():
    class NoSurface:
        form = mesh = mesh_key = problem = s = None
        mesh_time = 0.0

        def _cold_start(self): ...
        def _fresh_searches(self): ...
        def _couplings(self, warm=False): ...
        def _couple_below(self, state, given): ...
        def _warm(self, warm, vec, target): ...
        def measure(self, stats, index): ...
        def solution_record(self, frame_shift=0.0): ...
        def head_x(self): ...
        solution = None

    assert not isinstance(NoSurface(), StripDiscretisation)
    NoSurface.update_surface = lambda self: 0.0
    assert isinstance(NoSurface(), StripDiscretisation)
