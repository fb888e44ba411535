"""Exact roll contact (issue 30): the roll as a constraint, the pressure as a multiplier.

Kinds of check (docs/testing.md): the speed and time-unit scalings are exact scalings of the
equations (an independent reference: Norton-Hoff is a power law in the rate, so omega x s with
eps0 x s must give the same flow with every stress x s^m); the frame shift is an exact
invariance; the smooth-pressure and unilateral checks are limits derived by hand (a pressure
has no zigzag at the mesh scale; a contact pressure is >= 0 and the strip leaving the roll does
not penetrate it); the comparison with the penalty and with the report's scheme is a
self-comparison (two formulations of the same problem).
"""
from __future__ import annotations

import copy
import math
import tempfile
from pathlib import Path

import numpy as np
import pytest
from casebuild import example1_coarse, shared_scope

from hotroll.config.case import case_from_dict
from hotroll.workflows.runner import run_case


def _same(a, b, rel: float, abs_: float = 0.0) -> bool:
    """a == b to the tolerance; null (no neutral point in a sticking zone) only equals null."""
    if a is None or b is None:
        return a is None and b is None
    return a == pytest.approx(b, rel=rel, abs=abs_)

def solve(d: dict) -> tuple[dict, dict]:
    """(summary, contact.csv columns) of the case ``d``."""
    case = case_from_dict(d)
    with tempfile.TemporaryDirectory() as tmp:
        s = run_case(case, Path(tmp), resume=False)
        import csv

        with open(Path(tmp) / "contact.csv") as f:
            rows = list(csv.DictReader(f))
    prof = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    return s, prof


def with_(d: dict, **dotted) -> dict:
    d = copy.deepcopy(d)
    for key, value in dotted.items():
        sec, name = key.split(".")
        d.setdefault(sec, {})[name] = value
    return d


# --- exact scaling in the roll speed and the unit of time -----------------------------------
LAWS = {"viscoplastic": {"law": "viscoplastic"},            # a_f estimated (3.15)
        "coulomb": {"law": "coulomb", "mu": 0.3},
        "tresca": {"law": "tresca", "factor": 0.9}}
BASE_OMEGA = math.pi / 3


def _scaled(law: str, factor: float, minutes: bool = False) -> dict:
    """Example 1 (coarse) at omega x factor with eps0 x factor (the law's own rate scale); in
    minutes: omega and eps0 per minute (x60) and K in Pa min^m (K / 60^m)."""
    d = example1_coarse(f"scale-{law}", friction=LAWS[law])
    t = 60.0 if minutes else 1.0
    d["pass"]["roll_angular_velocity"] = BASE_OMEGA * factor * t
    d["material"]["eps0"] = 1e-4 * factor * t
    d["material"]["K"] = 1.0 / t ** d["material"]["m"]
    return d


@pytest.fixture(scope=shared_scope, params=sorted(LAWS))
def speed_runs(request):
    law = request.param
    return law, {f: solve(_scaled(law, f))[0] for f in (0.01, 1.0, 100.0)}, \
        solve(_scaled(law, 1.0, minutes=True))[0]


def test_roll_speed_scales_exactly(speed_runs):
    """omega = 0.01, 1, 100 x pi/3 (eps0 with it): forward slip, neutral angle and the contact
    arc the same to 1e-6, force and torque x (omega ratio)^m to 1e-6, every run converged, the
    same number of Newton iterations."""
    law, runs, _ = speed_runs
    ref, m = runs[1.0], runs[1.0]["m"]
    assert ref["exit_code"] == 0, (law, ref["failure"])
    for f, s in runs.items():
        assert s["exit_code"] == 0, (law, f, s["failure"])
        for key in ("forward_slip", "neutral_angle", "contact_start_angle", "contact_end_angle",
                    "contact_length", "mass_flux_error"):
            assert _same(s[key], ref[key], 1e-6, 1e-9), (law, f, key)
        for key in ("roll_force", "roll_torque"):
            assert s[key] == pytest.approx(ref[key] * f**m, rel=1e-6), (law, f, key)
        assert s["nonlinear_iterations"] == ref["nonlinear_iterations"], (law, f)


