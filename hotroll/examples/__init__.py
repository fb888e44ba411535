"""Bundled input files and their one lookup: case files (``cases/``: the report's examples,
Touloupoulos 2020, and realistic passes, each documenting its sources), pass schedules
(``schedules/``) and studies (``studies/``). Imports nothing of hotroll: the lowest layer."""

from __future__ import annotations

from pathlib import Path

HERE = Path(__file__).parent

#: Example name -> case files. The report's examples by number (Example 3 compares m = 0.15,
#: 0.2, 0.25; m = 0.2 is example1); the realistic passes by name.
EXAMPLES: dict[str, list[str]] = {
    "1": ["example1"],
    "2": ["example2"],
    "3": ["example3_m015", "example1", "example3_m025"],
    "hot_strip_finishing": ["hot_strip_finishing"],
    "roughing_slab": ["roughing_slab"],
    "hot_aluminium": ["hot_aluminium"],
    "tension_pass": ["tension_pass"],
    "hot_strip_finishing_thermal": ["hot_strip_finishing_thermal"],
    "thin_strip": ["thin_strip"],
    "asymmetric_plate": ["asymmetric_plate"],
    "asymmetric_radii": ["asymmetric_radii"],
    "narrow_bar": ["narrow_bar"],
}


def bundled_path(folder: Path, name: str, what: str) -> Path:
    """Path of the bundled file ``name`` (with or without ``.toml``) in ``folder``;
    FileNotFoundError listing the known ones."""
    path = Path(folder) / (name if name.endswith(".toml") else f"{name}.toml")
    if not path.is_file():
        known = sorted(p.stem for p in path.parent.glob("*.toml"))
        raise FileNotFoundError(f"no {what} {name!r} (known: {', '.join(known)})")
    return path


def example_path(name: str) -> Path:
    """Path of the bundled case file ``name`` (with or without ``.toml``)."""
    return bundled_path(HERE / "cases", name, "example case")


def schedule_path(name: str) -> Path:
    """Path of the bundled schedule ``name`` (with or without ``.toml``)."""
    return bundled_path(HERE / "schedules", name, "bundled schedule")


def study_path(name: str) -> Path:
    """Path of the bundled study ``name`` (with or without ``.toml``)."""
    return bundled_path(HERE / "studies", name, "bundled study")


def find_study(study: str | Path) -> Path:
    """A study file, else the bundled study of that name; FileNotFoundError naming both."""
    path = Path(study)
    if path.is_file():
        return path
    try:
        return study_path(str(study))
    except FileNotFoundError as e:
        raise FileNotFoundError(f"{study} is neither a file nor a bundled study ({e})") from None
