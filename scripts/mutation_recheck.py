"""Re-check mutmut's survivors against the whole test suite (or given test files).

mutmut runs a fast test selection against each mutant (``[tool.mutmut]`` in pyproject.toml);
the FE rolling runs are not in it. A survivor may still be killed by one of those. This script
runs each survivor (or each name given) against the tests named here, the full default suite by
default, with ``-x``. It runs two at a time and writes the verdicts to
``docs/mutation/recheck-<date>.txt``. Run it after ``scripts/mutation.sh`` has finished, from
the repository root:

    .venv/bin/python scripts/mutation_recheck.py [--tests tests/solvers/test_rolling.py ...] [NAME ...]
    .venv/bin/python scripts/mutation_recheck.py --status survived --status no-tests   # both

(``--status no-tests``: the mutants of functions no selected test calls, e.g. the command
line's subprocess paths, which the slow tests reach. Not while ``mutmut run`` is going: the
current ``tests/`` are copied over the ones it runs.)

(one --tests per file; a pytest error other than failing tests is reported as "error")

The mutated package is the one in ``mutants/`` (mutmut's trampolines pick the mutant from
MUTANT_UNDER_TEST). The current ``tests/`` are copied there first.
"""
from __future__ import annotations

import argparse
import datetime as dt
import json
import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MUTANTS = ROOT / "mutants"


#: mutmut's exit codes of the mutants this script re-checks: survived (0), no test (33).
STATUS_CODES = {"survived": 0, "no-tests": 33}


def survivors(statuses: tuple[str, ...] = ("survived",)) -> list[str]:
    """Names of the mutants mutmut recorded with these statuses ("survived": exit code 0 of
    the selection; "no-tests": no selected test calls the function)."""
    codes = {STATUS_CODES[s] for s in statuses}
    names = []
    for meta in sorted(MUTANTS.glob("hotroll/**/*.meta")):
        data = json.loads(meta.read_text())
        names += [k for k, v in data["exit_code_by_key"].items() if v in codes]
    return names


def check(name: str, tests: list[str], timeout: float) -> tuple[str, str, str]:
    """(name, verdict, first failing test or reason)."""
    env = dict(os.environ, MUTANT_UNDER_TEST=name, NGS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", "-p",
           "no:randomly", *tests]
    try:
        r = subprocess.run(cmd, cwd=MUTANTS, env=env, capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return name, "timeout", f"> {timeout:.0f} s"
    if r.returncode == 0:
        return name, "survived", ""
    if r.returncode != 1:       # 2-5: interrupted, internal or usage error, nothing collected
        return name, "error", f"pytest exit code {r.returncode}"
    failed = [ln.split(" ")[1] for ln in r.stdout.splitlines() if ln.startswith("FAILED ")]
    return name, "killed", failed[0] if failed else f"exit code {r.returncode}"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("names", nargs="*", help="mutant names (default: every survivor)")
    ap.add_argument("--tests", action="append", default=None,
                    help="a test file, directory or node id (repeat the option; default: tests)")
    ap.add_argument("--timeout", type=float, default=900.0, help="per mutant, s")
    ap.add_argument("-j", type=int, default=2)
    ap.add_argument("--status", action="append", choices=sorted(STATUS_CODES), default=None,
                    help="which mutants when no names are given (repeat; default: survived)")
    args = ap.parse_args()
    if not MUTANTS.is_dir():
        sys.exit("no mutants/ directory: run scripts/mutation.sh first")
    shutil.copytree(ROOT / "tests", MUTANTS / "tests", dirs_exist_ok=True)
    args.tests = args.tests or ["tests"]
    names = args.names or survivors(tuple(args.status or ["survived"]))
    print(f"{len(names)} mutants against {' '.join(args.tests)}", flush=True)
    out = ROOT / "docs" / "mutation" / f"recheck-{dt.date.today().isoformat()}.txt"
    lines = [f"Survivors of the selection re-checked against {' '.join(args.tests)} (-x), "
             f"{dt.datetime.now():%Y-%m-%d %H:%M}, scripts/mutation_recheck.py", ""]
    with ThreadPoolExecutor(args.j) as pool:
        for name, verdict, why in pool.map(lambda n: check(n, args.tests, args.timeout), names):
            print(f"{verdict:9s} {name} {why}", flush=True)
            lines.append(f"{verdict:9s} {name} {why}")
    killed = sum(ln.startswith("killed") for ln in lines)
    lines += ["", f"killed {killed} of {len(names)}"]
    tmp = out.with_suffix(".tmp")
    tmp.write_text("\n".join(lines) + "\n")
    os.replace(tmp, out)
    print(f"killed {killed} of {len(names)}; written {out.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