def test_minutes_give_the_same_pass(speed_runs):
    """The same pass in minutes (omega, eps0 per minute, K in Pa min^m): the same forces,
    torques, slip and angles to 1e-6 (the power in W/m reads per minute: / 60)."""
    law, runs, s = speed_runs
    ref = runs[1.0]
    for key in ("forward_slip", "neutral_angle", "contact_end_angle", "roll_force",
                "roll_torque"):
        assert _same(s[key], ref[key], 1e-6, 1e-9), (law, key)
    assert s["roll_power"] == pytest.approx(ref["roll_power"] * 60.0, rel=1e-6)


# --- frame ---------------------------------------------------------------------------------
def test_the_roll_axis_can_be_anywhere(tmp_path):
    """roll_axis_x = 0, 1 and 37.5 m: the steady solver works in the roll's frame, so every
    number is the same to 1e-9 and every written position moves with the axis (summary,
    contact.csv, top.csv, fields.npz)."""
    d = example1_coarse("frame")
    runs = {}
    for ax in (0.0, 1.0, 37.5):
        case = case_from_dict(with_(d, **{"pass.roll_axis_x": ax}))
        out = tmp_path / f"ax{ax}"
        s = run_case(case, out, resume=False)
        files = {name: np.genfromtxt(out / name, delimiter=",", names=True)
                 for name in ("contact.csv", "top.csv")}
        runs[ax] = (s, files, np.load(out / "fields.npz")["points"])
    ref, ref_files, ref_pts = runs[1.0]
    for ax, (s, files, pts) in runs.items():
        for key in ("roll_force", "roll_torque", "forward_slip", "neutral_angle",
                    "contact_end_angle", "plastic_power", "a_f", "mass_flux_in",
                    "nonlinear_iterations", "dofs"):
            assert _same(s[key], ref[key], 1e-9, 1e-12), (ax, key)
        assert s["neutral_angle_reason"] == ref["neutral_angle_reason"]
        for key in ("roll_centre", "contact_start", "contact_end"):
            assert s[key][0] - ax == pytest.approx(ref[key][0] - 1.0, abs=1e-9), (ax, key)
            assert s[key][1] == pytest.approx(ref[key][1], abs=1e-12), (ax, key)
        for name in files:
            assert files[name]["x"] - ax == pytest.approx(ref_files[name]["x"] - 1.0, abs=1e-9)
        assert pts[:, 0] - ax == pytest.approx(ref_pts[:, 0] - 1.0, abs=1e-9)


# --- the pressure ------------------------------------------------------------------------------
def _zigzag(prof: dict) -> float:
    """Largest departure of a raw nodal normal stress from the local quadratic through its
    neighbours (least squares over 7 contact nodes), over the arc's inner 96 %, / peak."""
    sn, ang = prof["normal_stress"], prof["angle"]
    n = len(sn)
    inner = (ang <= ang[0] - 0.02 * (ang[0] - ang[-1])) & (ang >= ang[-1] + 0.02 * (ang[0] - ang[-1]))
    dev = 0.0
    for i in np.nonzero(inner)[0]:
        lo, hi = max(0, i - 3), min(n, i + 4)
        c = np.polyfit(ang[lo:hi], sn[lo:hi], 2)
        dev = max(dev, abs(sn[i] - np.polyval(c, ang[i])))
    return dev / np.max(np.abs(sn))


FINISHING = {   # a finishing-type pass (5 -> 3.6 mm, R = 0.35 m, 0.4 m/s, Coulomb 0.3)
    "name": "finishing",
    "pass": {"roll_radius": 0.35, "entry_thickness": 0.005, "exit_thickness": 0.0036,
             "roll_angular_velocity": 0.4 / 0.35},
    "plate": {"length": 0.2},
    "material": {"K": 1.5e8, "m": 0.12},
    "friction": {"law": "coulomb", "mu": 0.3},
    "solver": {"method": "steady", "threads": 1},
    "contact": {"unilateral": True},
    "output": {"figures": False, "vtk": False},
}


@pytest.fixture(scope=shared_scope)
def finishing_runs():
    from hotroll.model.geometry import auto_contact_size

    h = auto_contact_size(case_from_dict(FINISHING).pass_.roll_pass())
    return {k: solve(with_(FINISHING, **{"mesh.h_contact": h / k})) for k in (1, 2)}


