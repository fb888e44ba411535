"""results/ reads a ``Solution`` record, not the live solver (issue 52, stage 1): a ``Solution``
built by hand from known analytic fields, no solve, no mesh, is written by ``write_results`` in
a Python where NGSolve (and netgen) cannot be imported; every file is written and the figures
results computes from the record are the ones worked out by hand here.

The record: Example 1's pass (R = 0.6 m, 0.5 -> 0.4 m) in the steady solver's frame (axis at
x = 0), moved by a frame shift of 0.25 m; penalty contact over the whole arc, n = 41 nodes at
equal angles (vertex, midpoint, vertex, ...) with a pressure linear along the arc,
p = P0 + G s (s from the entry), and a slip U (phi_n - phi)/phi_n that changes sign at the
neutral angle phi_n; the strip's vertex fields a uniform plane-strain compression,
v = (a x, -a y), edot = 2a/sqrt3 (-).
"""
from __future__ import annotations

import json
import math
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from hotroll.model.solution import PassData, RollContact, Solution, VertexFields

HERE = Path(__file__).resolve().parent
#: the hand-built record's data
N, SHIFT, P0, G, A_RATE, PHI_N_SHARE = 41, 0.25, 2.0, 3.0, 0.4, 0.3


def _case():
    from casebuild import EXAMPLE1_COARSE, build_case

    return build_case(EXAMPLE1_COARSE, **{"contact.method": "penalty"})


def _arc(rp):
    """(angles from entry to exit, x, y, chord length s from the entry) of the N nodes."""
    ang = np.linspace(rp.bite_angle, 0.0, N)
    cx, cy = rp.centre
    x, y = cx - rp.radius * np.sin(ang), cy - rp.radius * np.cos(ang)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    return ang, x, y, s


def _trapezoid(f, s) -> float:
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(s)))


def _fields(rp, K, m, case) -> VertexFields:
    """The uniform compression v = (a x, -a y) on a 9 x 5 grid of the strip's rectangle."""
    X, Y = np.meshgrid(np.linspace(-0.4, 0.3, 9), np.linspace(0.0, rp.half_exit, 5))
    pts = np.stack([X.ravel(), Y.ravel()], -1)
    quads = [(j * 9 + i, j * 9 + i + 1, (j + 1) * 9 + i + 1, (j + 1) * 9 + i)
             for j in range(4) for i in range(8)]
    tris = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))])
    nv = len(pts)
    edot = np.full(nv, 2.0 * A_RATE / math.sqrt(3.0))
    top = np.arange(4 * 9, 5 * 9)
    return VertexFields(
        points=pts, triangles=tris, v=np.stack([A_RATE * pts[:, 0], -A_RATE * pts[:, 1]], -1),
        pressure=-K * pts[:, 0], edot=edot, strain=np.zeros(nv),
        sigma_ef=K * (math.sqrt(3.0) * edot) ** m, temperature=np.full(nv, case.plate.temperature),
        flow_temperature=np.full(nv, case.plate.temperature),
        contact_edges=(np.stack([top[:-1], top[1:]], -1),))


def hand_built() -> tuple[object, Solution]:
    """The case and its hand-built ``Solution`` (module docstring)."""
    case = _case()
    rp = replace(case.pass_.roll_pass(), axis_x=0.0)     # the steady solver's frame
    K, m = case.material.K, case.material.m
    ang, x, y, s = _arc(rp)
    p = P0 + G * s
    phi_n = PHI_N_SHARE * rp.bite_angle
    slip = rp.u_roll * (phi_n - ang) / phi_n
    prof = {"x": x, "y": y, "angle": ang, "v_slip": slip, "normal_stress": -p,
            "shear_stress": 0.2 * p * np.sign(-slip), "vertex": (np.arange(N) % 2 == 0).astype(int)}
    U, q = rp.u_roll, 1.04 * rp.u_roll * rp.half_exit       # 4 % forward slip
    force = _trapezoid(p * np.cos(ang), s)
    torque = rp.radius * _trapezoid(0.2 * p, s)
    row = {"step": 0, "time": math.nan, "m": m, "roll_force": force, "roll_torque": torque,
           "roll_power": torque * rp.omega, "forward_slip": 0.04,
           "entry_velocity": q / rp.half_entry, "exit_velocity": q / rp.half_exit,
           "mass_flux_in": q, "mass_flux_out": q, "plastic_power": 0.7 * torque * rp.omega,
           "friction_power": 0.3 * torque * rp.omega, "penalty_power": 0.0,
           "outlet_penalty_power": 0.0, "horizontal_force": 0.0, "neutral_angle": phi_n,
           "tension_power": 0.0, "contact_length": float(s[-1]), "a_f": 5.0,
           "strain_rate_measure": 0.0, "slip_measure": 0.0, "neutral_x": 0.0, "head_x": 0.3,
           **{f"{part}_force_{c}": 0.0 for part in ("roll", "free_top", "face", "tension",
                                                    "symmetry") for c in "xy"},
           "symmetry_stress_force_y": force, "balance_error": 0.0, "free_top_force_share": 0.0,
           "power_balance_error": 0.0, "penalty_share": 0.0, "exit_thickness_measured":
           2.0 * rp.half_exit, "iterations": 7, "residual": 1e-9, "solver_converged": True}
    row["roll_force_y"] = -force
    top = {"x": x[::-1].copy(), "y": y[::-1].copy(), "v1": np.full(N, U), "v2": np.zeros(N)}
    rate = 2.0 * A_RATE / math.sqrt(3.0)
    sol = Solution(
        step=0, time=math.nan, history=[row], status="steady", time_stepping=False, window=1,
        frame_shift=SHIFT, pass_data=PassData(h=0.02, K=K, m=m),
        contacts=(RollContact(rp=rp, profile=prof, method="penalty", exact=False),),
        tops=(top,), fields=_fields(rp, K, m, case),
        quantities={"mean_flow_stress": K * (math.sqrt(3.0) * rate) ** m,
                    "mean_strain_rate": rate},
        solve_stats={"newton_solves": 1, "coupling_updates": 3, "fixed_point_settled": True,
                     "surface_residual_h": 1e-3},
        dofs=1234, nonlinear="newton")
    return case, sol


