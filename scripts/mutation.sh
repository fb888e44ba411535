#!/usr/bin/env bash
# Mutation testing (mutmut 3) of the whole package (the drawing code of the figures aside);
# [tool.mutmut] in pyproject.toml says what is mutated and which tests may run (the default
# suite without its slowest tests, which re-check the survivors: scripts/mutation_recheck.py).
# mutmut changes one thing in one function at a time (a < for a <=, 2.0 for 3.0, a dropped
# argument, ...) and runs the tests that call that function, fastest first (tests/conftest.py),
# stopping at the first failure: a mutant the tests still pass ("survived") is a behaviour no
# selected test pins down; re-check one mutant against any test by hand (below). mutmut learns which tests call which function in a
# "stats" run; a shared (module) fixture is built inside one test only, so the fixtures that
# several tests read use tests/casebuild.shared_scope, function-scoped in that run:
#   cd mutants && MUTANT_UNDER_TEST=<name> ../.venv/bin/python -m pytest tests/solvers/test_rolling.py -x
#
# NOT part of CI (it takes hours): run it by hand, in the background, after changing the code or
# its tests. The run of 2026-11-23 (the model layer and the figures, ~3100 mutants) took 35
# minutes on 2 workers; the whole package has several times as many, and a mutant of the
# solvers costs an FE solve or more. It prints progress; Ctrl-C or a kill of `mutmut run` stops
# it, `--keep` goes on from there (each mutant's result is saved as it comes).
#
#   nohup nice bash scripts/mutation.sh > mutation.log 2>&1 &
#
#   scripts/mutation.sh [-j N] [--keep] [--report] [--sample N [--seed S]] [MUTANT_GLOB ...]
#     -j N        mutmut workers (default 2, or $MUTATION_JOBS)
#     --sample N  a seeded uniform random sample of N of all the package's mutants
#                 (scripts/mutation_sample.py: the full run takes ten hours or more); the
#                 report gives the sample's score with its 95 % Wilson interval. --seed S: 2026.
#     --resume-sample  go on with the sample of the last --sample run: only its mutants
#                 without a result are run (after a session's end or a kill).
#     --keep      reuse mutants/ of the last run: mutmut re-tests only changed functions and
#                 mutants without a result. A survivor is NOT re-tested when only a test changed,
#                 so run without it (the default: mutants/ is deleted) for a score to record.
#     --report    no run: only write the two files below again from mutants/ (after re-testing
#                 some mutants with `.venv/bin/mutmut run NAME`, say)
#     MUTANT_GLOB only these mutants, e.g. 'hotroll.model.friction_estimate.*'
#                 (names as `.venv/bin/mutmut results` prints them); the files get a -partial suffix.
#
# Writes docs/mutation/results-<date>.txt (counts and score, per file, "no tests" per function)
# and docs/mutation/survivors-<date>.txt (each survivor with its diff). Afterwards:
#   .venv/bin/mutmut results         # every mutant that was not killed, with its status
#   .venv/bin/mutmut show NAME       # the diff of one mutant
#   .venv/bin/mutmut browse          # interactive: inspect, re-test after adding a test
# A line that must not be mutated (a diagnostic message, ...): `# pragma: no mutate`; a whole
# function: `# pragma: no mutate block` on its def line. mutants/ is git-ignored.
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=${MUTATION_JOBS:-2}
keep=0
report_only=0
sample=0
resume=0
seed=2026
names=()
while (($#)); do
    case $1 in
        -j) jobs=$2; shift 2 ;;
        --keep) keep=1; shift ;;
        --report) report_only=1; shift ;;
        --sample) sample=$2; shift 2 ;;
        --seed) seed=$2; shift 2 ;;
        --resume-sample) resume=1; keep=1; shift ;;
        -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d'; exit 0 ;;
        *) names+=("$1"); shift ;;
    esac
done

# one thread per worker: NGSolve's task manager, BLAS
export NGS_NUM_THREADS=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1

