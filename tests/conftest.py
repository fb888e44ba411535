"""The test suite mirrors the package's layers (docs/architecture.md): ``model/``, ``theory/``,
``config/``, ``fem/``, ``solvers/``, ``results/``, ``workflows/`` and ``interfaces/`` (the
command line, the tutorial as written). Shared case builders are ``casebuild.py`` (this folder
is on the import path through this file); shared inputs are in ``data/``."""
from __future__ import annotations

from pathlib import Path

#: The repository's root (docs, scripts) and the tests' shared data.
ROOT = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"
