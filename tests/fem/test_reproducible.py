"""The same numbers at any thread count and in every run (issue 50, item 3;
hotroll/fem/reproducible.py): no raw ``Integrate``, and a pass solved twice on 2 threads and
once on 1 gives the same bits (solution vector, fields, summary, profiles)."""
from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from casebuild import EXAMPLE1_COARSE, build_case

import hotroll
from hotroll.fem import reproducible
from hotroll.fem.reproducible import fe_space, integrate, parallel, serial, threaded, threads_now

PACKAGE = Path(hotroll.__file__).resolve().parent
#: a call of NGSolve's Integrate, or an import of it, anywhere but in the helper
RAW = re.compile(r"\bIntegrate\s*\(|import[^\n]*\bIntegrate\b|ngsolve\.Integrate\b")


def test_no_module_integrates_but_through_the_helper():
    """Every integral goes through ``fem.reproducible.integrate`` (a raw ``Integrate`` adds
    the elements in the order the threads reach them)."""
    offenders = [str(p.relative_to(PACKAGE)) for p in PACKAGE.rglob("*.py")
                 if p.name != "reproducible.py" and RAW.search(p.read_text())]
    assert offenders == []


def test_the_grep_sees_a_raw_integrate():
    assert RAW.search("    a = float(Integrate(cf, mesh))")
    assert RAW.search("from ngsolve import BND, Integrate, x")
    assert not RAW.search('"""Integrate the fraction of points"""')


@pytest.fixture
def idle(monkeypatch):
    """No other process wants a core: ``parallel`` takes the threads asked for (up to the
    cores), whatever else runs on the machine (another test worker)."""
    monkeypatch.setattr(reproducible, "others_running", lambda: 0)


def test_integrate_is_the_element_sum_at_any_thread_count(idle):
    from netgen.geom2d import unit_square
    from ngsolve import BND, Integrate, Mesh, dx, sin, x, y

    mesh = Mesh(unit_square.GenerateMesh(maxh=0.03))
    cf = sin(7 * x) * y + x * x
    ref = Integrate(cf, mesh, order=6)
    top = mesh.Boundaries("top")
    values = []
    for n in (1, 2, 2, 1, 2):
        with threaded(n):
            values.append((integrate(cf, mesh, order=6), integrate(x * y, mesh, BND, definedon=top),
                           integrate(cf * dx(element_boundary=True), mesh)))
    assert values == [values[0]] * len(values)
    assert values[0][0] == pytest.approx(ref, rel=1e-13)
    assert values[0][1] == pytest.approx(0.5, rel=1e-13)


#: NGSolve's space classes (a call of one, anywhere but through ``fe_space``, is flagged)
SPACES = {"H1", "VectorH1", "L2", "VectorL2", "HDiv", "HCurl", "FacetFESpace", "SurfaceL2",
          "NumberSpace", "IntegrationRuleSpace", "Compress", "FESpace", "Periodic"}


def _raw_space_calls(source: str) -> list[int]:
    """Lines of ``source`` calling an NGSolve space class directly."""
    import ast

    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Call):
            f = node.func
            name = f.id if isinstance(f, ast.Name) else getattr(f, "attr", None)
            if name in SPACES:
                out.append(node.lineno)
    return out


def test_no_module_makes_a_space_but_through_the_helper():
    """Every finite element space is made by ``fem.reproducible.fe_space`` (one made under the
    task manager is coloured by whichever thread locks its DOFs first)."""
    offenders = [f"{p.relative_to(PACKAGE)}:{line}" for p in PACKAGE.rglob("*.py")
                 for line in _raw_space_calls(p.read_text())]
    assert offenders == []


def test_the_check_sees_a_raw_space():
    assert _raw_space_calls("V = VectorH1(mesh, order=2)\nQ = ngsolve.L2(mesh)") == [1, 2]
    assert _raw_space_calls('"""Velocity VectorH1(order) x pressure H1(order - 1)"""') == []
    assert _raw_space_calls("V = fe_space(VectorH1, mesh, order=2)") == []


