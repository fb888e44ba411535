"""Bundled study files: the report's mesh table and Examples 1-3 (``hotroll study NAME``)."""

from __future__ import annotations

from pathlib import Path

from ...app.examples import bundled_path


def study_path(name: str) -> Path:
    """Path of the bundled study ``name`` (with or without ``.toml``)."""
    return bundled_path(Path(__file__).parent, name, "bundled study")


def find_study(study: str | Path) -> Path:
    """A study file, else the bundled study of that name; FileNotFoundError naming both."""
    path = Path(study)
    if path.is_file():
        return path
    try:
        return study_path(str(study))
    except FileNotFoundError as e:
        raise FileNotFoundError(f"{study} is neither a file nor a bundled study ({e})") from None