if ((report_only == 0)); then
    # Each test the selection deselects should still exist (a renamed test would silently come
    # back into the selection): a warning, not an error.
    selection_warnings=$(.venv/bin/python - 2>/dev/null <<'PY' | tail -n 1 || echo "(selection check failed)"
import tomllib
import pytest

args = tomllib.load(open("pyproject.toml", "rb"))["tool"]["mutmut"]["pytest_add_cli_args_test_selection"]
gone = [args[i + 1] for i, a in enumerate(args) if a == "--deselect"]


class Items:
    ids: list = []

    def pytest_collection_modifyitems(self, items):
        self.ids = [item.nodeid for item in items]


items = Items()
pytest.main(["--collect-only", "-qq", "-p", "no:cacheprovider", "tests"], plugins=[items])
print(" ".join(g for g in gone if not any(i == g or i.startswith(g + "::") or i.startswith(g + "[")
                                          for i in items.ids)))
PY
    )
    [[ -z $selection_warnings ]] || echo "WARNING: the selection deselects tests that do not exist: $selection_warnings"
    export MUTATION_SELECTION_WARNINGS=$selection_warnings

    [[ $keep == 1 ]] || rm -rf mutants
    start=$(date +%s)
    if ((resume == 1)); then
        mapfile -t names < <(.venv/bin/python scripts/mutation_sample.py pending)
        echo "mutation.sh: $(date -Is), resuming the sample: ${#names[@]} mutants without a result"
        ((${#names[@]} > 0)) || { echo "nothing left to run: scripts/mutation.sh --report"; exit 0; }
    fi
    if ((sample > 0)); then
        echo "mutation.sh: $(date -Is), generating the mutants and mutmut's stats for a sample"
        .venv/bin/python scripts/mutation_sample.py prepare
        mapfile -t names < <(.venv/bin/python scripts/mutation_sample.py pick "$sample" --seed "$seed")
    fi
    commit=$(git rev-parse --short HEAD)$([[ -z $(git status --porcelain --untracked-files=no) ]] ||
                                           echo " (with uncommitted changes)")
    echo "mutation.sh: $(date -Is), $jobs workers, ${names[*]:-all mutants}"
    if [[ -t 1 ]]; then
        .venv/bin/mutmut run --max-children "$jobs" "${names[@]}"
    else    # a log file: of mutmut's spinner line (10 rewrites a second) every 100th mutant
        .venv/bin/mutmut run --max-children "$jobs" "${names[@]}" | tr '\r' '\n' | LC_ALL=C awk '
            /^\342\240/ {
                last = $0; key = substr($0, 5)
                if (match($0, /[0-9]+\/[0-9]+/)) key = int(substr($0, RSTART, RLENGTH) / 100)
                if (key != shown) { shown = key; print; last = "" }
                fflush(); next
            }
            { if (last != "") print last; last = ""; print; fflush() }
            END { if (last != "") print last }'
    fi
    run="run of $(date -d "@$start" '+%F %H:%M'), commit $commit; $jobs workers, $(( ($(date +%s) - start + 30) / 60 )) min"
    echo "$run" > mutants/mutation-run.txt
    suffix=$(date +%F)
else
    run="$(cat mutants/mutation-run.txt 2>/dev/null || echo "run of $(date -r mutants/mutmut-stats.json '+%F %H:%M')")"
    run+=" (this report written again from mutants/)"
    suffix=$(date -r mutants/mutmut-stats.json +%F)
fi

mkdir -p docs/mutation
if [[ -f mutants/sample.txt ]] && { ((sample > 0)) || ((resume == 1)) ||
                                     { ((report_only == 1)) && ((${#names[@]} == 0)); }; }; then
    mapfile -t names < <(grep -v '^#' mutants/sample.txt)
    export MUTATION_SAMPLE="$(head -n 1 mutants/sample.txt | sed 's/^# //')"
    suffix+=-sample
elif ((${#names[@]} > 0)); then
    suffix+=-partial
fi
MUTATION_RUN=$run .venv/bin/python - "$suffix" "${names[@]}" <<'EOF'
"""Summary of mutants/*.meta (mutmut's results) -> docs/mutation/."""
import collections
import fnmatch
import json
import os
import sys
from datetime import datetime
from importlib.metadata import version
from pathlib import Path

from mutmut.mutation.diff_apply import get_diff_for_mutant
from mutmut.stats import status_by_exit_code

suffix, globs = sys.argv[1], sys.argv[2:]
out = Path("docs/mutation")
by_file, names_by_status = {}, collections.defaultdict(list)
no_tests = collections.Counter()
for meta in sorted(Path("mutants").rglob("*.py.meta")):
    path = str(meta.relative_to("mutants"))[: -len(".meta")]
    codes = json.loads(meta.read_text())["exit_code_by_key"]
    exact = set(globs)
    codes = {k: v for k, v in codes.items()
             if not globs or k in exact or any(fnmatch.fnmatch(k, g) for g in globs if "*" in g)}
    if not codes:
        continue
    count = collections.Counter()
    for name, code in codes.items():
        status = status_by_exit_code[code]
        count[status] += 1
        names_by_status[status].append((path, name))
        if status == "no tests":
            no_tests[name.rpartition("__mutmut_")[0]] += 1
    by_file[path] = count

total = collections.Counter()
for c in by_file.values():
    total.update(c)


def score(c):
    caught = c["killed"] + c["timeout"] + c["segfault"]
    tested = caught + c["survived"] + c["suspicious"]
    return (f"{100 * caught / tested:5.1f} %" if tested else "    -  ",
            f"{100 * caught / sum(c.values()):5.1f} %" if c else "    -  ")


def wilson(c, z=1.96):
    """The sample's score (caught / tested) with its 95 % Wilson interval."""
    caught = c["killed"] + c["timeout"] + c["segfault"]
    n = caught + c["survived"] + c["suspicious"]
    if not n:
        return "sample score: no mutant tested"
    p = caught / n
    mid = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * (p * (1 - p) / n + z * z / (4 * n * n)) ** 0.5 / (1 + z * z / n)
    return (f"sample score {100 * p:.1f} % of {n} tested mutants, 95 % Wilson interval "
            f"{100 * (mid - half):.1f} .. {100 * (mid + half):.1f} %")


stats = json.loads(Path("mutants/mutmut-stats.json").read_text())
cols = ("killed", "survived", "timeout", "no tests", "suspicious", "segfault", "not checked")
lines = [
    f"Mutation testing, {datetime.now():%Y-%m-%d %H:%M} (scripts/mutation.sh; mutmut {version('mutmut')})",
    os.environ["MUTATION_RUN"],
    f"test selection: {len(stats['duration_by_test'])} tests, "
    f"{sum(stats['duration_by_test'].values()):.1f} s in all ([tool.mutmut] in pyproject.toml)",
    (f"mutants: a uniform random sample, {os.environ['MUTATION_SAMPLE']} (mutants/sample.txt)"
     if os.environ.get("MUTATION_SAMPLE") else
     f"mutants: {', '.join(globs) if globs else 'all configured'}"),
    *([wilson(total)] if os.environ.get("MUTATION_SAMPLE") else []),
    *([f"WARNING: the selection deselects tests that do not exist: {os.environ['MUTATION_SELECTION_WARNINGS']}"]
      if os.environ.get("MUTATION_SELECTION_WARNINGS") else []),
    "",
    "caught = killed + timeout + segfault (the mutant crashed the tests: NGSolve given None, ...)",
    "score = caught / tested (tested: not counting 'no tests'); all = caught / all mutants",
    "",
    f"{'file':40s}" + "".join(f"{c:>12s}" for c in cols) + f"{'score':>9s}{'all':>9s}",
]
for path, c in list(by_file.items()) + [("TOTAL", total)]:
    lines.append(f"{path:40s}" + "".join(f"{c[k]:12d}" for k in cols) + "".join(f"{s:>9s}" for s in score(c)))
other = set(total) - set(cols)
if other:
    lines.append("other statuses: " + ", ".join(f"{k}: {total[k]}" for k in sorted(other)))
lines += ["", "'no tests' per function (no test in the selection calls it):"]
lines += [f"  {n:5d}  {f}" for f, n in sorted(no_tests.items())] or ["  none"]
results = out / f"results-{suffix}.txt"
results.write_text("\n".join(lines) + "\n")

surv = [f"Surviving mutants ({len(names_by_status['survived'])}; suspicious: "
        f"{len(names_by_status['suspicious'])}), {datetime.now():%Y-%m-%d %H:%M}; {os.environ['MUTATION_RUN']}",
        "Each: `.venv/bin/mutmut show NAME`; re-test after adding a test: `.venv/bin/mutmut run NAME`.", "",
        "per function (survived / all its mutants):"]
per_function = collections.Counter(n.rpartition("__mutmut_")[0] for _, n in names_by_status["survived"])
all_per_function = collections.Counter(n.rpartition("__mutmut_")[0] for ns in names_by_status.values()
                                       for _, n in ns)
surv += [f"  {n:4d} / {all_per_function[f]:4d}  {f}" for f, n in sorted(per_function.items())] + [""]
for status in ("survived", "suspicious"):
    for path, name in sorted(names_by_status[status]):
        try:
            diff = get_diff_for_mutant(name, path=path)
        except Exception as e:     # the report must not fail on one unreadable mutant
            diff = f"(no diff: {e})"
        surv += [f"## {name}  [{status}]", diff, ""]
survivors = out / f"survivors-{suffix}.txt"
survivors.write_text("\n".join(surv) + "\n")
print("\n".join(lines))
print(f"\nwritten: {results}, {survivors}")
EOF