def test_a_space_made_under_the_task_manager_assembles_as_one_made_in_one_thread(idle):
    """``fe_space`` under 2 threads: Set and a nonlinear form's Apply give the bits of a space
    made with no task manager (one thread's colouring), in every repeat. (A raw ``VectorH1`` made
    under 2 threads on this mesh: 4 distinct results in 20, 5 of them not these.)"""
    import hashlib

    from netgen.geom2d import unit_square
    from ngsolve import CF, BilinearForm, GridFunction, InnerProduct, Mesh, VectorH1, dx, exp, grad, sin, x, y

    mesh = Mesh(unit_square.GenerateMesh(maxh=0.015))
    cf = CF((sin(7 * x) * y + x * x, exp(x * y)))

    def bits(fes) -> tuple[str, str]:
        u, v = fes.TnT()
        gf = GridFunction(fes)
        gf.Set(cf)
        a = BilinearForm(fes)
        a += (InnerProduct(grad(u), grad(v)) + (1 + gf * gf) * u * v) * dx
        r = gf.vec.CreateVector()
        a.Apply(gf.vec, r)
        return tuple(hashlib.sha1(w.FV().NumPy().tobytes()).hexdigest() for w in (gf.vec, r))

    with threaded(2), parallel():
        with serial():
            ref = bits(VectorH1(mesh, order=2))
        got = [bits(fe_space(VectorH1, mesh, order=2)) for _ in range(6)]
    assert got == [ref] * len(got)


def test_threaded_sets_the_count_and_the_outer_one_holds(idle):
    """A run is serial (no task manager: its idle workers spin) but inside ``parallel``,
    which takes the count ``threaded`` set, the outer one holding."""
    import ngsolve

    if reproducible.cores() < 2:
        pytest.skip("one core")
    with threaded(2):
        assert ngsolve.GetNumThreads() == 1
        with parallel():
            assert ngsolve.GetNumThreads() == 2
            with parallel():                       # nested: a no-op
                assert ngsolve.GetNumThreads() == 2
        assert ngsolve.GetNumThreads() == 1
        with threaded(1), parallel():
            assert ngsolve.GetNumThreads() == 2
    with threaded(1), parallel():
        assert ngsolve.GetNumThreads() == 1


def test_the_count_leaves_every_core_another_process_wants(monkeypatch):
    """threads_now: the count asked for, capped by the cores and by the cores no other runnable
    thread wants; "auto" asks for AUTO_MAX. Worked by hand for each line."""
    monkeypatch.setattr(reproducible, "cores", lambda: 2)
    for others, asked, expected in [(0, 2, 2), (1, 2, 1), (5, 2, 1), (0, 1, 1), (0, 8, 2),
                                    (0, "auto", 2), (1, "auto", 1)]:
        monkeypatch.setattr(reproducible, "others_running", lambda o=others: o)
        assert threads_now(asked) == expected, (others, asked)
    monkeypatch.setattr(reproducible, "cores", lambda: 16)
    for others, asked, expected in [(0, "auto", reproducible.AUTO_MAX), (13, "auto", 3),
                                    (3, 8, 8), (10, 8, 6), (16, 8, 1)]:
        monkeypatch.setattr(reproducible, "others_running", lambda o=others: o)
        assert threads_now(asked) == expected, (others, asked)


def test_a_busy_process_is_seen_running():
    """others_running sees a CPU-bound process beside this one (the kernel's runnable count):
    a busy loop is runnable at every instant."""
    import subprocess
    import sys
    import time

    busy = subprocess.Popen([sys.executable, "-c", "while True: pass"])
    try:
        time.sleep(0.3)
        seen = [reproducible.others_running() for _ in range(20)]
    finally:
        busy.kill()
        busy.wait()
    assert min(seen) >= 1


