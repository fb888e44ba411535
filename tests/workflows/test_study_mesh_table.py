"""The report's mesh table as a study (issue 18's check): the bundled ``mesh_table`` study on a
local cluster of 2 workers gives the table of its serial run, and the table is a mesh study
(the roll force of the six Table 2 meshes within 0.5 % of each other, the unknowns growing as
h^-2). About a minute per run on 2 cores (F2: 46,000 unknowns)."""
from __future__ import annotations

import csv
import math

import pytest
from casebuild import assert_same_table

from hotroll.config.study import load_study
from hotroll.examples import study_path
from hotroll.workflows.study import run_study


@pytest.fixture(scope="module")
def tables(tmp_path_factory):
    out = tmp_path_factory.mktemp("mesh_table")
    study, base = load_study(study_path("mesh_table"))
    serial = run_study(study, base, out / "serial", serial=True, workers=2)
    cluster = run_study(study, base, out / "cluster", workers=2)
    return out, serial, cluster


def test_the_cluster_gives_the_serial_table(tables):
    out, serial, cluster = tables
    assert [r["status"] for r in serial] == ["done"] * 6
    assert_same_table(serial, cluster)
    assert len({r["worker"] for r in cluster}) == 2                # both workers solved


def test_the_table_is_a_mesh_study(tables):
    out, serial, _ = tables
    with open(out / "serial" / "study.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [r["mesh.h_contact"] for r in rows] == ["C1", "C2", "M1", "M2", "F1", "F2"]
    forces = [float(r["roll_force"]) for r in rows]
    assert max(forces) / min(forces) - 1.0 < 5e-3
    h = [float(r["h_contact"]) for r in rows]
    dofs = [float(r["dofs"]) for r in rows]
    # unknowns ~ h^-p with p between 1 (the far mesh fixed) and 2 (all sizes scale)
    p = math.log(dofs[-1] / dofs[0]) / math.log(h[0] / h[-1])
    assert 1.0 < p < 2.2
    assert (out / "serial" / "study.png").is_file()
    assert (out / "serial" / "study_profiles.png").is_file()
