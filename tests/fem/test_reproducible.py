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
from hotroll.fem.reproducible import integrate, threaded

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


def test_integrate_is_the_element_sum_at_any_thread_count():
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


def test_threaded_sets_the_count_and_the_outer_one_holds():
    import ngsolve

    with threaded(2):
        assert ngsolve.GetNumThreads() == 2
        with threaded(1):
            assert ngsolve.GetNumThreads() == 2
    assert ngsolve.GetNumThreads() == 1          # no task manager
    with threaded(1):
        assert ngsolve.GetNumThreads() == 1


def _figures(out: Path) -> dict:
    """Every figure a run writes, but its times."""
    summary = json.loads((out / "summary.json").read_text())
    for key in [k for k in summary if "wall_time" in k or k.startswith("estimated_")]:
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
#: the heat equation coupled (its exit temperatures are integrals) and unilateral contact (an
#: active set a last bit could flip)
OPEN = pytest.mark.xfail(strict=False, reason="open (issue 50): with 2 threads some runs still "
                        "differ in the last bits, a source not found yet")
CASES = {"viscoplastic": pytest.param(EXAMPLE1_COARSE, marks=OPEN),
         "coulomb_thermal": pytest.param(_thermal_coulomb(), marks=OPEN)}


@pytest.mark.parametrize("base", CASES.values(), ids=CASES.keys())
def test_a_pass_is_the_same_bits_in_every_run_and_at_1_and_2_threads(base, tmp_path,
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
