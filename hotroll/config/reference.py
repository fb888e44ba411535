"""The case file's keys as a Markdown reference, generated from the schema itself (each field's
text, unit, allowed range and default): docs/reference/case.md between its ``generated`` marks
(``python scripts/reference_docs.py`` rewrites them; a test checks the page is current)."""
from __future__ import annotations

import re

from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from hotroll.config.base import fields_of
from hotroll.config.case import Case

BEGIN = "<!-- generated from the schema by scripts/reference_docs.py: do not edit below -->"
END = "<!-- end of the generated keys -->"
_DESCRIPTION = re.compile(r"^(?P<text>.*?) \[(?P<unit>[^\]]*)\](?:; allowed: (?P<allowed>.*))?$",
                          re.S)


def _section_model(info) -> type[BaseModel] | None:
    """The section model of a field (an optional section: the model inside ``X | None``)."""
    for a in (info.annotation, *getattr(info.annotation, "__args__", ())):
        if isinstance(a, type) and issubclass(a, BaseModel):
            return a
    return None


def _default(info) -> str:
    value = info.default
    if value is PydanticUndefined:
        return "required"
    if value is None:
        return "none"
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, str):
        return f'`"{value}"`'
    return f"{value:g}" if isinstance(value, float) else str(value)


def _text(info) -> str:
    """A field's meaning, without its unit and allowed range."""
    m = _DESCRIPTION.match(" ".join((info.description or "").split()))
    return m["text"] if m else info.description or ""


def _row(key: str, info) -> str:
    m = _DESCRIPTION.match(" ".join((info.description or "").split()))
    text, unit, allowed = ((m["text"], m["unit"], m["allowed"] or "") if m
                           else (info.description or "", "-", ""))
    cells = [f"`{key}`", _default(info), unit or "-", allowed, text]
    return "| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |"


def case_keys_markdown() -> str:
    """Every section of a case and its keys: default, unit, allowed, meaning."""
    lines = []
    for name, info in fields_of(Case).items():
        model = _section_model(info)
        if model is None:
            lines += [f"`{name}` (top level): {info.description} (default {_default(info)}).", ""]
            continue
        lines += _table(f"## [{name}]", info.description or "", model)
        tables = {key: _section_model(sub) for key, sub in fields_of(model).items()
                  if _section_model(sub) is not None}
        shown = set()
        for key, sub in tables.items():      # a roll's own tables: one table for those alike
            if key in shown:
                continue
            alike = [k for k, m in tables.items() if k not in shown and
                     list(fields_of(m)) == list(fields_of(sub))]
            shown.update(alike)
            heading = ", ".join(f"[{name}.{k}]" for k in alike)
            texts = " ".join(f"`{k}`: {_text(fields_of(model)[k])}." for k in alike)
            lines += _table(f"### {heading}", texts, sub)
    return "\n".join(lines).rstrip() + "\n"


def _table(heading: str, text: str, model: type[BaseModel]) -> list[str]:
    """A section's heading, text and key table (its own tables left out)."""
    return [heading, "", text, "", "| key | default | unit | allowed | meaning |",
            "|---|---|---|---|---|",
            *[_row(key, sub) for key, sub in fields_of(model).items()
              if _section_model(sub) is None], ""]


def with_generated(page: str, body: str | None = None) -> str:
    """``page`` with the text between the generated marks replaced by ``body`` (default: the
    case's keys)."""
    head, rest = page.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    return f"{head}{BEGIN}\n\n{case_keys_markdown() if body is None else body}\n{END}{tail}"
