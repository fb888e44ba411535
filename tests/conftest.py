"""The test suite mirrors the package's layers (docs/architecture.md): ``model/``, ``theory/``,
``config/``, ``fem/``, ``solvers/``, ``results/``, ``workflows/`` and ``interfaces/`` (the
command line, the tutorial as written). Shared case builders are ``casebuild.py`` (this folder
is on the import path through this file); shared inputs are in ``data/``."""
from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from casebuild import EXAMPLE1_COARSE, build_case, shared_scope

from hotroll.workflows.runner import run_case

#: The repository's root (docs, scripts) and the tests' shared data.
ROOT = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"


def _session_unless_stats(fixture_name, config) -> str:
    """"session", except in mutmut's stats run ("function": casebuild.shared_scope)."""
    return "function" if shared_scope(fixture_name, config) == "function" else "session"


@pytest.fixture(scope=_session_unless_stats)
def solved_example1(tmp_path_factory) -> Path:
    """The output directory of ``EXAMPLE1_COARSE`` solved once per test process (a cached
    solved case: read it, do not write into it)."""
    out = tmp_path_factory.mktemp("solved_example1")
    run_case(build_case(EXAMPLE1_COARSE), out)
    return out

#: The files that take longest (``pytest --durations=0``, 2026-11-25: the mesh-table study
#: 55 s, the property tests 42 s, the studies 40 s, contact and rolling 28 s each, ...),
#: collected first: pytest-xdist's ``--dist loadfile`` hands out files in collection order,
#: so the longest go first and the short ones fill the gaps (longest-first scheduling)
#: instead of one long file running alone at the end. The 3D pass's two files first (issue 53:
#: test_spread_3d.py took 6.5 min on a loaded machine before its laws and scalings moved to
#: test_spread_3d_laws.py).
LONGEST_FIRST = ("solvers/test_spread_3d.py", "solvers/test_spread_3d_laws.py",
                 "workflows/test_study_mesh_table.py", "config/test_case_properties.py",
                 "workflows/test_study.py", "solvers/test_contact.py", "solvers/test_rolling.py",
                 "solvers/test_thermal_transient.py", "workflows/test_faults.py",
                 "results/test_summary_unchanged.py", "interfaces/test_behaviour.py",
                 "solvers/test_thermal_coupling.py")


def pytest_collection_modifyitems(config, items):
    """Under pytest-xdist: the longest files first (the order of the rest, and within a file,
    unchanged). Under mutmut (``MUTANT_UNDER_TEST``, scripts/mutation.sh): the fastest tests
    first, by mutmut's own measured durations, so that a mutant the tests kill dies early
    (mutmut runs them with ``-x``)."""
    if os.environ.get("MUTANT_UNDER_TEST"):
        stats = Path("mutmut-stats.json")        # mutmut runs the tests from mutants/
        if stats.is_file():
            duration = json.loads(stats.read_text()).get("duration_by_test", {})
            items.sort(key=lambda item: duration.get(item.nodeid, 0.0))
        return
    if not hasattr(config, "workerinput"):     # not an xdist worker: collection order
        return
    here = Path(__file__).resolve().parent
    rank = {name: i for i, name in enumerate(LONGEST_FIRST)}

    def key(item) -> int:
        try:
            rel = Path(str(item.path)).resolve().relative_to(here).as_posix()
        except ValueError:
            return len(rank)
        return rank.get(rel, len(rank))

    items.sort(key=key)
