"""Rewrite the generated part of docs/reference/case.md from the case schema.

    python scripts/reference_docs.py
"""
from pathlib import Path

from hotroll.config.reference import with_generated
from hotroll.files import atomic

PAGE = Path(__file__).resolve().parents[1] / "docs" / "reference" / "case.md"

if __name__ == "__main__":
    text = with_generated(PAGE.read_text())
    with atomic(PAGE) as tmp:
        Path(tmp).write_text(text)
    print(f"wrote {PAGE}")
