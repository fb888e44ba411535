"""pyroll-core's own test suite with and without ``import hotroll.pyroll`` (issue 51 item 5).

pyroll-core's tests are not in its PyPI distribution and this project does not copy them: get
its repository's ``tests`` folder yourself (pyroll-project/pyroll-core; e.g. ``git archive
<commit> tests | tar -x -C DIR``), then

    python scripts/pyroll_core_tests.py DIR/tests [--path EXTRA_SITE_DIR ...]

runs pytest on it twice against the installed pyroll-core, each in its own process: once as
it is, once with a pytest plugin that imports ``hotroll.pyroll`` before the tests are collected.
It prints both runs' counts, hotroll's FE solves in the second (``hotroll.pyroll.STATS``) and
every test whose outcome the plugin changed; exit status 1 if a test passing without the plugin
fails with it. ``--path``: directories put on PYTHONPATH for both runs (e.g. where plotly,
which some of pyroll-core's tests import, was installed). docs/how-to/pyroll.md has the counts.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

LOADER = '''"""pytest plugin: import hotroll.pyroll first; its STATS at the end (scripts/pyroll_core_tests.py)."""
import json
import os

import hotroll.pyroll as hp


def pytest_sessionfinish(session, exitstatus):
    with open(os.environ["HOTROLL_PYROLL_STATS"], "w") as f:
        json.dump(dict(hp.STATS), f)
'''


def outcomes(junit: Path) -> dict[str, str]:
    """test id -> passed, failed, error or skipped, from pytest's JUnit XML."""
    out = {}
    for case in ET.parse(junit).getroot().iter("testcase"):
        name = f"{case.get('classname')}::{case.get('name')}"
        kinds = {child.tag for child in case}
        out[name] = ("failed" if "failure" in kinds else "error" if "error" in kinds
                     else "skipped" if "skipped" in kinds else "passed")
    return out


def run(tests: Path, paths: list[str], plugin: bool, work: Path) -> tuple[dict, str]:
    """pytest on ``tests`` (in its parent folder, so that none of hotroll's pytest settings
    apply) -> (outcomes, pytest's last line)."""
    junit = work / f"junit_{'plugin' if plugin else 'plain'}.xml"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [*paths, str(work), str(ROOT), os.environ.get("PYTHONPATH", "")]),
        HOTROLL_PYROLL_STATS=str(work / "stats.json"), MPLBACKEND="Agg")
    cmd = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "no:xdist",
           f"--junitxml={junit}", str(tests)]
    if plugin:
        cmd[3:3] = ["-p", "load_hotroll_pyroll"]
    done = subprocess.run(cmd, cwd=tests.parent, env=env, capture_output=True, text=True)
    lines = [ln for ln in done.stdout.splitlines() if ln.strip()]
    return outcomes(junit), (lines[-1] if lines else done.stderr[-300:])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("tests", type=Path, help="pyroll-core's tests folder")
    ap.add_argument("--path", action="append", default=[],
                    help="a directory put on PYTHONPATH for both runs (repeatable)")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        (work / "load_hotroll_pyroll.py").write_text(LOADER)
        plain, plain_line = run(args.tests.resolve(), args.path, False, work)
        print(f"without the plugin: {plain_line}")
        with_plugin, plugin_line = run(args.tests.resolve(), args.path, True, work)
        print(f"with import hotroll.pyroll: {plugin_line}")
        stats = json.loads((work / "stats.json").read_text())
    print(f"hotroll's FE solves with the plugin: {stats['fe_solves']} "
          f"({stats['cache_hits']} cache hits)")
    changed = {k: (plain.get(k), v) for k, v in with_plugin.items() if plain.get(k) != v}
    for name, (before, after) in sorted(changed.items()):
        print(f"  {name}: {before} without, {after} with the plugin")
    broken = [k for k, (before, after) in changed.items()
              if before == "passed" and after in ("failed", "error")]
    print(f"{len(broken)} test(s) passing without the plugin fail with it")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