def test_the_pressure_is_smooth_up_to_the_arcs_ends(finishing_runs):
    """The nodal normal stress (the multiplier's nodal forces over their lengths) within 10 %
    of the peak of its local smooth curve over the inner 96 % of the arc, on the automatic
    mesh and on one twice as fine; no tensile value
    beyond the contact end's tolerance (the end is iterated to p = 0 within 1e-3 h: a pressure
    of about 1e-4 of the peak)."""
    for k, (s, prof) in finishing_runs.items():
        assert s["exit_code"] == 0, (k, s["failure"])
        assert _zigzag(prof) < 0.10, k
        assert np.max(prof["normal_stress"]) <= 1e-3 * np.max(np.abs(prof["normal_stress"]))


def test_coulomb_shear_follows_the_multiplier_at_vertices_and_midpoints(finishing_runs):
    """Where the strip slips (|v_s| > 1 % U), Coulomb's shear is min(mu p, k) of the multiplier
    pressure at vertices and midpoints alike: |tau| / min(mu p, k) = 1 +- 0.05 at both."""
    for k, (s, prof) in finishing_runs.items():
        U = s["roll_surface_speed"]
        slip = np.abs(prof["v_slip"]) > 0.01 * U
        p = -prof["normal_stress_multiplier"]     # the multiplier's own nodal values
        limit = np.minimum(0.3 * p, prof["shear_flow_stress"])
        ok = slip & (p > 0)
        for vertex in (0, 1):
            sel = ok & (prof["vertex"] == vertex)
            ratio = np.abs(prof["shear_stress"][sel]) / limit[sel]
            assert sel.sum() > 5 and np.all(np.abs(ratio - 1.0) < 0.05), (k, vertex)


def test_exact_contact_has_no_leak_and_no_penalty_on_the_roll(finishing_runs):
    """Flux in = flux out up to the traced free tops' discretisation (far below the forward
    slip, falling with h), no penalty power."""
    leaks = []
    for k, (s, _) in finishing_runs.items():
        assert s["leak_to_slip"] < 0.05, k
        leaks.append(s["mass_flux_error"])
        assert abs(s["penalty_share"]) < 1e-9, k
    # on the default mesh refined at the contact's start the traced tops' leak is down to
    # their own 1e-3 h tolerance's band (measured 7.6e-6, 8.1e-6; 1.43e-4 -> 1.03e-4 without
    # the refinement: first order in h, tests/solvers/test_contact_start_mesh.py)
    assert max(abs(x) for x in leaks) < 5e-5, leaks


# --- unilateral contact ------------------------------------------------------------------------
@pytest.fixture(scope=shared_scope)
def example1_unilateral():
    return solve(example1_coarse("unilateral"))       # unilateral is the default


def test_a_thick_strip_leaves_the_roll_before_the_gap(example1_unilateral):
    """Example 1 (h/l_c about 1.8): held to the whole arc, the contact stress turns tensile
    before the gap (next test); unilateral (the default), the strip leaves the roll where the
    pressure falls to zero: the contact's end is a node of the arc's chain (the map puts it
    there), its pressure is zero to the solver's tolerance (1e-3 of the peak: the condition the
    end is iterated to), the pressure >= 0 on the arc, the run converges."""
    s, prof = example1_unilateral
    assert s["exit_code"] == 0, s["failure"]
    assert s["unilateral"] is True and s["contact_end_kind"] == "separation"
    assert s["separation_angle"] > 0.01
    # the arc's ends are the written profile's (plumbing); the gap of a rigid roll is angle 0
    assert s["contact_end_angle"] == pytest.approx(prof["angle"][-1], abs=1e-12)
    assert s["separation_angle"] == pytest.approx(prof["angle"][-1], abs=1e-12)
    assert s["contact_start_angle"] == pytest.approx(prof["angle"][0], abs=1e-12)
    p = -prof["normal_stress"]
    assert abs(p[-1]) <= 1e-3 * p.max()
    assert s["contact_end_pressure"] == pytest.approx(p[-1], abs=1e-9 * p.max())
    assert p.min() >= -1e-3 * p.max() and not s["contact_loss_detected"]


