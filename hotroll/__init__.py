"""hotroll: finite-element simulation of hot flat rolling (Touloupoulos 2020 scheme and beyond).

From Python: ``hotroll.load_case``, ``hotroll.solve(case) -> Result``, ``hotroll.study``,
``hotroll.roll_schedule`` (``hotroll/api.py``; the tutorial is docs/tutorial.md).

Layers, each importing only those below it (the import contract in pyproject.toml):
cli, api, pyroll -> workflows -> results -> solvers -> fem -> config -> theory -> model ->
examples, files.
"""

__version__ = "0.1.0"

_API = ("Case", "CaseError", "Result", "example_case", "load_case", "case_from_dict",
        "open_result", "roll_schedule", "solve", "study")


def __getattr__(name):
    """The API's names, imported when first used (``import hotroll`` stays light)."""
    if name in _API:
        import importlib

        return getattr(importlib.import_module("hotroll.api"), name)
    raise AttributeError(f"module 'hotroll' has no attribute {name!r}")
