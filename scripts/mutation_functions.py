"""Mutation testing of a few named functions with restricted tests (issue 52 session 3): the
mutants mutmut 3 would make (its own ``create_mutations``), each written into a scratch
clone, the given tests run there (PYTHONPATH = the clone), the file restored. For new pure
code whose tests take a second, where the package-wide run (scripts/mutation.sh) would take
hours. One JSON line per mutant (function, line, killed/survived/timeout, the diff).

    git clone -q . /tmp/mutclone && ln -s "$PWD/.venv" /tmp/mutclone/.venv
    python scripts/mutation_functions.py /tmp/mutclone [FUNCTION ...] > mutants.jsonl
    python scripts/mutation_functions.py /tmp/mutclone --targets T.json > mutants.jsonl

``--targets``: a JSON list of [file, function, regex or null, [test files]] instead of
``TARGETS`` below (the wrap's functions).
``--sample N --seed S``: enumerate all mutants of the targets, run a seeded uniform random
subset of N. ``--dry``: print the mutant counts per file and stop. ``--done F.jsonl``: skip
the mutants an interrupted run already wrote to F (append the rest to it); with
``--retry-timeouts`` its timeouts run again (a loaded machine's; count a mutant by its last
line in F).

Never run it on the working tree itself: it rewrites the files it mutates (restored after
each mutant, but a kill in between would leave one mutated).
"""
from __future__ import annotations

import difflib
import json
import os
import re
import subprocess
import sys

import libcst  # noqa: F401 - mutmut's parser (installed with mutmut)
from libcst.metadata import MetadataWrapper, PositionProvider
from mutmut.mutation.file_mutation import create_mutations, deep_replace

T_FAST = ["tests/solvers/test_roll_overlap.py"]
T_RES = T_FAST + ["tests/results"]
#: (file, function (a method: its name), a regex a removed line must match or None, tests)
TARGETS = [
    ("hotroll/solvers/contact_end.py", "overlap_after", None, T_FAST),
    ("hotroll/results/outcome.py", "contact_problem", None, T_RES),
    ("hotroll/results/outcome.py", "exit_code", "contact_unresolved|return 10", T_RES),
    ("hotroll/fem/free_surface.py", "step", None, T_FAST),
]


def run(root: str, tests: list[str]) -> str:
    env = dict(os.environ, PYTHONPATH=root)
    try:
        r = subprocess.run(["nice", ".venv/bin/python", "-m", "pytest", "-q", "-x", "-p",
                            "no:cacheprovider", *tests], cwd=root, env=env,
                           capture_output=True, text=True, timeout=600)
    except subprocess.TimeoutExpired:
        return "timeout"
    return "killed" if r.returncode != 0 else "survived"


def enumerate_mutants(root: str, targets) -> list[dict]:
    """Every mutant of the targets, in order: dicts with the target, k, line, diff, new_src."""
    out = []
    for path, fname, linefilt, tests in targets:
        full = os.path.join(root, path)
        with open(full) as fh:
            src = fh.read()
        module, muts, _, _ = create_mutations(path, src)
        pos = MetadataWrapper(module, unsafe_skip_copy=True).resolve(PositionProvider)
        muts = [m for m in muts if m.contained_by_top_level_function is not None
                and getattr(getattr(m.contained_by_top_level_function, "name", None), "value",
                            None) == fname]
        for k, m in enumerate(muts):
            new_src = deep_replace(module, m.original_node, m.mutated_node).code
            diff = [line for line in difflib.unified_diff(src.splitlines(), new_src.splitlines(),
                                                          lineterm="", n=0)
                    if line[:1] in "+-" and not line.startswith(("+++", "---"))]
            if linefilt is not None and not any(re.search(linefilt, line) for line in diff
                                                if line.startswith("-")):
                continue
            out.append({"file": path, "fn": fname, "k": k, "line": pos[m.original_node].start.line,
                        "diff": diff, "tests": tests, "full": full, "src": src,
                        "new_src": new_src})
    return out


def main() -> None:
    root, only = sys.argv[1], sys.argv[2:]
    targets = TARGETS
    sample, seed, dry = None, 0, False
    if "--sample" in only:
        i = only.index("--sample")
        sample = int(only[i + 1])
        del only[i:i + 2]
    if "--seed" in only:
        i = only.index("--seed")
        seed = int(only[i + 1])
        del only[i:i + 2]
    done = set()
    retry = "--retry-timeouts" in only       # with --done: run its timeouts again
    if retry:
        only.remove("--retry-timeouts")
    if "--done" in only:         # a JSONL of an interrupted run: its mutants are skipped
        i = only.index("--done")
        with open(only[i + 1]) as fh:
            done = {(d["file"], d["fn"], d["k"])
                    for d in (json.loads(line) for line in fh if line.strip())
                    if not (retry and d["status"] == "timeout")}
        del only[i:i + 2]
    if "--dry" in only:
        only.remove("--dry")
        dry = True
    if only[:1] == ["--targets"]:
        with open(only[1]) as fh:
            targets = [tuple(t) for t in json.load(fh)]
        only = only[2:]
    targets = [t for t in targets if not only or t[1] in only]
    muts = enumerate_mutants(root, targets)
    if sample is not None and sample < len(muts):
        import random
        idx = sorted(random.Random(seed).sample(range(len(muts)), sample))
        muts = [muts[i] for i in idx]
    if dry:
        import collections
        c = collections.Counter(m["file"] for m in muts)
        for f, n in c.items():
            print(f, n)
        print("total", len(muts))
        return
    for m in muts:
        if (m["file"], m["fn"], m["k"]) in done:
            continue
        try:
            with open(m["full"], "w") as fh:
                fh.write(m["new_src"])
            status = run(root, m["tests"])
        finally:
            with open(m["full"], "w") as fh:
                fh.write(m["src"])
        print(json.dumps({"file": m["file"], "fn": m["fn"], "k": m["k"], "line": m["line"],
                          "status": status, "diff": m["diff"]}), flush=True)


if __name__ == "__main__":
    main()
