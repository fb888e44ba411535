"""``mpiexec -n N hotroll ...`` with N > 1 (issue 53): ``hotroll run`` shares a case between
the ranks (its 3D pass's flow solve: solvers/spread_mpi.py; rank 0 writes OUT, the others a
temporary directory, removed), every other command is refused before any computation with
exit code 2 and what to do instead, since every rank would solve the whole case into the same
files; one rank runs as without mpirun.

Labels: [plumb] the launchers' variables read, the message, the exit code, the files."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from hotroll.cli import MPI_COMMANDS, MPI_SIZE_VARIABLES, mpi_refusal

EXAMPLE = Path(__file__).resolve().parents[2] / "hotroll" / "examples" / "cases" / "example1.toml"


@pytest.mark.parametrize("key", MPI_SIZE_VARIABLES)
def test_more_than_one_rank_is_refused_but_for_run_naming_the_launchers_variable(key):
    why = mpi_refusal({key: "3"}, ["schedule", "x.toml"])
    assert why is not None and why.startswith(f"refused: launched on 3 MPI ranks ({key}=3)")
    assert "hotroll study" in why and "hotroll run" in why
    assert mpi_refusal({key: "3"}) is not None                 # no command: refused too
    assert MPI_COMMANDS == ("run",)
    assert mpi_refusal({key: "3"}, ["run", "x.toml", "-o", "out"]) is None
    assert mpi_refusal({key: "1"}, ["schedule"]) is None and mpi_refusal({key: "x"}) is None
    assert mpi_refusal({}) is None
    assert mpi_refusal({key: "3", "HOTROLL_ALLOW_MPI": "1"}, ["study"]) is None


def test_hotroll_schedule_under_two_ranks_exits_2_before_any_computation(tmp_path):
    """[plumb] the command itself (a subprocess with PMI_SIZE=2, as mpich's launcher sets it):
    exit code 2, the refusal on stderr, no output directory made."""
    out = tmp_path / "out"
    env = dict(os.environ, PMI_SIZE="2", PMI_RANK="0")
    r = subprocess.run([sys.executable, "-c", "from hotroll.cli import main; main()",
                        "schedule", "hot_strip_3pass", "-o", str(out)], env=env,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stderr
    assert "launched on 2 MPI ranks (PMI_SIZE=2)" in " ".join(r.stderr.split())
    assert not out.exists()


def test_hotroll_run_under_mpiexec_writes_once_what_one_process_writes(tmp_path):
    """[plumb] ``mpiexec -n 2 hotroll run example1 --method steady``: exit 0, rank 0's OUT the summary of a
    run without mpiexec (the 2D pass is the same serial work on each rank: its figures equal
    bitwise), its MPI line printed once, ``--format json`` one document (rank 0's), no rank's
    temporary directory left behind."""
    hotroll = Path(sys.executable).parent / "hotroll"
    mpiexec = Path(sys.executable).parent / "mpiexec"
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    env = dict(os.environ, TMPDIR=str(tmp))
    runs = {}
    for name, cmd in (("serial", [str(hotroll)]), ("mpi", [str(mpiexec), "-n", "2",
                                                            str(hotroll)])):
        r = subprocess.run(cmd + ["run", str(EXAMPLE), "--method", "steady", "-o",
                                  str(tmp_path / name), "--no-figures"], env=env, capture_output=True, text=True,
                           timeout=300)
        assert r.returncode == 0, r.stderr[-3000:]
        runs[name] = (r.stderr, json.loads((tmp_path / name / "summary.json").read_text()))
    out, mpi = runs["mpi"]
    assert out.count("MPI: 2 ranks") == 1 and "MPI:" not in runs["serial"][0]
    r = subprocess.run([str(mpiexec), "-n", "2", str(hotroll), "run", str(EXAMPLE), "--method",
                        "steady", "-o", str(tmp_path / "json"), "--no-figures", "--format",
                        "json"], env=env, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    doc = json.loads(r.stdout)           # rank 0's tables alone: one document, nothing else
    assert doc[0]["title"] == "example1: summary"
    serial = runs["serial"][1]
    for key in ("roll_force", "roll_torque", "forward_slip", "neutral_angle"):
        assert mpi[key] == serial[key], key
    assert list(tmp.iterdir()) == []
    assert tempfile.gettempdir() != str(tmp)       # the test's own process untouched


def test_an_amg_3d_pass_under_mpiexec_is_refused_before_any_computation(tmp_path):
    """[plumb] ``spread.linear_solver = "amg+gmres"`` (scipy's AMG, one process) under
    ``mpiexec -n 2 hotroll run``: exit code 2 naming the key, no OUT, no rank's temporary
    directory left behind."""
    case = (Path(__file__).resolve().parents[2] / "hotroll" / "examples" / "cases"
            / "narrow_bar.toml").read_text() + 'linear_solver = "amg+gmres"\n'
    (tmp_path / "bar.toml").write_text(case)
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    mpiexec = Path(sys.executable).parent / "mpiexec"
    r = subprocess.run([str(mpiexec), "-n", "2", str(Path(sys.executable).parent / "hotroll"),
                        "run", str(tmp_path / "bar.toml"), "-o", str(tmp_path / "out")],
                       env=dict(os.environ, TMPDIR=str(tmp)), capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 2, r.stderr[-2000:]
    assert "spread.linear_solver = 'amg+gmres' runs on one process" in " ".join(
        (r.stdout + r.stderr).split())
    assert not (tmp_path / "out").exists() and list(tmp.iterdir()) == []