def _figures(out: Path) -> dict:
    """Every figure a run writes, but its times."""
    summary = json.loads((out / "summary.json").read_text())
    for key in [k for k in summary if "wall_time" in k or k.startswith("estimated_")
                or k == "solver_threads"]:
        summary.pop(key)
    with np.load(out / "fields.npz") as z:
        fields = {k: z[k].tobytes() for k in z.files}
    csvs = {p.name: p.read_bytes() for p in sorted(out.glob("*.csv"))}
    return {"summary": summary, "fields": fields, "csv": csvs}


def _solve(case, out: Path, monkeypatch) -> tuple[bytes, dict]:
    """Run ``case`` to ``out``: the flow's final solution vector (bytes) and its figures."""
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows import runner

    vectors = []

    class Kept(SteadyRun):
        def run(self, *args, **kwargs):
            result = super().run(*args, **kwargs)
            vectors.append(self.form.nonlinear.gf.vec.FV().NumPy().tobytes())
            return result

    monkeypatch.setattr(runner, "SteadyRun", Kept)
    runner.run_case(case, out, resume=False)
    return vectors[-1], _figures(out)


def _thermal_coulomb() -> dict:
    """The bundled thermal_pass with Coulomb friction and unilateral contact."""
    import tomllib

    from hotroll.examples import example_path

    d = tomllib.loads(example_path("thermal_pass").read_text())
    d["friction"] = {"law": "coulomb", "mu": 0.3}
    d["contact"] = {"unilateral": True}
    return d


#: Example 1 (viscoplastic); a thermal pass with Coulomb friction (an unsymmetric Jacobian),
#: the heat equation coupled (its exit temperatures are integrals) and unilateral contact (a
#: contact end a last bit could move)
CASES = {"viscoplastic": EXAMPLE1_COARSE, "coulomb_thermal": _thermal_coulomb()}


@pytest.mark.parametrize("base", CASES.values(), ids=CASES.keys())
def test_a_pass_is_the_same_bits_in_every_run_and_at_1_and_2_threads(base, tmp_path, idle,
                                                                     monkeypatch):
    runs = [_solve(build_case(base, **{"solver.threads": n}), tmp_path / f"{k}_{n}",
                   monkeypatch) for k, n in enumerate((2, 2, 1))]
    vec, figures = runs[0]
    assert figures["summary"]["converged"]
    for other_vec, other in runs[1:]:
        assert other_vec == vec
        assert other["fields"] == figures["fields"]
        assert other["csv"] == figures["csv"]
        assert other["summary"] == figures["summary"]


def test_a_region_holds_its_count_and_a_run_restores_ngsolves(monkeypatch):
    """A region that went serial (another process wanted the core) stays serial inside, even
    when the core frees meanwhile (its nested regions are no-ops); after ``threaded`` NGSolve
    has the thread count its caller had."""
    import ngsolve

    if reproducible.cores() < 2:
        pytest.skip("one core")
    before = ngsolve.GetNumThreads()
    busy = [1]
    monkeypatch.setattr(reproducible, "others_running", lambda: busy[0])
    with threaded(2):
        with parallel():
            assert ngsolve.GetNumThreads() == 1
            busy[0] = 0
            with parallel():
                assert ngsolve.GetNumThreads() == 1
        with parallel():
            assert ngsolve.GetNumThreads() == 2
    assert ngsolve.GetNumThreads() == before


def test_a_cgroup_quota_caps_the_cores(monkeypatch, tmp_path):
    """cores(): a cgroup v2 quota of 150000/100000 (1.5 CPUs) caps the affinity at 1; "max" does
    not cap."""
    import builtins

    real_open = builtins.open

    def fake(text):
        def opener(path, *a, **k):
            if str(path) == "/sys/fs/cgroup/cpu.max":
                f = tmp_path / "cpu.max"
                f.write_text(text)
                return real_open(f, *a, **k)
            return real_open(path, *a, **k)
        return opener

    monkeypatch.setattr(reproducible.os, "sched_getaffinity", lambda pid: {0, 1, 2, 3})
    monkeypatch.setattr(builtins, "open", fake("150000 100000\n"))
    assert reproducible.cores() == 1
    monkeypatch.setattr(builtins, "open", fake("max 100000\n"))
    assert reproducible.cores() == 4
