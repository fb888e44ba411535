"""The sample's mutation score after the survivors were classified (docs/mutation/README.md).

mutmut's verdicts (mutants/*.meta, of the sample in mutants/sample.txt: scripts/mutation.sh
--sample N) plus the verdict of every mutant it did not kill, from the tables of the page given
(rows ``| <mutant> | <verdict> | <reason or test> |``):

- T: killed by a test written after the run (named in the row; re-run against the mutant);
- R: killed in the re-check by a slow test outside mutmut's selection, or by a test in a fresh
  process (import-time code, which mutmut's fork server imports before it picks the mutant);
- E: equivalent (no input tells it apart; the reason is in the row);
- D: drawing only (figure code outside results/figures/, which is not mutated by rule);
- O: open (not killed, not equivalent).

score = caught / (sample - E - D), caught = killed + timeout + segfault + T + R; with the 95 %
Wilson interval of a binomial proportion.

    .venv/bin/python scripts/mutation_score.py docs/mutation/README.md [more pages with tables]
"""
from __future__ import annotations

import collections
import math
import re
import sys
from pathlib import Path

from mutation_sample import exit_codes, sample_names  # noqa: E402 (scripts/ is on sys.path)

ROOT = Path(__file__).resolve().parent.parent
ROW = re.compile(r"^\|\s*`?(hotroll\.[^|`\s]+)`?\s*\|\s*([TREDO])\s*\|")


def wilson(caught: int, n: int, z: float = 1.96) -> tuple[float, float]:
    p = caught / n
    mid = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return mid - half, mid + half


def main(pages: list[str]) -> None:
    sample, codes = sample_names(), exit_codes()
    verdicts = {}
    for page in pages:
        for line in Path(page).read_text().splitlines():
            m = ROW.match(line)
            if m:
                verdicts[m.group(1)] = m.group(2)
    from mutmut.stats import status_by_exit_code

    count = collections.Counter()
    unclassified = []
    for name in sample:
        status = status_by_exit_code.get(codes.get(name), "missing")
        if status in ("killed", "timeout", "segfault"):
            count["mutmut caught"] += 1
        elif status not in ("survived", "no tests", "suspicious"):
            count[f"mutmut {status}"] += 1
            unclassified.append(name)
        elif name in verdicts:
            count[verdicts[name]] += 1
        else:
            count["unclassified"] += 1
            unclassified.append(name)
    n = len(sample) - count["E"] - count["D"]
    caught = count["mutmut caught"] + count["T"] + count["R"]
    lo, hi = wilson(caught, n)
    print(f"sample: {len(sample)} mutants; " + ", ".join(f"{k}: {v}" for k, v in sorted(count.items())))
    print(f"score: {caught} caught of {n} non-equivalent (not drawing) = {100 * caught / n:.1f} %, "
          f"95 % Wilson interval {100 * lo:.1f} .. {100 * hi:.1f} %")
    pending = count["mutmut not checked"]
    if pending:
        # the sample is not complete: the score over the mutants with a result, and the
        # bounds if every pending mutant were caught or none were
        ran = n - pending
        lo, hi = wilson(caught, ran)
        print(f"with a result: {caught} caught of {ran} = {100 * caught / ran:.1f} %, 95 % "
              f"Wilson interval {100 * lo:.1f} .. {100 * hi:.1f} % (not a sample's score: "
              f"the {pending} pending are the slowest functions' mutants, not a random part); "
              f"all {n}: between {100 * caught / n:.1f} % and "
              f"{100 * (caught + pending) / n:.1f} %")
    if unclassified:
        print(f"{len(unclassified)} not classified (counted as not caught): "
              + " ".join(unclassified[:20]) + (" ..." if len(unclassified) > 20 else ""))


if __name__ == "__main__":
    main(sys.argv[1:] or [str(ROOT / "docs/mutation/README.md")])