def write(out: str) -> None:
    """Write the hand-built record's results into ``out`` (run in a Python without NGSolve)."""
    from hotroll.results.run_summary import write_results

    case, sol = hand_built()
    write_results(case, sol, Path(out), wall=0.5, extra={"warnings": []})


#: the child: NGSolve and netgen unimportable before hotroll is imported
CHILD = """
import sys
sys.modules["ngsolve"] = None
sys.modules["netgen"] = None
sys.path[:0] = [{tests!r}, {here!r}]
import test_no_live_run as t
t.write({out!r})
loaded = sorted(k for k in sys.modules if k.startswith(("hotroll.fem", "hotroll.solvers")))
print("LOADED", loaded)
"""


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("no_live_run")
    code = CHILD.format(tests=str(HERE.parent), here=str(HERE), out=str(out))
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return out, proc.stdout


def test_results_are_written_without_ngsolve(written):
    """Every file of a steady run without a temperature is written, with NGSolve and netgen
    unimportable, and neither ``hotroll.fem`` nor ``hotroll.solvers`` was loaded."""
    out, stdout = written
    assert sorted(p.name for p in out.iterdir()) == [
        "contact.csv", "fields.npz", "history.csv", "summary.json", "top.csv"]
    assert "LOADED []" in stdout


def test_figures_from_the_record_by_hand(written):
    """What results computes from the record, against the hand values: the entry pressure,
    the mean of p = P0 + G s over the first 5 % of the arc's chords S, is P0 + G 0.05 S / 2
    (the trapezoid of a linear function is exact); the P1 smoothing keeps a pressure linear
    along the arc (an L2 projection reproduces its space) and so does the exit correction
    (its fitted line is the pressure's): no normal-force change; the neutral point is the
    roll's point at phi_n, (cx - R sin phi_n, cy - R cos phi_n), moved by the frame shift
    as every x written is."""
    out, _ = written
    case, sol = hand_built()
    rp = sol.contacts[0].rp
    ang, x, y, s = _arc(rp)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["entry_pressure"] == pytest.approx(P0 + G * 0.05 * s[-1] / 2.0, rel=1e-12)
    assert summary["exit_correction_normal_force_change"] == pytest.approx(0.0, abs=1e-12)
    assert summary["min_contact_pressure"] == pytest.approx(P0, rel=1e-12)
    phi_n = PHI_N_SHARE * rp.bite_angle
    cx, cy = rp.centre
    assert summary["neutral_angle"] == pytest.approx(phi_n, rel=1e-12)
    assert summary["neutral_point"] == pytest.approx(
        [cx + SHIFT - rp.radius * math.sin(phi_n), cy - rp.radius * math.cos(phi_n)], rel=1e-12)
    assert summary["contact_start"] == pytest.approx([x[0] + SHIFT, y[0]], rel=1e-12)
    assert summary["roll_centre"] == pytest.approx([cx + SHIFT, cy], rel=1e-12)
    contact = np.genfromtxt(out / "contact.csv", delimiter=",", names=True)
    p = P0 + G * s
    assert contact["normal_stress_smooth"] == pytest.approx(-p, rel=1e-12)
    assert contact["normal_stress_corrected"] == pytest.approx(-p, rel=1e-12)
    assert contact["x"] == pytest.approx(x + SHIFT, rel=1e-12)


def test_roll_force_is_the_trapezoid_of_the_given_pressure(written):
    """[identity] The summary's roll force is the trapezoid of the given pressure's vertical
    component along the arc, the figure the hand-built history row carries (results averages
    the history, it does not integrate); mean_pressure = force / contact length."""
    out, _ = written
    case, sol = hand_built()
    ang, x, y, s = _arc(sol.contacts[0].rp)
    summary = json.loads((out / "summary.json").read_text())
    force = _trapezoid((P0 + G * s) * np.cos(ang), s)
    assert summary["roll_force"] == pytest.approx(force, rel=1e-12)
    assert summary["mean_pressure"] == pytest.approx(force / s[-1], rel=1e-12)
    assert summary["converged"] and summary["exit_code"] == 0


def test_fields_are_the_record_moved_by_the_frame_shift(written):
    """[identity] fields.npz holds the record's vertex fields (the uniform compression), its
    points moved by the frame shift; the roll's contact edges as given."""
    out, _ = written
    _, sol = hand_built()
    f = sol.fields
    with np.load(out / "fields.npz") as z:
        assert list(z.files)[:9] == ["points", "triangles", "v", "pressure", "edot", "strain",
                                     "sigma_ef", "temperature", "flow_temperature"]
        assert np.array_equal(z["points"], f.points + [SHIFT, 0.0])
        assert np.array_equal(z["v"], f.v) and np.array_equal(z["edot"], f.edot)
        assert np.array_equal(z["contact_edges"], f.contact_edges[0])
