"""Interstand tensions from the stand speeds (workflows/tandem.py, ``mill.tensions =
"from_speeds"``): the search on a model whose answer is known in closed form (with stands that
lose flux, as a coarse FE stand does), and a coarse three-stand hot tandem on FE (about 20 s):
what leaves a stand enters the next, thickness and flux, measured on the solved fields; the
tensions move with a stand's speed as slab theory says."""
from __future__ import annotations

import copy
import json
import tomllib
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from casebuild import assert_schedule_refused, shared_scope

from hotroll.config.schedule import schedule_from_dict
from hotroll.workflows.schedule import run_schedule
from hotroll.workflows.tandem import TensionError, solve_tensions

DATA = Path(__file__).resolve().parents[1] / "data" / "two_pass_schedule.toml"


# --- the search on a log-linear mill: ln Q_k = a_k - b_k t_{k-1} + c_k t_k -------------------

def _mill(a, b, c, sigma=1e8, tol=1e-6, loss=None):
    """A fake schedule and roll function whose stands' exit fluxes follow the log-linear law
    (tensions in Pa), each stand passing out (1 - loss_k) of what it takes in (default: all);
    its interstand tensions solve a tridiagonal linear system exactly."""
    n = len(a)
    loss = np.zeros(n) if loss is None else np.asarray(loss, dtype=float)
    sch = SimpleNamespace(
        passes=[SimpleNamespace(front_tension=0.0, back_tension=0.0) for _ in range(n)],
        mill=SimpleNamespace(flux_tolerance=tol), pass_name=lambda k: f"F{k + 1}")
    calls = []

    def roll(t, quiet):
        tt = np.r_[0.0, t, 0.0]
        calls.append(list(t))
        out = [float(np.exp(a[k] - b[k] * tt[k] + c[k] * tt[k + 1])) for k in range(n)]
        rows = [{"mass_flux_out": out[k], "mass_flux": out[k] / (1.0 - loss[k]),
                 "mean_flow_stress": sigma, "fe_solves": 1} for k in range(n)]
        return rows, [{}] * n
    return sch, roll, calls


def _exact(a, b, c, loss=None):
    """Solve a_{k+1} - ln(1 - loss_{k+1}) - b_{k+1} t_k + c_{k+1} t_{k+1} = a_k - b_k t_{k-1}
    + c_k t_k: stand k+1's inlet flux is stand k's exit flux."""
    n = len(a)
    loss = np.zeros(n) if loss is None else np.asarray(loss, dtype=float)
    A, rhs = np.zeros((n - 1, n - 1)), np.zeros(n - 1)
    for k in range(n - 1):
        rhs[k] = a[k] - a[k + 1] + np.log(1.0 - loss[k + 1])
        A[k, k] = -b[k + 1] - c[k]
        if k + 1 < n - 1:
            A[k, k + 1] = c[k + 1]
        if k > 0:
            A[k, k - 1] = b[k]
    return np.linalg.solve(A, rhs)


def test_the_search_finds_the_tensions_of_a_log_linear_mill():
    """Four stands, each downstream one 1-1.5 % too fast at zero tension: the tridiagonal Jacobian from the two
    coloured runs is exact for this law, so one Newton step lands on the closed-form tensions
    (to the flux tolerance); 2 + 1 + 1 runs whatever the number of stands."""
    a = np.log([1.0, 1.01, 1.025, 1.04])
    b, c = np.array([2.0, 2.5, 3.0, 3.5]) * 1e-9, np.array([3.0, 3.5, 4.0, 4.5]) * 1e-9
    sch, roll, calls = _mill(a, b, c)
    rows, _, info = solve_tensions(sch, roll, None, lambda m: None)
    t = np.asarray(info["interstand_tensions"])
    assert t == pytest.approx(_exact(a, b, c), rel=1e-6)
    assert np.all(t > 0) and info["flux_mismatch"] <= 1e-6
    assert info["tension_runs"] == len(calls) == 4
    q = [r["mass_flux_out"] for r in rows]
    assert max(q) / min(q) - 1 <= 2e-6