def test_held_to_the_arc_the_tensile_stretch_is_reported():
    """Bilateral exact contact on the same pass: the raw multiplier's tensile nodes at the
    exit are reported as contact loss (no exit correction hides them), the end named held."""
    s, prof = solve(with_(example1_coarse("bilateral"), **{"contact.unilateral": False}))
    assert s["exit_code"] == 0
    assert s["unilateral"] is False and s["contact_end_kind"] == "held"
    assert np.max(prof["normal_stress"]) > 0.0
    assert s["contact_loss_detected"] and s["min_contact_pressure"] < 0.0
    assert s["contact_end_angle"] == pytest.approx(0.0, abs=1e-12)
    assert s["separation_angle"] is None


def test_the_separation_point_converges_with_the_mesh():
    """Example 1 on the report's meshes C1, C2 and M2: the separation angle's spread below
    10 % of its distance from the gap (issue 50; with the end snapped to a node it moved by
    one element, 0.040 rad on C2 against 0.0675 at h = 0.02), each run settled (exit 0; the
    old active set cycled on F2) and without tension on the arc."""
    angles = []
    for mesh in ("C1", "C2", "M2"):
        s, prof = solve(example1_coarse(f"sep_{mesh}", mesh={"h_contact": mesh}))
        assert s["exit_code"] == 0, (mesh, s["failure"])
        p = -prof["normal_stress"]
        assert p.min() >= -1e-3 * p.max(), mesh
        angles.append(s["separation_angle"])
    assert max(angles) - min(angles) < 0.1 * min(angles), angles


def test_the_roughing_slab_is_not_held_by_a_pulling_roll():
    """The bundled roughing_slab (200 -> 170 mm, Tresca 0.9): held to the arc its multiplier
    ends at -114 MPa (issue 50); by default the strip leaves the roll before the gap, no
    tensile pressure anywhere on the arc, the run settles. [hand] the end is iterated to
    p = 0 within its tolerance in x (an elastic strip's 1e-2 h, solvers/couplings.py:
    ContactEnd), so the pressure left at the end is at most about the slope there times that
    tolerance: asserted below twice the last arc segment's slope times it (measured 4.9e5 Pa
    against 9.6e5 Pa; the entry corner's peak, 3.4e8 Pa on the refined mesh, says nothing
    about the end)."""
    import tomllib

    from hotroll.examples import example_path
    from hotroll.solvers.couplings import ContactEnd
    from hotroll.solvers.steady_settings import SteadySettings

    d = tomllib.loads(example_path("roughing_slab.toml").read_text())
    d = with_(d, **{"solver.threads": 1, "output.figures": False, "output.vtk": False})
    s, prof = solve(d)
    assert s["exit_code"] == 0, s["failure"]
    assert s["contact_end_kind"] == "separation"
    p = -prof["normal_stress"]
    assert p.min() >= -1e-3 * p.max()
    case = case_from_dict(d)
    assert case.strip_elasticity is not None
    tol_x = ContactEnd.TOLERANCE_ELASTIC * SteadySettings().surface_tol * s["h_contact"]
    x = prof["x"]
    slope = (p[-2] - p[-1]) / (x[-1] - x[-2])
    assert slope > 0.0
    assert abs(p[-1]) <= 2.0 * slope * tol_x


def test_the_separated_top_stays_off_the_roll(example1_unilateral):
    """After the contact's end the traced exit top lies on or below the roll (no penetration)
    and the exit is thinner than the gap (the strip went on stretching)."""
    from hotroll.fem.free_surface import roll_height

    s, _ = example1_unilateral
    case = case_from_dict(with_(example1_coarse("unilateral"), **{"contact.unilateral": True}))
    rp = case.pass_.roll_pass()
    with tempfile.TemporaryDirectory() as tmp:
        run_case(case, Path(tmp), resume=False)
        import csv

        with open(Path(tmp) / "top.csv") as f:
            top = [(float(r["x"]), float(r["y"])) for r in csv.DictReader(f)]
    x, y = np.array(top).T
    on_arc = (x > rp.x_touch) & (x < rp.axis_x)
    assert np.all(y[on_arc] <= roll_height(rp, x[on_arc]) + 1e-9 * rp.radius)
    assert s["exit_thickness"] < 2 * rp.half_exit


