"""A mutmut sample's pending mutants run without mutmut (issue 50): the same mutants and the
same tests, without mutmut's per-mutant collection of the whole suite and its trampolines.

Each pending name (``mutation_sample.py pending``: ``module.x_function__mutmut_N`` or
``module.xǁClassǁmethod__mutmut_N``) is the N-th of the mutants mutmut 3 makes of that function
(``create_mutations``, in order; checked against ``mutmut show``), written into a scratch copy
of the sample's tree. The tests are those mutmut's stats say call the function
(``mutants/mutmut-stats.json``), fastest first, with ``-x``: a failure kills the mutant, as
under mutmut. One JSON line per mutant (name, exit code as mutmut records it: 1 killed, 0
survived, 36 timeout, 35 suspicious: pytest ended otherwise).

    # the sample's tree: its source (unmutated), and the tests mutmut runs (mutants/tests:
    # the sample's, with the tests added for its verdicts)
    mkdir /tmp/pend1 && (cd /work/wt-mut && tar --exclude=./mutants --exclude=./.venv -cf - .) \
        | tar xf - -C /tmp/pend1 && rm -rf /tmp/pend1/tests \
        && cp -a /work/wt-mut/mutants/tests /tmp/pend1/ && ln -s "$PWD/.venv" /tmp/pend1/.venv
    python scripts/mutation_pending.py run /tmp/pend1 --names P.txt --stats STATS.json \\
        [--part 1/2] [--timeout 1800] [--done OUT.jsonl] >> OUT.jsonl
    python scripts/mutation_pending.py record OUT.jsonl --mutants /work/wt-mut/mutants

``record`` writes the exit codes into mutmut's ``*.py.meta`` files (only where mutmut has none:
run it while no mutmut is running), so that ``scripts/mutation.sh --report`` counts them.
Never point ``run`` at a working tree: it rewrites the files it mutates (restored after each
mutant; a kill in between leaves one mutated).
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import libcst as cst
from mutmut.mutation.file_mutation import create_mutations, deep_replace


def parse(name: str) -> tuple[str, str | None, str, int, str]:
    """(file, class or None, function, N, the stats' key) of a mutmut mutant name."""
    base, n = name.rsplit("__mutmut_", 1)
    cut = max(base.rfind(".x_"), base.rfind(".xǁ"))
    module, mangled = base[:cut], base[cut + 1:]
    if mangled.startswith("xǁ"):
        _, cls, fn = mangled.split("ǁ")
    else:
        cls, fn = None, mangled[2:]
    return module.replace(".", "/") + ".py", cls, fn, int(n), base


def mutant_source(root: str, path: str, cls: str | None, fn: str, n: int) -> tuple[str, str]:
    """(original, mutated) source of the file: the n-th mutant (1-based) of ``cls.fn``."""
    src = (Path(root) / path).read_text()
    module, muts, _, _ = create_mutations(path, src)
    owner = {}
    for node in module.body:
        if isinstance(node, cst.ClassDef):
            for item in node.body.body:
                if isinstance(item, cst.FunctionDef):
                    owner[id(item)] = node.name.value
    mine = [m for m in muts
            if isinstance(m.contained_by_top_level_function, cst.FunctionDef)
            and m.contained_by_top_level_function.name.value == fn
            and owner.get(id(m.contained_by_top_level_function)) == cls]
    m = mine[n - 1]
    return src, deep_replace(module, m.original_node, m.mutated_node).code


#: a pytest plugin (written into the tree) that keeps the collected items whose ids are in the
#: file $MUTATION_PENDING_IDS, in that file's order: ids with a "/" in a parameter ("[W/(m^2
#: K)]") cannot be given on the command line (pytest reads them as paths)
PLUGIN = '''import os


def pytest_collection_modifyitems(session, config, items):
    path = os.environ.get("MUTATION_PENDING_IDS")
    if not path:
        return
    with open(path) as fh:
        order = {line.rstrip("\\n"): i for i, line in enumerate(fh) if line.strip()}
    keep = sorted((it for it in items if it.nodeid in order), key=lambda it: order[it.nodeid])
    config.hook.pytest_deselected(items=[it for it in items if it.nodeid not in order])
    items[:] = keep
'''


def run_tests(root: str, tests: list[str], timeout: float) -> int:
    ids = Path(root) / "_pending_ids.txt"
    ids.write_text("\n".join(tests) + "\n")
    (Path(root) / "_pending_select.py").write_text(PLUGIN)
    files = sorted({t.split("::", 1)[0] for t in tests})
    env = dict(os.environ, PYTHONPATH=root, MUTATION_PENDING_IDS=str(ids))
    try:
        r = subprocess.run(["nice", sys.executable, "-m", "pytest", "-q", "-x", "-p",
                            "no:cacheprovider", "-p", "no:randomly", "-p", "_pending_select",
                            *files], cwd=root, env=env, capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return 36
    if r.returncode in (0, 1, 3):   # passed; a test failed; pytest's internal error (mutmut: a kill)
        return r.returncode
    if r.returncode == 5:           # no tests collected
        return 33
    print(f"mutation_pending: pytest exit {r.returncode}:\n{r.stdout[-2000:]}{r.stderr[-2000:]}",
          file=sys.stderr)
    return 35                       # anything else (a usage error, an interrupt): suspicious


def collected(root: str) -> set[str]:
    """The test ids pytest collects in the tree (the stats may name ids that a
    parametrisation or a later test file no longer gives: pytest refuses the whole command
    line for one unknown id)."""
    env = dict(os.environ, PYTHONPATH=root)
    r = subprocess.run([sys.executable, "-m", "pytest", "--collect-only", "-q", "-p",
                        "no:cacheprovider", "tests"], cwd=root, env=env, capture_output=True,
                       text=True)
    return {line.strip() for line in r.stdout.splitlines() if "::" in line}


def run(a) -> None:
    names = [line.strip() for line in Path(a.names).read_text().splitlines() if line.strip()]
    i, k = (int(v) for v in a.part.split("/"))
    names = names[i - 1::k]
    done = set()
    if a.done and Path(a.done).exists():
        done = {json.loads(line)["name"] for line in Path(a.done).read_text().splitlines()
                if line.strip()}
    stats = json.loads(Path(a.stats).read_text())
    by_fn, durations = stats["tests_by_mangled_function_name"], stats["duration_by_test"]
    valid = collected(a.root)
    for name in names:
        if name in done:
            continue
        path, cls, fn, n, key = parse(name)
        named = by_fn.get(key, [])
        tests = sorted((t for t in named if t in valid), key=lambda t: durations.get(t, 0.0))
        full = Path(a.root) / path
        src, mutated = mutant_source(a.root, path, cls, fn, n)
        try:
            full.write_text(mutated)
            code = run_tests(a.root, tests, a.timeout) if tests else 33
        finally:
            full.write_text(src)
        print(json.dumps({"name": name, "exit_code": code, "tests": len(tests),
                          "not_collected": len(named) - len(tests)}), flush=True)


def record(a) -> None:
    codes = {}
    for line in Path(a.jsonl).read_text().splitlines():
        if line.strip():
            d = json.loads(line)
            codes[d["name"]] = d["exit_code"]
    written = 0
    for meta in Path(a.mutants).glob("hotroll/**/*.py.meta"):
        data = json.loads(meta.read_text())
        hit = {k: codes[k] for k, v in data["exit_code_by_key"].items()
               if v is None and k in codes}
        if hit:
            data["exit_code_by_key"].update(hit)
            meta.write_text(json.dumps(data))
            written += len(hit)
    print(f"mutation_pending: {written} results written into mutmut's meta files")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run")
    r.add_argument("root")
    r.add_argument("--names", required=True)
    r.add_argument("--stats", required=True)
    r.add_argument("--part", default="1/1")
    r.add_argument("--timeout", type=float, default=1800.0)
    r.add_argument("--done", default=None)
    c = sub.add_parser("record")
    c.add_argument("jsonl")
    c.add_argument("--mutants", required=True)
    a = p.parse_args()
    run(a) if a.command == "run" else record(a)


if __name__ == "__main__":
    main()
