"""``mpirun -n N hotroll ...`` with N > 1 (issue 53): refused before any computation with exit
code 2 and what to do instead, since every rank would solve the whole case into the same
files (the MPI-distributed 3D solve is not built); one rank runs as without mpirun.

Labels: [plumb] the launchers' variables read, the message, the exit code."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from hotroll.cli import MPI_SIZE_VARIABLES, mpi_refusal

EXAMPLE = Path(__file__).resolve().parents[2] / "hotroll" / "examples" / "cases" / "example1.toml"


@pytest.mark.parametrize("key", MPI_SIZE_VARIABLES)
def test_more_than_one_rank_is_refused_naming_the_launchers_variable(key):
    why = mpi_refusal({key: "3"})
    assert why is not None and why.startswith(f"refused: launched on 3 MPI ranks ({key}=3)")
    assert "hotroll study" in why
    assert mpi_refusal({key: "1"}) is None and mpi_refusal({key: "x"}) is None
    assert mpi_refusal({}) is None
    assert mpi_refusal({key: "3", "HOTROLL_ALLOW_MPI": "1"}) is None


def test_hotroll_under_two_ranks_exits_2_before_any_computation(tmp_path):
    """[plumb] the command itself (a subprocess with PMI_SIZE=2, as mpich's launcher sets it):
    exit code 2, the refusal on stderr, no output directory made."""
    out = tmp_path / "out"
    env = dict(os.environ, PMI_SIZE="2", PMI_RANK="0")
    r = subprocess.run([sys.executable, "-c", "from hotroll.cli import main; main()", "run",
                        str(EXAMPLE), "-o", str(out)], env=env, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 2, r.stderr
    assert "launched on 2 MPI ranks (PMI_SIZE=2)" in " ".join(r.stderr.split())
    assert not out.exists()