# --- exit codes --------------------------------------------------------------------------------
LAB = {   # a slow lab pass: 0.02 m/s roll surface speed, m = 0.05, R/h0 = 10, 25 %
    "name": "lab",
    "pass": {"roll_radius": 0.1, "entry_thickness": 0.01, "exit_thickness": 0.0075,
             "roll_angular_velocity": 0.2},
    "plate": {"length": 0.1},
    "material": {"K": 1e8, "m": 0.05},
    "friction": {"law": "tresca", "factor": 0.3},
    "solver": {"method": "steady", "threads": 1},
    "output": {"figures": False, "vtk": False},
}


def test_a_leaking_penalty_is_not_a_success():
    """The report's penalty on a slow lab pass (0.02 m/s, m = 0.05) lets the strip through the
    roll by more than a fifth of the forward slip: exit code 7, the reason named; the same pass
    with exact contact is a success."""
    lab = LAB
    pen, _ = solve(with_(lab, **{"contact.method": "penalty"}))
    ex, _ = solve(lab)
    assert ex["exit_code"] == 0 and ex["leak_to_slip"] < 0.05     # the traced tops' flux
    assert pen["exit_code"] == 7 and "leak_to_slip" in pen["failure"]
    for r in (pen, ex):   # the criterion's figure from the summary's own (plumbing)
        assert r["leak_to_slip"] == pytest.approx(
            abs(r["mass_flux_error"]) / max(abs(r["forward_slip"]), 0.01), rel=1e-12)
    assert pen["forward_slip"] < ex["forward_slip"]


def test_the_penalty_is_an_option_of_the_steady_solver_only():
    """contact.method = "multiplier" with the report's scheme is refused, naming the field."""
    from hotroll.config.case import CaseError

    with pytest.raises(CaseError, match="contact.method"):
        case_from_dict(with_(example1_coarse("x"), **{"contact.method": "multiplier",
                                                       "solver.method": "transient"}))
    assert case_from_dict(with_(example1_coarse("x"), **{"solver.method": "transient"})
                          ).contact.resolved("transient") == "penalty"


def test_unilateral_contact_needs_the_steady_solver_and_traced_tops():
    """[contact] unilateral = true with the report's scheme (its bilateral (2.28a)) or with
    constrained tops (no free top to trace after the contact's end) is refused naming the
    field; "auto" resolves to the steady solver's unilateral and the scheme's bilateral."""
    from hotroll.config.case import CaseError

    for other in ({"solver.method": "transient"}, {"plate.free_surface": "constrained"}):
        with pytest.raises(CaseError, match="contact.unilateral"):
            case_from_dict(with_(example1_coarse("x"), **{"contact.unilateral": True}, **other))
    case = case_from_dict(example1_coarse("x"))
    assert case.contact.unilateral == "auto"
    assert case.contact.resolved_unilateral("steady") is True
    assert case.contact.resolved_unilateral("transient") is False


# --- the written pressure carries the force -------------------------------------------------
def test_the_written_pressure_and_shear_give_the_roll_force(finishing_runs):
    """The roll force recomputed from contact.csv alone: int (-sigma_n n_y... ) along the arc,
    the P2 profile integrated by Simpson's rule per edge (vertex, midpoint, vertex) with the
    roll's normal and tangent at each node, against summary's roll_force (from the form's
    integrals): 2e-3 (an independent quadrature of the same fields)."""
    for k, (s, prof) in finishing_runs.items():
        R = s["roll_radius"]
        cx, cy = s["roll_centre"]
        x, y = prof["x"], prof["y"]
        n = np.stack([cx - x, cy - y], -1) / R           # into the roll
        t = np.stack([-(y - cy), x - cx], -1) / R         # along U
        # traction of the roll on the strip: sigma_n n + tau t (sigma_n < 0 in compression)
        fy = prof["normal_stress"] * n[:, 1] + prof["shear_stress"] * t[:, 1]
        seg = np.hypot(np.diff(x), np.diff(y))
        L = seg[0::2] + seg[1::2]
        force = -np.sum(L * (fy[0:-1:2] + 4 * fy[1::2] + fy[2::2]) / 6.0)
        assert force == pytest.approx(s["roll_force"], rel=2e-3), k


