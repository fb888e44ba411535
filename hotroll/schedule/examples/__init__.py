"""Bundled pass schedules (``hotroll schedule NAME --out DIR``)."""
from __future__ import annotations

from pathlib import Path


def schedule_path(name: str) -> Path:
    """Path of the bundled schedule ``name`` (with or without ``.toml``)."""
    path = Path(__file__).with_name(name if name.endswith(".toml") else f"{name}.toml")
    if not path.is_file():
        known = sorted(p.stem for p in path.parent.glob("*.toml"))
        raise FileNotFoundError(f"no bundled schedule {name!r} (known: {', '.join(known)})")
    return path