def test_what_leaves_a_stand_enters_the_next_though_each_stand_loses_flux():
    """The same four stands, each losing 1.7-2e-3 of its flux (what a coarse FE stand does:
    issue 51): the tensions make stand k+1's inlet flux stand k's exit flux (the closed form
    with the losses), not the exit fluxes equal; the exit fluxes then differ by the losses, and
    the largest loss is reported as the stands' own."""
    a = np.log([1.0, 1.01, 1.025, 1.04])
    b, c = np.array([2.0, 2.5, 3.0, 3.5]) * 1e-9, np.array([3.0, 3.5, 4.0, 4.5]) * 1e-9
    loss = [1.7e-3, 2.0e-3, 1.8e-3, 1.9e-3]
    sch, roll, calls = _mill(a, b, c, loss=loss)
    rows, _, info = solve_tensions(sch, roll, None, lambda m: None)
    assert np.asarray(info["interstand_tensions"]) == pytest.approx(_exact(a, b, c, loss),
                                                                    rel=1e-6)
    for up, down in zip(rows[:-1], rows[1:]):
        assert down["mass_flux"] / up["mass_flux_out"] - 1.0 == pytest.approx(0.0, abs=1e-6)
    assert info["stand_flux_error"] == pytest.approx(2.0e-3, rel=1e-9)
    assert info["tension_runs"] == len(calls) == 4


def test_a_too_slow_stand_is_named_not_pulled_into_compression():
    """Stand 2 takes 2 % less than stand 1 delivers at zero tension: only a compressive force
    would match them (the strip loops); the search stops naming the pair."""
    a = np.log([1.0, 0.98, 1.0])
    b, c = np.full(3, 2e-9), np.full(3, 3e-9)
    sch, roll, _ = _mill(a, b, c)
    with pytest.raises(TensionError, match="compressive force between stands F1 and F2"):
        solve_tensions(sch, roll, None, lambda m: None)


def test_a_finished_runs_tensions_are_the_start():
    a = np.log([1.0, 1.01, 1.02])
    b, c = np.full(3, 2e-9), np.full(3, 3e-9)
    sch, roll, calls = _mill(a, b, c)
    t = solve_tensions(sch, roll, None, lambda m: None)[2]["interstand_tensions"]
    sch, roll, calls = _mill(a, b, c)
    info = solve_tensions(sch, roll, t, lambda m: None)[2]
    assert len(calls) == 1 and info["interstand_tensions"] == pytest.approx(t, rel=1e-12)


# --- a coarse three-stand hot tandem on FE ---------------------------------------------------

OMEGA = [1.0, 1.186, 1.397]        # rad/s: about 1 % and 2 % faster than mass flow at zero pull


def _tandem(omega=OMEGA) -> dict:
    d = tomllib.loads(DATA.read_text())
    d["mesh"]["h_contact"] = 0.007
    d["mill"] = {"speeds": "given", "tensions": "from_speeds"}
    d["pass"][0]["exit_thickness"] = 0.085
    d["pass"][1].update(exit_thickness=0.072, transport={"duration": 10.0})
    d["pass"].append({"name": "R3", "roll_radius": 0.3, "exit_thickness": 0.062})
    for p, w in zip(d["pass"], omega):
        p["roll_angular_velocity"] = w
    return d


@pytest.fixture(scope=shared_scope)
def tandems(tmp_path_factory):
    out = {}
    for key, omega in (("base", OMEGA), ("faster_2", [OMEGA[0], 1.005 * OMEGA[1], OMEGA[2]])):
        where = tmp_path_factory.mktemp(key)
        rows = run_schedule(schedule_from_dict(_tandem(omega)), where, resume=False,
                            figure=False)
        out[key] = rows, json.loads((where / "schedule.json").read_text()), where
    return out


