"""Bundled pass schedules (``hotroll schedule NAME --out DIR``)."""
from __future__ import annotations

from pathlib import Path

from ...app.examples import bundled_path


def schedule_path(name: str) -> Path:
    """Path of the bundled schedule ``name`` (with or without ``.toml``)."""
    return bundled_path(Path(__file__).parent, name, "bundled schedule")
