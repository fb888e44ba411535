"""Faults (issue 18): the memory and time estimate before meshing (a mesh that would not fit is
refused unless forced), a full disk (a clear error, nothing half-written), atomic writes."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from hotroll.config.case import load_case
from hotroll.examples import example_path
from hotroll.files import DiskFullError
from hotroll.workflows.estimate import (
    DOFS_PER_TRIANGLE,
    MESHER_FACTOR,
    ResourceError,
    check,
    corner_triangles,
    estimate,
)

ENV = {**os.environ, "NGS_NUM_THREADS": "1"}


def _case(name: str = "example1", **over):
    over.setdefault("solver.method", "steady")
    return load_case(example_path(name)).with_overrides(**{"solver.threads": 1, **over})


@pytest.mark.parametrize("name, over", [
    ("example1", {"mesh.h_contact": 0.01}),
    ("example1", {"mesh.h_contact": "C1"}),
    ("hot_aluminium", {}),
    ("roughing_slab", {"pass.exit_thickness": 0.15}),
    ("tension_pass", {"mesh.grading": 0.5}),
    ("example2", {"mesh.h_contact": 0.02, "solver.method": "transient"}),
])
def test_the_estimate_counts_the_mesh_before_it_is_made(name, over):
    """The estimated unknowns against the mesh the solver then builds: within 20 % on other
    passes, sizes, gradings and both methods (the fit used 9 cases, none of these)."""
    from hotroll.fem.mesh import build_plate_mesh
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.runner import build_model, steady_settings

    case = _case(name, **over)
    est = estimate(case)
    model, _ = build_model(case)
    if case.solver.method == "steady":
        run = SteadyRun(model, steady_settings(case), case.plate.length)
        dofs = run.form.fes.ndof
    else:
        import ngsolve

        mesh = build_plate_mesh(case.pass_.roll_pass(), case.plate.length, model.mesh)
        V = ngsolve.VectorH1(mesh, order=2)
        dofs = V.ndof + ngsolve.H1(mesh, order=1).ndof
    assert est.dofs == pytest.approx(dofs, rel=0.2), (est.dofs, dofs)
    assert est.memory_bytes > 0 and est.seconds > 0


def test_the_estimate_counts_the_contact_starts_refinement():
    """[measured] the unknowns a 16x refinement at the contact's start adds, estimated
    (``corner_triangles``) against the meshes' on the bundled roughing slab: within 30 %
    (the fit's CORNER_FACTOR from four passes, 0.56-0.88 of the fan)."""
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.runner import build_model, steady_settings

    est, dofs = [], []
    for ratio in (1.0, 16.0):
        case = _case("roughing_slab", **{"mesh.corner_refinement": ratio})
        est.append(estimate(case).dofs)
        model, _ = build_model(case)
        dofs.append(SteadyRun(model, steady_settings(case), case.plate.length).form.fes.ndof)
    assert est[1] - est[0] == pytest.approx(dofs[1] - dofs[0], rel=0.3), (est, dofs)


def test_the_estimate_grows_as_the_mesh_is_refined():
    """Every size scales with h below half_entry / 60 (the far size 15 h): 2D, 4 x the
    unknowns for h / 2, the contact start's refinement aside (here 16x: its triangles the
    same at any h, ``corner_triangles``)."""
    cases = [_case(**{"mesh.h_contact": h, "mesh.corner_refinement": 16.0})
             for h in (0.002, 0.001)]
    coarse, fine = (estimate(c) for c in cases)
    corner = [DOFS_PER_TRIANGLE * MESHER_FACTOR * corner_triangles(
        c.mesh.h, c.mesh.corner_refinement, c.mesh.grading) for c in cases]
    assert corner[0] == pytest.approx(corner[1], rel=1e-12) and corner[0] > 0.0
    assert (fine.dofs - corner[1]) / (coarse.dofs - corner[0]) == pytest.approx(4.0, rel=0.05)
    assert fine.memory_bytes > coarse.memory_bytes and fine.seconds > coarse.seconds


def test_a_mesh_over_the_memory_limit_is_refused_before_meshing(tmp_path, monkeypatch):
    """Nothing is meshed nor written; the error names mesh.h_contact and gives the estimate;
    forced, the same case runs."""
    from hotroll.fem import mesh as mesh_mod
    from hotroll.workflows import runner

    case = _case(**{"mesh.h_contact": 0.03, "solver.memory_limit": 1e6})
    called = []
    monkeypatch.setattr(mesh_mod, "_graded_mesh", lambda *a, **k: called.append(1))
    with pytest.raises(ResourceError) as e:
        runner.run_case(case, tmp_path / "refused", resume=False)
    text = str(e.value)
    assert "mesh.h_contact" in text and "unknowns" in text and "GB" in text and "force" in text
    assert not called and not (tmp_path / "refused").exists()
    monkeypatch.undo()
    forced = case.with_overrides(**{"solver.force": True, "output.figures": False})
    assert check(forced).fits is False                          # forced, not fitting
    s = runner.run_case(forced, tmp_path / "forced", resume=False)
    assert s["exit_code"] == 0 and s["estimated_dofs"] == pytest.approx(s["dofs"], rel=0.2)


def test_the_command_line_refuses_with_exit_code_8_and_runs_forced(tmp_path):
    case = tmp_path / "c.toml"
    text = example_path("example1").read_text().replace('method = "transient"',
                                                        'method = "steady"')
    case.write_text(text.replace("[solver]", "[solver]\nmemory_limit = 1e6"))
    cmd = [sys.executable, "-m", "hotroll.cli", "run", str(case), "--mesh", "0.03",
           "--no-figures", "--out", str(tmp_path / "o")]
    r = subprocess.run(cmd, capture_output=True, text=True, env=ENV, timeout=300)
    assert r.returncode == 8, r.stderr
    assert "refused" in r.stderr and "mesh.h_contact" in r.stderr and "Traceback" not in r.stderr
    r = subprocess.run(cmd + ["--force"], capture_output=True, text=True, env=ENV, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]


def test_a_study_records_a_refused_case_and_goes_on(tmp_path):
    from hotroll.config.study import load_study
    from hotroll.workflows.study import run_study

    base = example_path("example1").read_text().replace('method = "transient"',
                                                        'method = "steady"')
    (tmp_path / "base.toml").write_text(base)
    (tmp_path / "s.toml").write_text(
        '[base]\nfile = "base.toml"\nset = { "solver.memory_limit" = 6e8 }\n'
        '[vary]\n"mesh.h_contact" = [0.03, 0.0004]\n')
    st, b = load_study(tmp_path / "s.toml")
    rows = run_study(st, b, tmp_path / "out", serial=True)
    assert [r["status"] for r in rows] == ["done", "too_large"]
    assert rows[1]["exit_code"] == 8 and "mesh.h_contact" in rows[1]["reason"]
    assert not (tmp_path / "out" / "cases" / rows[1]["case"] / "summary.json").exists()
    from hotroll.results.report_table import study_context

    page = study_context(tmp_path / "out")                 # the report shows it failed
    assert [t["failed"] for t in page["table"]] == [False, True]
    assert page["status"] == "1 of 2 cases done"


def test_a_full_disk_leaves_the_old_file_whole_and_names_the_file(tmp_path, monkeypatch):
    import errno

    from hotroll.results import output

    path = tmp_path / "summary.json"
    output.write_json(path, {"roll_force": 1.0})

    class Full:
        """A file that takes part of the text, then finds the disk full."""

        def __init__(self, name, *a, **k):
            Path(name).write_text('{"roll_f')

        def __enter__(self):
            return self

        def __exit__(self, *a):
            return False

        def write(self, text):
            raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(output, "open", Full, raising=False)
    with pytest.raises(DiskFullError) as e:
        output.write_json(path, {"roll_force": 2.0})
    assert "disk full" in str(e.value) and str(path) in str(e.value) and "MB free" in str(e.value)
    assert json.loads(path.read_text()) == {"roll_force": 1.0}
    assert [p.name for p in tmp_path.iterdir()] == ["summary.json"]      # no temporary left


@pytest.fixture
def small_disk(tmp_path):
    """A real 256 kB file system (tmpfs; needs root, as on the CI machine)."""
    d = tmp_path / "small"
    d.mkdir()
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", str(d)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        pytest.skip(f"cannot mount a small tmpfs here: {r.stderr.strip()}")
    yield d
    subprocess.run(["umount", "-l", str(d)], capture_output=True)


@pytest.mark.parametrize("command", [
    ["example", "1", "--mesh", "0.03"],
    ["study", "STUDY", "--serial"],
])
def test_a_real_full_disk_gives_a_clear_error(small_disk, tmp_path, command):
    """The run or study writes into a 256 kB file system: exit code 9, the message says disk
    full and names a file, no traceback, no temporary file left, every file there whole."""
    if "STUDY" in command:
        base = example_path("example1").read_text().replace('method = "transient"',
                                                            'method = "steady"')
        (tmp_path / "base.toml").write_text(base)
        (tmp_path / "s.toml").write_text('[base]\nfile = "base.toml"\n[vary]\n'
                                         '"mesh.h_contact" = [0.03, 0.02]\n')
        command = [str(tmp_path / "s.toml") if c == "STUDY" else c for c in command]
    r = subprocess.run([sys.executable, "-m", "hotroll.cli", *command, "--out",
                        str(small_disk / "out")], capture_output=True, text=True, env=ENV,
                       timeout=300)
    assert r.returncode == 9, (r.returncode, r.stderr[-3000:])
    assert "disk full" in r.stderr and str(small_disk) in r.stderr
    assert "Traceback" not in r.stderr
    left = [p for p in (small_disk / "out").rglob("*") if ".tmp" in p.name]
    assert not left
    for p in (small_disk / "out").rglob("*.json"):
        json.loads(p.read_text())                                  # whole, not cut