def test_sticking_zone_by_hand():
    """``Q.sticking_zone`` on profiles worked by hand: |v_s| < 1e-3 U over more than
    ``min_length``; the longest stretch; nodes at 0.95e-3 U stick, at 1.05e-3 U they slip."""
    from hotroll.fem.quantities import sticking_zone

    U = 2.0
    ang = np.linspace(0.3, 0.0, 7)
    prof = {"x": -np.sin(ang), "y": 1 - np.cos(ang), "angle": ang,
            "v_slip": U * np.array([-0.1, -0.95e-3, 0.5e-3, 0.95e-3, 1.05e-3, 0.2, 0.3])}
    arc = np.hypot(np.diff(prof["x"]), np.diff(prof["y"]))
    assert sticking_zone(prof, U, 0.5 * arc[0]) == [pytest.approx(0.25), pytest.approx(0.15)]
    assert sticking_zone(prof, U, 3.0 * arc[0]) is None          # shorter than min_length
    prof["v_slip"][5] = 0.0                                       # one stuck node alone
    assert sticking_zone(prof, U, 0.5 * arc[0]) == [pytest.approx(0.25), pytest.approx(0.15)]


def test_slip_sign_changes_by_hand():
    """``Q.slip_sign_changes`` counts the sign changes of v_s between the zone's nodes (its
    ends included, exact zeros skipped): by hand 3 on the whole arc, 1 and 0 on parts."""
    from hotroll.fem.quantities import slip_sign_changes

    ang = np.linspace(0.6, 0.0, 7)                          # 0.6, 0.5, ..., 0.0 rad
    prof = {"angle": ang, "v_slip": np.array([-1e-8, 2e-8, 0.0, 3e-8, -1e-8, -2e-8, 5e-2])}
    assert slip_sign_changes(prof, [0.61, -0.01]) == 3
    assert slip_sign_changes(prof, [0.41, -0.01]) == 2          # 0 skipped: +, -, -, +
    assert slip_sign_changes(prof, [0.51, 0.29]) == 0          # +, 0, +
    assert slip_sign_changes(prof, [0.21, 0.05]) == 0
    assert slip_sign_changes(prof, [0.21, -0.01]) == 1


def test_flux_neutral_angle_by_hand():
    """y(phi) U cos(phi) = q solved for phi: back-substitution, and NaN outside the arc."""
    from hotroll.fem.quantities import flux_neutral_angle
    from hotroll.model.geometry import RollPass

    rp = RollPass(0.3, 0.01, 0.008, 2.0)
    phi = 0.02
    q = (rp.half_exit + rp.radius * (1 - math.cos(phi))) * rp.u_roll * math.cos(phi)
    assert flux_neutral_angle(rp, q) == pytest.approx(phi, rel=1e-10)
    assert math.isnan(flux_neutral_angle(rp, 0.5 * rp.u_roll * rp.half_exit))


# --- exact scalings outside the comfortable corner: the slow lab pass -------------------------
def test_slow_lab_pass_scales_exactly():
    """The slow lab pass (0.02 m/s, m = 0.05) with exact contact: omega x 100 (eps0 x 100, the
    law's own rate scale) leaves slip and angles as they were and scales every stress by
    100^m; K x 1000 scales the stresses only; roll_axis_x moved to 5 m changes nothing. An exact
    scaling of the equations (1e-9)."""
    base, _ = solve(LAB)
    fast, _ = solve(with_(LAB, **{"pass.roll_angular_velocity": 20.0, "material.eps0": 1e-2}))
    hard, _ = solve(with_(LAB, **{"material.K": 1e11}))
    moved, _ = solve(with_(LAB, **{"pass.roll_axis_x": 5.0}))
    m = LAB["material"]["m"]
    assert base["exit_code"] == 0, base["failure"]
    kinematic = ("forward_slip", "neutral_angle", "contact_start_angle", "contact_end_angle",
                 "mass_flux_error", "exit_thickness")
    stresses = ("roll_force", "roll_torque", "min_contact_pressure", "plastic_power")
    for s, factor in ((fast, 100.0**m), (hard, 1000.0), (moved, 1.0)):
        assert s["exit_code"] == 0 and s["nonlinear_iterations"] == base["nonlinear_iterations"]
        for key in kinematic:
            assert s[key] == pytest.approx(base[key], rel=1e-9, abs=1e-15), key
        for key in stresses:
            rate = 100.0 if (s is fast and key == "plastic_power") else 1.0  # power: x U too
            assert s[key] == pytest.approx(base[key] * factor * rate, rel=1e-9), key
    assert moved["neutral_point"][0] == pytest.approx(base["neutral_point"][0] + 4.0, abs=1e-12)


