"""The typed summary of a run: every key of ``summary.json`` declared once, with its SI unit,
its label for a person and its meaning (in ``results/summary_keys.py``; docs/reference/summary.md
is generated from it).

``Summary`` is a read-only mapping (``s["roll_force"]``, ``s.get(...)``, ``dict(s)``) and a
dataclass (``s.roll_force``). ``Summary.from_dict(d)`` refuses an unknown key or a missing one
(a typo in the code that builds it fails at once); ``strict=False`` reads what an older
version wrote (unknown keys kept, missing ones absent). Figures that exist only under a
condition (``when``: a ``[thermal]`` section, a ``[pass] width``, a run written by
``run_case``) are absent, not null, when the condition does not hold.
"""
from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field, fields

from hotroll.results.summary_keys import (  # noqa: F401 (re-exported)
    ABSENT,
    GROUPS,
    ROLL_ENTRY,
    ROLL_FLATTENING_ENTRY,
    SummaryKeys,
    _f,
)


@dataclass(eq=False)
class Summary(SummaryKeys, Mapping):
    """summary.json: means over the last window of the history and the run's figures."""

    _other: dict = field(default_factory=dict, repr=False, metadata={"internal": True})

    # --- construction ------------------------------------------------------------------------
    @classmethod
    def keys_declared(cls) -> list[str]:
        return [f.name for f in fields(cls) if not f.metadata.get("internal")]

    @classmethod
    def from_dict(cls, data: Mapping, *, strict: bool = True) -> Summary:
        """The summary of ``data``. ``strict``: every key declared, every unconditional one
        present (ValueError naming them); else unknown keys kept, missing ones absent."""
        declared = cls.keys_declared()
        unknown = [k for k in data if k not in declared]
        if strict:
            cond = {f.name for f in fields(cls) if f.metadata.get("when")}
            missing = [k for k in declared if k not in data and k not in cond]
            if unknown or missing:
                raise ValueError(f"summary: undeclared keys {unknown}, missing keys {missing} "
                                 "(hotroll/results/summary.py declares each key)")
        obj = cls(**{k: data[k] for k in data if k in declared})
        obj._other = {k: data[k] for k in unknown}
        return obj

    # --- the mapping --------------------------------------------------------------------------
    def __getitem__(self, key: str):
        if key in self._other:
            return self._other[key]
        value = getattr(self, key, ABSENT) if key in _DECLARED else ABSENT
        if value is ABSENT:
            raise KeyError(key)
        return value

    def __iter__(self) -> Iterator[str]:
        yield from (k for k in _DECLARED if getattr(self, k) is not ABSENT)
        yield from self._other

    def __len__(self) -> int:
        return sum(1 for _ in self)

    def to_dict(self) -> dict:
        """The plain dict summary.json holds (absent keys left out)."""
        return {k: self[k] for k in self}

    # --- what each key is ---------------------------------------------------------------------
    @classmethod
    def units_map(cls) -> dict[str, str]:
        """key -> SI unit of every declared key that has one."""
        return {f.name: f.metadata["unit"] for f in fields(cls) if f.metadata.get("unit")}

    @classmethod
    def labels(cls) -> dict[str, str]:
        return {f.name: f.metadata["label"] for f in fields(cls) if "label" in f.metadata}

    @classmethod
    def groups(cls) -> dict[str, tuple[str, ...]]:
        """The HTML page's groups: name -> keys, in declaration order."""
        return {g: tuple(f.name for f in fields(cls) if f.metadata.get("group") == g)
                for g in GROUPS}

    @classmethod
    def reference_rows(cls) -> list[tuple[str, str, str, str]]:
        """(key, unit, label, meaning with its condition) for docs/reference/summary.md."""
        note = {"thermal": "with `[thermal]`", "width": "with `[pass] width`",
                "spread": "with `[spread]` (the 3D pass across the width)",
                "roll": "with `[roll] model` hitchcock or elastic",
                "mill": "with `[pass] mill_modulus`",
                "gap": "with `[pass] roll_gap`",
                "run": "written by a run (`hotroll run`, a schedule, a study)",
                "asymmetric": "for an asymmetric pass (two rolls that differ: the "
                              "full-thickness strip)"}
        rows = []
        for f in fields(cls):
            if f.metadata.get("internal"):
                continue
            md = f.metadata
            meaning = "; ".join(x for x in (md["meaning"], note.get(md["when"], "")) if x)
            rows.append((f.name, md["unit"] or "", md["label"], meaning))
        return rows


_DECLARED = tuple(Summary.keys_declared())


def summary_keys_markdown() -> str:
    """The table of summary.json's keys for docs/reference/summary.md."""
    lines = ["| key | unit | label | meaning |", "|---|---|---|---|"]
    bar = "\\|"          # a | inside a table cell
    lines += [f"| `{k}` | {u} | {lab} | {m.replace('|', bar)} |"
              for k, u, lab, m in Summary.reference_rows()]
    lines += ["", "Each entry of `rolls` (an asymmetric pass):", "",
              "| key | unit | meaning |", "|---|---|---|"]
    lines += [f"| `{k}` | {u or ''} | {m} |" for k, (u, m) in ROLL_ENTRY.items()]
    lines += [f"| `{k}` | {u or ''} | a flattening roll's only: {m} |"
              for k, (u, m) in ROLL_FLATTENING_ENTRY.items()]
    return "\n".join(lines) + "\n"