def _faces(where: Path, row: dict) -> dict:
    """The stand's inlet and outlet faces from its solved fields (fields.npz): the flux (half
    strip, the trapezoid rule over the face's vertices: the strip is rigid there) and the full
    thickness (twice the face's top)."""
    f = np.load(where / row["case"] / "fields.npz")
    p, v = f["points"], f["v"]
    out = {}
    for key, x in (("in", p[:, 0].min()), ("out", p[:, 0].max())):
        on = np.abs(p[:, 0] - x) <= 1e-9 * max(1.0, abs(x))
        o = np.argsort(p[on, 1])
        y, vx = p[on, 1][o], v[on, 0][o]
        out[key] = (float(np.trapezoid(vx, y)), 2.0 * float(y[-1]))
    return out


def test_what_leaves_a_stand_enters_the_next(tandems):
    """Between stands k and k+1, from each stand's own solved fields: stand k+1's inlet is as
    thick as stand k's outlet (the solved exit thickness is handed on, not the nominal gap:
    this coarse strip leaves 1.2e-3 thinner than the gap), and takes in what stand k passes
    out, to the flux tolerance 1e-4 (before issue 51: 1.8e-3 apart). The tensions are handed
    on: stand k's front tension is stand k+1's back tension."""
    rows, js, where = tandems["base"]
    faces = [_faces(where, r) for r in rows]
    mismatch = []
    for k, (up, down) in enumerate(zip(faces[:-1], faces[1:])):
        assert down["in"][1] == pytest.approx(up["out"][1], rel=1e-9)
        assert rows[k + 1]["entry_thickness"] == pytest.approx(up["out"][1], rel=1e-9)
        assert rows[k]["exit_thickness"] == rows[k + 1]["entry_thickness"]
        mismatch.append(np.log(down["in"][0] / up["out"][0]))
    assert np.max(np.abs(mismatch)) <= 1e-4
    assert js["flux_mismatch"] == pytest.approx(float(np.max(np.abs(mismatch))), abs=1e-7)
    # each stand's own FE loss, reported as measured on its faces (issue 51: 1.7-2e-3 at this
    # coarse mesh; 2.1e-5 since the refined corner and the traced top's cubic rule; not the
    # tensions' to mend), the faces' trapezoid against the FE integral on a rigid face: to
    # 1e-8 (measured 3e-9)
    own = max(abs(f["out"][0] / f["in"][0] - 1.0) for f in faces)
    assert js["stand_flux_error"] == pytest.approx(own, abs=1e-8)
    t = js["interstand_tensions"]
    assert [r["front_tension"] for r in rows[:-1]] == t == [r["back_tension"] for r in rows[1:]]
    assert rows[0]["back_tension"] == 0.0 and rows[-1]["front_tension"] == 0.0
    # the speeds ask for a real pull, well below the flow stress
    assert all(0.02 * r["mean_flow_stress"] < x < 0.5 * r["mean_flow_stress"]
               for x, r in zip(t, rows))
    assert js["units"]["interstand_tensions"] == "Pa"


def test_a_faster_stand_pulls_harder_before_it_and_pushes_less_after(tandems):
    """Slab theory: a stand's forward slip rises with its front tension and falls with its back
    tension, so stand 2 turned 0.5 % faster takes more tension from stand 1 and leaves less to
    stand 3."""
    t0 = tandems["base"][1]["interstand_tensions"]
    t1 = tandems["faster_2"][1]["interstand_tensions"]
    assert t1[0] > 1.05 * t0[0] and t1[1] < 0.95 * t0[1]


@pytest.mark.parametrize("change,field", [
    (lambda d: d["mill"].update(speeds="mass_flow"), 'mill.tensions: "from_speeds" needs'),
    (lambda d: d["mill"].update(flux_tolerance=0.1), "mill.flux_tolerance"),
    (lambda d: d["mill"].update(tensions="measured"), "mill.tensions"),
])
def test_bad_tandems_name_the_field(change, field):
    d = copy.deepcopy(_tandem())
    change(d)
    assert_schedule_refused(d, field)
