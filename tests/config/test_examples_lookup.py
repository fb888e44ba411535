"""The one lookup of the bundled files (hotroll/examples/__init__.py): by name with or without
.toml, and a missing one refused with the list of the known ones."""
from __future__ import annotations

import pytest

from hotroll.examples import HERE, example_path, find_study, schedule_path, study_path

pytestmark = pytest.mark.mutation


def test_a_name_with_or_without_toml():
    assert example_path("example1") == example_path("example1.toml") == \
        HERE / "cases" / "example1.toml"
    assert schedule_path("finishing_mill") == HERE / "schedules" / "finishing_mill.toml"
    assert study_path("af_study.toml") == HERE / "studies" / "af_study.toml"


def test_a_missing_name_lists_the_known_ones():
    known = ", ".join(sorted(p.stem for p in (HERE / "studies").glob("*.toml")))
    assert known == "af_study, edge_zone, mesh_table, report_examples"
    with pytest.raises(FileNotFoundError) as e:
        study_path("nope")
    assert str(e.value) == f"no bundled study 'nope' (known: {known})"
    with pytest.raises(FileNotFoundError, match=r"^no bundled schedule 'x' \(known: "
                                                r"finishing_mill, finishing_mill_elastic, "
                                                r"finishing_mill_microstructure, ten_stand_finishing\)$"):
        schedule_path("x")
    with pytest.raises(FileNotFoundError, match=r"^no example case 'x' \(known: .*example1"):
        example_path("x")


def test_find_study_takes_a_file_first(tmp_path):
    own = tmp_path / "mine.toml"
    own.write_text("")
    assert find_study(own) == own and find_study(str(own)) == own
    assert find_study("mesh_table") == HERE / "studies" / "mesh_table.toml"
    with pytest.raises(FileNotFoundError) as e:
        find_study(tmp_path / "gone.toml")
    assert str(e.value).startswith(f"{tmp_path / 'gone.toml'} is neither a file nor a bundled "
                                   "study (no bundled study ")
