"""docs/reference/summary.md's generated table (results/summary.py): a Markdown table whose
first two lines are its head and the separator, then the keys' rows, the first key's first
(tests/results/test_summary_typed.py checks that the page holds the table, which a table
without its head would pass)."""
from __future__ import annotations

from hotroll.results.summary import Summary, summary_keys_markdown


def test_the_key_table_starts_with_its_head():
    lines = summary_keys_markdown().splitlines()
    assert lines[:2] == ["| key | unit | label | meaning |", "|---|---|---|---|"]
    first = next(iter(Summary.reference_rows()))[0]
    assert lines[2].startswith(f"| `{first}` | ")
