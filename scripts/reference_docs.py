"""Rewrite the generated parts of docs/reference/case.md (from the case schema) and
docs/reference/summary.md (from the typed summary, ``hotroll/results/summary.py``).

    python scripts/reference_docs.py
"""
from pathlib import Path

from hotroll.config.reference import with_generated
from hotroll.files import atomic
from hotroll.results.summary import summary_keys_markdown

DOCS = Path(__file__).resolve().parents[1] / "docs" / "reference"
PAGES = {DOCS / "case.md": None, DOCS / "summary.md": summary_keys_markdown()}

if __name__ == "__main__":
    for page, body in PAGES.items():
        text = with_generated(page.read_text(), body)
        with atomic(page) as tmp:
            Path(tmp).write_text(text)
        print(f"wrote {page}")
