"""The study's progress on a cluster (workflows/study.py, run_study): the "running" count the
command line's bar shows is the groups in flight, min(workers, groups left): 2 on two
workers with three groups, then fewer as they finish; 1 when serial. The cluster and the
groups' runs are faked (distributed's Client runs each group at once; no FE)."""
from __future__ import annotations

import distributed
import pytest

import hotroll.workflows.study as study
from hotroll.config.study import load_study
from hotroll.examples import example_path


class _Future:
    def __init__(self, value):
        self.value = value

    def result(self):
        return self.value


class _Client:
    def __init__(self, address):
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def submit(self, fn, *args, pure=True):
        return _Future(fn(*args))


class _Cluster:
    def __init__(self, **kw):
        pass

    def close(self):
        pass


@pytest.fixture
def three_groups(tmp_path, monkeypatch):
    """Example 1 on three meshes (three groups: a group holds the cases of one mesh)."""
    (tmp_path / "s.toml").write_text(f'[base]\nfile = "{example_path("example1")}"\n'
                                     '[vary]\n"mesh.h_contact" = [0.02, 0.03, 0.04]\n')
    monkeypatch.setattr(distributed, "Client", _Client)
    monkeypatch.setattr(distributed, "LocalCluster", _Cluster)
    monkeypatch.setattr(distributed, "as_completed", lambda futures: iter(list(futures)))
    monkeypatch.setattr(study, "run_group", lambda items, out, warm: [
        {"index": c["index"], "case": c["label"], **c["values"], "status": "done",
         "exit_code": 0, "reason": None, "resumed": False} for c in items])
    monkeypatch.delenv("DASK_SCHEDULER_ADDRESS", raising=False)
    return load_study(tmp_path / "s.toml")


def test_the_groups_in_flight_on_two_workers(tmp_path, three_groups):
    st, base = three_groups
    seen = []
    rows = study.run_study(st, base, tmp_path / "out", workers=2, progress=seen.append)
    assert [r["status"] for r in rows] == ["done"] * 3
    assert [p["running"] for p in seen] == [2, 2, 1, 0]


def test_the_groups_in_flight_when_serial(tmp_path, three_groups):
    st, base = three_groups
    seen = []
    study.run_study(st, base, tmp_path / "out", workers=2, serial=True, progress=seen.append)
    assert [p["running"] for p in seen] == [1, 1, 1, 0]
