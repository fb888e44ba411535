"""A uniform random sample of the package's mutants (scripts/mutation.sh --sample N).

The whole package has about 23,000 mutants; at the measured ~40 mutants a minute on 2 cores
(2026-11-25, the cheap modules first, the solver files costing more) a full run takes ten hours
or more. A seeded uniform sample of N mutants estimates the share of killed mutants with a
binomial standard error sqrt(p (1 - p) / N) (about 1 % for N = 800 at p = 0.9); the report
states the sample's 95 % Wilson interval. Random mutant sampling is the standard way to cut the
cost of mutation analysis (Wong & Mathur 1995; Zhang et al., ICSE 2010).

    .venv/bin/python scripts/mutation_sample.py prepare       # mutants/ and mutmut's stats at HEAD
    .venv/bin/python scripts/mutation_sample.py pick N [--seed S]   # -> mutants/sample.txt
    .venv/bin/python scripts/mutation_sample.py pending     # the sample's mutants not yet run

A run stopped part-way (a session's end, a kill) goes on with ``scripts/mutation.sh
--resume-sample``: only the sample's mutants without a result are run.
"""
from __future__ import annotations

import argparse
import json
import os
import random
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def prepare() -> None:
    """What ``mutmut run`` does before it tests a mutant: copy and mutate the package into
    mutants/ (only the files that changed) and record which tests call which function."""
    os.chdir(ROOT)
    from mutmut.__main__ import (
        collect_or_load_stats,
        copy_also_copy_files,
        copy_src_dir,
        create_mutants,
        get_mutant_runner,
        set_mutant_under_test,
        setup_source_paths,
        store_lines_covered_by_tests,
    )
    set_mutant_under_test("mutant_generation")
    (ROOT / "mutants").mkdir(exist_ok=True)
    copy_src_dir()
    copy_also_copy_files()
    setup_source_paths()
    store_lines_covered_by_tests()
    stats = create_mutants(2)
    print(f"mutation_sample: {stats.mutated} files mutated, {stats.unmodified} unmodified")
    collect_or_load_stats(get_mutant_runner(2), mutants_caught_by_type_checker={},
                          apply_config_invalidation=True)


def all_mutants() -> list[str]:
    """Every mutant name in mutants/ (sorted: the sample depends on the seed only)."""
    names = []
    for meta in sorted((ROOT / "mutants").glob("hotroll/**/*.py.meta")):
        names += json.loads(meta.read_text())["exit_code_by_key"]
    return sorted(names)


def pick(n: int, seed: int) -> list[str]:
    names = all_mutants()
    if not 0 < n <= len(names):
        raise SystemExit(f"mutation_sample: N must be in 1..{len(names)} (the mutants), not {n}")
    sample = sorted(random.Random(seed).sample(names, n))
    (ROOT / "mutants" / "sample.txt").write_text(
        f"# {n} of {len(names)} mutants, seed {seed}\n" + "\n".join(sample) + "\n")
    return sample


def sample_names() -> list[str]:
    """The sample's mutant names (mutants/sample.txt)."""
    return [line.strip() for line in (ROOT / "mutants" / "sample.txt").read_text().splitlines()
            if line.strip() and not line.startswith("#")]


def exit_codes() -> dict:
    """mutmut's exit code of every mutant (None: not run yet)."""
    codes = {}
    for meta in (ROOT / "mutants").glob("hotroll/**/*.py.meta"):
        codes.update(json.loads(meta.read_text())["exit_code_by_key"])
    return codes


def pending() -> list[str]:
    """The sample's mutants that mutmut has no result for yet."""
    codes = exit_codes()
    return [name for name in sample_names() if codes.get(name) is None]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    sub.add_parser("prepare")
    sub.add_parser("pending")
    q = sub.add_parser("pick")
    q.add_argument("n", type=int)
    q.add_argument("--seed", type=int, default=2026)
    a = p.parse_args()
    if a.command == "prepare":
        prepare()
    elif a.command == "pending":
        print("\n".join(pending()))
    else:
        print("\n".join(pick(a.n, a.seed)))


if __name__ == "__main__":
    main()
