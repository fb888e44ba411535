"""Bundled study files: the report's mesh table and Examples 1-3 (``hotroll study NAME``)."""

from __future__ import annotations

from pathlib import Path

from ...app.examples import bundled_path


def study_path(name: str) -> Path:
    """Path of the bundled study ``name`` (with or without ``.toml``)."""
    return bundled_path(Path(__file__).parent, name, "bundled study")