# --- the summary's contact figures against the files and the run ----------------------------
def test_contact_figures_are_the_written_ones(finishing_runs):
    """min_contact_pressure = - the largest normal stress of contact.csv; exit_thickness =
    2 x flux / exit velocity (the head face); neutral_angle_flux = y(phi) U cos(phi) = q solved
    with the summary's own flux (plumbing over the by-hand checks of the functions)."""
    from hotroll.fem.quantities import flux_neutral_angle
    from hotroll.model.geometry import RollPass

    for k, (s, prof) in finishing_runs.items():
        assert s["min_contact_pressure"] == pytest.approx(-np.max(prof["normal_stress"]),
                                                          rel=1e-12)
        assert s["exit_thickness"] == pytest.approx(
            2.0 * s["mass_flux_out"] / s["exit_velocity"], rel=1e-12)
        p = FINISHING["pass"]
        rp = RollPass(p["roll_radius"], p["entry_thickness"] / 2, p["exit_thickness"] / 2,
                      p["roll_angular_velocity"])
        assert s["neutral_angle_flux"] == pytest.approx(
            flux_neutral_angle(rp, s["mass_flux_in"]), rel=1e-12)


def test_pressure_last_update_is_the_last_newton_step(tmp_path, monkeypatch):
    """pressure_last_update (Pa) = the last Newton step's multiplier change x U x s x K of the
    run that wrote it (plumbing)."""
    import hotroll.solvers.steady as S

    runs, solve_ = [], S.SteadyRun.solve

    def keep(self, *args, **kw):
        runs.append(self)
        return solve_(self, *args, **kw)

    monkeypatch.setattr(S.SteadyRun, "solve", keep)
    s = run_case(case_from_dict(with_(example1_coarse("plu"), **{"material.K": 3e7})), tmp_path)
    r = runs[-1]
    expected = (r.result.stats[-1].multiplier_update * r.problem.rp.u_roll * r.form.lam_scale
                * r.problem.material.K)
    assert s["pressure_last_update"] == pytest.approx(expected, rel=1e-12)
    assert 0.0 <= s["pressure_last_update"]


# --- the steady solver's Solution (moved from the removed test_active_set.py) ---------------
@pytest.fixture(scope=shared_scope)
def steady_unilateral():
    from casebuild import steady_run

    run = steady_run(case_from_dict(example1_coarse("unilateral_run")))
    run.run()
    return run


def test_the_steady_solution_has_no_time_and_records_its_solves(steady_unilateral):
    """The steady solver's Solution: no time (NaN, not the report's scheme's seconds), one
    history row per solve with its Newton iterations and final residual (below the solver's
    tolerance for the last, converged one)."""
    run = steady_unilateral
    state, stats = run.state, run.last_stats
    assert math.isnan(state.time) and state.step == len(state.history) - 1
    last = state.history[-1]
    assert math.isnan(last["time"])
    assert last["iterations"] == stats.iterations and last["residual"] == stats.residual
    assert last["solver_converged"] and last["residual"] <= run.s.tol


def test_friction_acts_on_the_contact_only(steady_unilateral):
    """The friction indicator is 1 on the arc's edges (mapped onto [x_c, x_e]) and 0 on every
    other top edge: after the contact's end the top is free (no friction), and the arc's last
    vertex is the contact's end x_e."""
    run = steady_unilateral
    chi = run.form.chi.vec.FV().NumPy()[run.top.edge]
    assert np.array_equal(chi == 1.0, run.arc)
    x_e = run.shape.end(run.problem.rp)
    assert x_e < run.problem.rp.axis_x                 # this thick strip separates
    xy = run.top.vertex_positions(run.d, run.top.verts[run.top.vertex_contact])
    assert xy[:, 0].max() == pytest.approx(x_e, abs=1e-12)
