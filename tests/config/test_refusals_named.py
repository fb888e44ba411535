"""Refused input names what was refused and where, exactly (the texts a user reads): a
schedule that is not a table, a study file that is not TOML, a study's plot.lines that is
not varied (the varied keys listed, sorted, comma-separated), Sims' pass with a negative
flow stress, and a law with a constant exponent admits every temperature (0 K up)."""
from __future__ import annotations

import math

import pytest

from hotroll.config.base import CaseError
from hotroll.config.schedule import schedule_from_dict
from hotroll.config.study import load_study
from hotroll.model.flow_stress.norton_hoff import NortonHoffStress
from hotroll.theory import sims


def test_a_schedule_that_is_not_a_table_is_refused_by_its_source():
    with pytest.raises(CaseError) as e:
        schedule_from_dict([1, 2], "mill.toml")
    assert str(e.value) == ("mill.toml: invalid schedule (1 problem)\n"
                            "  schedule: must be a table of sections, got list")


def test_a_study_file_that_is_not_toml_names_the_file(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text("name = \n")
    with pytest.raises(CaseError) as e:
        load_study(path)
    assert e.value.source == str(path)
    assert str(e.value).startswith(f"{path}: invalid study (1 problem)\n  TOML syntax error: ")


def test_plot_lines_not_varied_lists_the_varied_keys(tmp_path):
    (tmp_path / "base.toml").write_text('name = "b"\n')
    (tmp_path / "s.toml").write_text(
        '[base]\nfile = "base.toml"\n[vary]\n"material.m" = [0.2, 0.3]\n'
        '"material.K" = [1e8, 2e8]\n[plot]\nx = "material.m"\nlines = "pass.exit_thickness"\n')
    with pytest.raises(CaseError) as e:
        load_study(tmp_path / "s.toml")
    assert e.value.problems == ["plot.lines: 'pass.exit_thickness' is not a varied key "
                                "(material.K, material.m)"]


def test_sims_names_a_negative_flow_stress():
    with pytest.raises(ValueError) as e:
        sims(0.3, 0.1, 0.08, -1.0)
    assert str(e.value) == "mean_flow_stress must be in (0, inf), got -1"


def test_a_constant_exponent_admits_every_temperature():
    assert NortonHoffStress(1e8, 0.15).admissible_temperature_range() == (0.0, math.inf)
