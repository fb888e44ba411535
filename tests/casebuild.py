"""Building test cases from a base dict: one section replaced and dotted keys overridden."""
from __future__ import annotations

import copy
import math

from hotroll.config.case import Case, case_from_dict

#: Example 1 on a coarse contact mesh, steady, no figures: the base of the study and report
#: tests (about 1 s a run).
EX1_COARSE_TOML = """name = "ex1c"
[pass]
roll_radius = 0.6
entry_thickness = 0.5
exit_thickness = 0.4
roll_angular_velocity = 1.0471975511965976
[plate]
length = 1.0
[material]
K = 1.0
m = 0.2
[mesh]
h_contact = 0.02
[solver]
method = "steady"
threads = 1
[output]
figures = false
vtk = false
"""


def build_case(base: dict, section: str | None = None, table: dict | None = None,
               **dotted) -> Case:
    """``base`` with ``[section]`` replaced by ``table`` (if given) and ``{"sec.key": v}`` set."""
    d = copy.deepcopy(base)
    if table is not None:
        d[section] = table
    for key, value in dotted.items():
        sec, name = key.split(".")
        d.setdefault(sec, {})[name] = value
    return case_from_dict(d)


def example1_coarse(name: str, **sections) -> dict:
    """Example 1's pass (R = 0.6 m, 0.5 -> 0.4 m, omega = pi/3 rad/s, Norton-Hoff K = 1,
    m = 0.2) on the coarse mesh h = 0.02 m, one thread, no figures; ``sections`` replace or
    add whole sections (friction, solver, plate, ...)."""
    base = {
        "name": name,
        "pass": {"roll_radius": 0.6, "entry_thickness": 0.5, "exit_thickness": 0.4,
                 "roll_angular_velocity": math.pi / 3},
        "plate": {"length": 1.0},
        "material": {"K": 1.0, "m": 0.2},
        "mesh": {"h_contact": 0.02},
        "solver": {"method": "steady", "threads": 1},
        "output": {"figures": False, "vtk": False},
    }
    base.update(copy.deepcopy(sections))
    return base


#: The solved case several test files read (``solved_example1`` of tests/conftest.py): Example
#: 1's pass on a coarse mesh (h = 0.02 m), viscoplastic a_f = 5, a 4 m plate, steady (0.6 s).
EXAMPLE1_COARSE = example1_coarse("example1_coarse", plate={"length": 4.0},
                                  friction={"law": "viscoplastic", "a_f": 5.0})


def shared_scope(fixture_name, config) -> str:
    """Scope of a fixture whose result several tests read: "module", except in mutmut's stats
    run (MUTANT_UNDER_TEST=stats), where it is "function". mutmut records which tests call each
    function and runs only those against its mutants; a module fixture is built in the first
    test only, and the other tests reading it would never run against a mutant of the code
    that made their numbers."""
    import os

    return "function" if os.environ.get("MUTANT_UNDER_TEST") == "stats" else "module"


def gap_means_from_fields(summary: dict, fields: dict) -> dict:
    """mean_flow_stress and mean_strain_rate recomputed from written vertex fields (fields.npz):
    area means over the triangles whose centroid lies between the contact start and the roll
    gap, each triangle at the mean of its vertex values."""
    import numpy as np

    x0 = summary["contact_start"][0]
    p, t = fields["points"], fields["triangles"]
    cx = p[t, 0].mean(axis=1)
    band = (cx > x0) & (cx < summary["roll_centre"][0])
    e1, e2 = p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])[band]
    return {key: float(np.sum(area * fields[name][t[band]].mean(axis=1)) / area.sum())
            for key, name in (("mean_flow_stress", "sigma_ef"), ("mean_strain_rate", "edot"))}


def assert_same_table(a: list[dict], b: list[dict], skip=("wall_time_s", "worker")) -> None:
    """Two study tables row by row: the same keys, every value equal (NaN = NaN), but the
    ``skip`` ones (timings, which worker)."""
    assert len(a) == len(b)
    for ra, rb in zip(a, b):
        assert ra.keys() == rb.keys()
        for k in ra:
            if k in skip:
                continue
            va, vb = ra[k], rb[k]
            assert va == vb or (isinstance(va, float) and math.isnan(va) and math.isnan(vb)), \
                (ra.get("case"), k)


def assert_schedule_refused(d: dict, field: str) -> None:
    """``schedule_from_dict(d)`` refuses the schedule with a CaseError naming ``field``."""
    import pytest

    from hotroll.config.case import CaseError
    from hotroll.config.schedule import schedule_from_dict

    with pytest.raises(CaseError) as e:
        schedule_from_dict(d, "schedule.toml")
    assert field in str(e.value)


def steady_run(case):
    """The ``SteadyRun`` of a case (built, not solved), with the case's own settings."""
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.runner import build_model, steady_settings

    model, _ = build_model(case)
    return SteadyRun(model, steady_settings(case), case.plate.length)


def solved_steady_run(example: str):
    """A bundled example solved by the steady solver in process (no files): its ``SteadyRun``,
    for tests that read the solver's own objects (the thermal strip, the forms)."""
    from hotroll.config.case import load_case
    from hotroll.examples import example_path

    run = steady_run(load_case(example_path(example)).with_overrides(
        **{"solver.method": "steady"}))
    run.record = False
    run.solve()
    return run
