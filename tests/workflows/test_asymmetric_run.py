"""An asymmetric pass end to end (issue 52): the bundled asymmetric_plate (speed ratio 1.1)
through `hotroll run`, its summary (the per-roll `rolls`, the legacy one-roll keys as the two
rolls' means, the strip's curl and cross-shear zone), the refusals of what the full-thickness
strip does not carry yet, and a symmetric pass untouched by the asymmetric keys.

Labels: [plumb] the command line writes what it should; [id] identities between the summary
and the history rows it is made of (they catch a summary that swaps, scales or mixes up the
rolls, not a wrong solve: tests/solvers/test_full_strip.py checks the solve); [hand] numbers
the case gives."""
from __future__ import annotations

import csv
import json

import pytest
from typer.testing import CliRunner

from hotroll.cli import app
from hotroll.config.case import CaseError, load_case
from hotroll.examples import EXAMPLES, example_path
from hotroll.results.summary import ROLL_ENTRY, Summary
from hotroll.workflows.build import asymmetric_refusal, build_model

NAME = "asymmetric_plate"
GAP_KEYS = ("speed_ratio", "cross_shear_length", "exit_curvature", "exit_angle",
            "entry_guide_force_y", "vertical_balance_error")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """`hotroll run asymmetric_plate` (the bundled name; with its figures): exit code, output,
    summary.json and history.csv's last row."""
    out = tmp_path_factory.mktemp("asym") / "out"
    result = CliRunner().invoke(app, ["run", NAME, "--out", str(out)])
    summary = json.loads((out / "summary.json").read_text()) if (
        out / "summary.json").exists() else None
    with open(out / "history.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    last = {k: float(v) if v not in ("", "True", "False") else v for k, v in rows[-1].items()}
    return result, summary, last, out


def test_the_bundled_asymmetric_pass_is_listed_and_asymmetric():
    """[hand] registered as an example; the case's rolls: equal radii, the upper at 2 m/s and
    the lower at 2/1.1 m/s."""
    assert EXAMPLES[NAME] == [NAME]
    gap = load_case(example_path(NAME)).roll_gap()
    assert not gap.symmetric and gap.differences() == ["omega"]
    assert gap.upper.surface_speed == pytest.approx(2.0, rel=1e-12)
    assert gap.lower.surface_speed == pytest.approx(2.0 / 1.1, rel=1e-12)


def test_hotroll_run_exits_0_with_the_asymmetric_keys(run):
    """[plumb] exit 0, a typed summary with every asymmetric key and both rolls, their units
    in the summary's table; the console table shows both rolls; the two-roll figure."""
    result, summary, _, out = run
    assert result.exit_code == 0, result.output
    Summary.from_dict(summary)          # every key declared, every unconditional one there
    for key in ("rolls", *GAP_KEYS, "roll_force", "roll_torque", "roll_power"):
        assert summary[key] is not None, key
    assert [r["side"] for r in summary["rolls"]] == ["upper", "lower"]
    assert set(summary["rolls"][0]) == set(ROLL_ENTRY)
    units = summary["units"]
    assert units["exit_curvature"] == "1/m" and units["cross_shear_length"] == "m"
    assert units["rolls.roll_torque"] == "N m/m" and units["rolls.roll_power"] == "W/m"
    assert units["rolls.roll_force"] == "N/m" and units["rolls.neutral_angle"] == "rad"
    text = " ".join(result.output.split())
    assert "upper roll: roll_force" in text and "lower roll: roll_force" in text
    assert "roll_force (mean of the two rolls)" in text
    assert (out / "contact_lower.csv").exists() and (out / "fig_rolls.png").exists()


def test_the_rolls_entries_are_the_history_rows_figures(run):
    """[id] each roll's entry = its history column of the last (converged) row, the steady
    solver's window; radius and speed [hand] from the case; the strip's keys likewise."""
    _, summary, last, _ = run
    for entry in summary["rolls"]:
        side = entry["side"]
        for key in ROLL_ENTRY:
            if key in ("side", "radius", "surface_speed", "contact_end_kind", "roll_overlap",
                       "contact_end_pressure"):
                continue        # the case's, and the contact's (not history columns)
            assert entry[key] == pytest.approx(last[f"{side}_{key}"], rel=1e-12, abs=1e-12), \
                (side, key)
    upper, lower = summary["rolls"]
    assert upper["radius"] == lower["radius"] == 0.4
    assert (upper["surface_speed"], lower["surface_speed"]) == pytest.approx((2.0, 2.0 / 1.1))
    for key in GAP_KEYS[1:]:
        assert summary[key] == pytest.approx(last[key], rel=1e-12, abs=1e-15), key
    assert summary["speed_ratio"] == pytest.approx(1.1, rel=1e-12)


def test_the_legacy_keys_are_the_two_rolls_means(run):
    """[id] roll_force, roll_torque, roll_power, contact_length, forward_slip: the mean of
    the two rolls' (as their descriptions say); the force balance holds each roll's."""
    _, summary, _, _ = run
    upper, lower = summary["rolls"]
    for key in ("roll_force", "roll_torque", "roll_power", "contact_length", "forward_slip"):
        assert summary[key] == pytest.approx(0.5 * (upper[key] + lower[key]), rel=1e-12), key
    fb = summary["force_balance"]
    assert fb["upper_roll"][1] == -upper["roll_force"] and fb["lower_roll"][1] == \
        lower["roll_force"]


def test_the_pass_converged_and_balances(run):
    """[id] a converged solve's balances (vertical forces; the rolls' power against the
    dissipation) and the flux, and the faster roll supplies the more torque."""
    _, summary, _, _ = run
    assert summary["exit_code"] == 0 and summary["converged"]
    assert summary["vertical_balance_error"] < 1e-8
    assert summary["power_balance_error"] < 1e-2 and summary["mass_flux_error"] < 1e-2
    upper, lower = summary["rolls"]
    assert upper["roll_torque"] > lower["roll_torque"]


def test_the_contact_edges_are_each_rolls_contact(run):
    """[id] fields.npz's contact_edges (the figures' contact lines): one row (a, b) per
    contact edge, the upper roll's then the lower's, each edge's two vertices on one surface
    (y > 0 the upper's); on each side the edges' lengths on the deformed points add up to
    that roll's contact length in history.csv (the integral of its contact indicator: measured
    3.5e-7 and 5.2e-7, the chords against the curved edges)."""
    import numpy as np

    _, _, last, out = run
    fields = np.load(out / "fields.npz")
    edges, pts = fields["contact_edges"], fields["points"]
    assert edges.ndim == 2 and edges.shape[1] == 2 and len(edges) > 10
    ya, yb = pts[edges[:, 0], 1], pts[edges[:, 1], 1]
    assert np.all(ya * yb > 0.0)
    upper = ya > 0.0
    n_up = int(upper.sum())
    assert np.all(upper[:n_up]) and not np.any(upper[n_up:])
    length = np.linalg.norm(pts[edges[:, 0]] - pts[edges[:, 1]], axis=1)
    for name, side in (("upper", upper), ("lower", ~upper)):
        assert length[side].sum() == pytest.approx(last[f"{name}_contact_length"], rel=1e-5)


#: (overrides on asymmetric_plate, the key its refusal names)
REFUSED = [
    ({"solver.method": "transient", "contact.method": "penalty"}, "solver.method"),
    ({"plate.free_surface": "constrained"}, "plate.free_surface"),
    ({"contact.method": "penalty"}, "contact.method"),
    ({"pass.roll_gap": 0.018, "pass.mill_modulus": 5e9, "pass.width": 2.0}, "pass.roll_gap"),
    ({"friction": {"law": "viscoplastic", "a_f": "estimate"}}, "friction.a_f"),
    ({"friction": {"law": "viscoplastic", "a_f": 0.3, "lower": {"a_f": "estimate"}}},
     "friction.lower.a_f"),
]


@pytest.mark.parametrize("over,key", REFUSED, ids=[k for _, k in REFUSED])
def test_each_refusal_names_its_key_before_any_computation(over, key, monkeypatch):
    """The full strip's refusals, each a line starting with its key, from build_model before
    anything is built (the reference law, the first thing it computes, would fail the test)."""
    import hotroll.workflows.build as build

    case = load_case(example_path(NAME), over)
    refusal = asymmetric_refusal(case)
    assert refusal is not None and any(p.startswith(f"{key}: ") for p in refusal.problems), \
        refusal
    assert len(refusal.problems) == len(set(refusal.problems))     # each line once
    monkeypatch.setattr(build, "reference_material", lambda c: pytest.fail("computed"))
    with pytest.raises(CaseError, match=key.replace(".", r"\.")):
        build_model(case)


def test_a_viscoplastic_pass_with_a_given_a_f_per_roll_builds():
    """[plumb] a_f given per roll reaches the full strip's Problem.gap, each roll's own."""
    case = load_case(example_path(NAME), {"friction": {
        "law": "viscoplastic", "a_f": 0.3, "lower": {"a_f": 0.4}}})
    assert asymmetric_refusal(case) is None
    problem, _ = build_model(case)
    assert problem.gap.a_f == {1: 0.3, -1: 0.4}
    assert problem.gap.rolls[-1].u_roll == pytest.approx(2.0 / 1.1)


def test_a_symmetric_pass_has_no_asymmetric_keys(tmp_path):
    """[plumb] a symmetric pass takes the half model: none of the asymmetric keys, its
    roll_force the history row's own (not a mean of two) [id]."""
    out = tmp_path / "sym"
    case = load_case(example_path(NAME), {"pass.speed_ratio": None, "output.figures": False})
    assert case.roll_gap().symmetric and build_model(case)[0].gap is None
    from hotroll.workflows.runner import run_case

    summary = run_case(case, out)
    assert not any(k in summary for k in ("rolls", *GAP_KEYS))
    assert not (out / "contact_lower.csv").exists()
    with open(out / "history.csv", newline="") as fh:
        last = list(csv.DictReader(fh))[-1]
    assert summary["roll_force"] == pytest.approx(float(last["roll_force"]), rel=1e-12)


def test_the_report_page_shows_both_rolls(run):
    """[plumb] `hotroll report`: a group per roll (its figures with their units) and the
    two-roll figure."""
    _, summary, _, out = run
    result = CliRunner().invoke(app, ["report", str(out)])
    assert result.exit_code == 0, result.output
    page = (out / "report.html").read_text()
    assert 'data-key="rolls.lower.roll_torque"' in page and "<h3>Upper roll</h3>" in page
    assert "Both rolls&#39; contact pressure and shear" in page


def test_the_figures_draw_both_rolls_where_they_are(run):
    """RunFiles.rolls (the figures' rolls): the upper at the summary's roll centre, the lower
    below the exit mid-plane by h1/2 + its radius, so that both arcs touch the strip's exit
    surfaces at the gap (hand geometry: y = +-h1/2 at x = the axis, h1 the exit thickness)."""
    from hotroll.results.figures.run_files import RunFiles

    _, summary, _, out = run
    rolls = RunFiles(out).rolls()
    assert [side for _, _, side in rolls] == [1, -1]
    h1 = 0.02                                     # asymmetric_plate's exit thickness, m
    (xu, yu), Ru, _ = rolls[0]
    (xl, yl), Rl, _ = rolls[1]
    assert xl == pytest.approx(xu)
    assert yu - Ru == pytest.approx(0.5 * h1, rel=1e-9)
    assert yl + Rl == pytest.approx(-0.5 * h1, rel=1e-9)
    assert Rl == pytest.approx(summary["rolls"][1]["radius"])


def test_the_bundled_reground_roll_pass_is_two_radii_on_one_drive():
    """asymmetric_radii: the lower roll 360 mm against 400 mm, both at 5 rad/s (no speed
    ratio: each roll its own angular velocity), so the lower surface runs at 1.8 m/s against
    2.0 (hand: omega R), the speed ratio is 10/9, and the pass line sits where both bite at the
    same x: dh (R2 - R1) / (2 (R1 + R2 - dh)) = -0.1316 mm (hand, dh = 5 mm), below the exit
    mid-plane because the upper roll is the larger."""
    from hotroll.config.case import load_case
    from hotroll.examples import example_path

    gap = load_case(example_path("asymmetric_radii")).roll_gap()
    assert not gap.symmetric
    assert gap.upper.surface_speed == pytest.approx(2.0, rel=1e-12)
    assert gap.lower.surface_speed == pytest.approx(1.8, rel=1e-12)
    assert gap.speed_ratio == pytest.approx(10.0 / 9.0, rel=1e-12)
    dh, R1, R2 = 0.005, 0.4, 0.36
    assert gap.pass_line == pytest.approx(dh * (R2 - R1) / (2 * (R1 + R2 - dh)), rel=1e-12)
    assert gap.arc(1).x_touch == pytest.approx(gap.arc(-1).x_touch, abs=1e-12)


def test_one_flattening_roll_has_its_figures_in_its_entry(tmp_path):
    """[plumb] [roll.lower] model = "hitchcock" (the upper rigid), on a coarse mesh: the
    model reaches the full strip (GapRolls.roll_models), the lower roll's `rolls` entry
    carries its flattening figures with their units, the upper's none; [hand] its equivalent
    radius is Hitchcock's R (1 + C F'/dh) of its own force (C = 16 (1 - nu^2)/(pi E), dh 5 mm):
    exactly of the force of its last update (5e-14), which the reported force, the converged
    flow's, follows to the fixed point's tolerance (measured 3.7e-6 at 1x, 4.0e-5 at 16x;
    asserted 1e-4), of which R' carries the share C F'/(dh + C F') = 3.4 %."""
    import math

    from hotroll.workflows.runner import run_case

    case = load_case(example_path(NAME), {"roll.lower": {"model": "hitchcock"},
                                          "mesh.h_contact": 0.0025, "output.figures": False})
    problem, _ = build_model(case)
    assert set(problem.gap.roll_models) == {-1} and problem.roll is None
    s = run_case(case, tmp_path / "out")
    assert s["exit_code"] == 0
    upper, lower = s["rolls"]
    assert "roll_model" not in upper and lower["roll_model"] == "hitchcock"
    assert lower["roll_updates"] >= 1 and lower["roll_flattening"] > 0.0
    C = 16.0 * (1.0 - 0.3**2) / (math.pi * 2.1e11)
    share = C * lower["roll_force"] / (0.005 + C * lower["roll_force"])
    assert lower["roll_equivalent_radius"] == pytest.approx(
        0.4 * (1.0 + C * lower["roll_force"] / 0.005), rel=1e-4 * share)
    assert s["units"]["rolls.roll_flattening"] == "m"
    assert s["units"]["rolls.roll_equivalent_radius"] == "m"


def test_the_strip_curls_onto_the_slower_roll_and_stays_outside_both(run):
    """[hand] the strip curls towards the slower (lower) roll and presses on it past its gap
    (contact_end_kind "wrap", its end after the roll axes at x = 1 m, the pressure there ~0),
    and its free surfaces lie outside both rolls (roll_overlap within 0.02 elements, the
    limit of results/outcome.py: the bundled pass at 1.15 before issue 52's session 3 lay
    0.26 mm inside its slower roll with exit code 0)."""
    _, summary, _, _ = run
    upper, lower = summary["rolls"]
    assert summary["exit_curvature"] < 0.0          # towards the lower roll
    assert lower["contact_end_kind"] == "wrap" and lower["contact_end"] > 1.0
    assert upper["contact_end_kind"] == "separation" and upper["contact_end"] < 1.0
    h = summary["h_contact"]
    assert 0.0 <= summary["roll_overlap"] <= 0.02 * h
    assert max(upper["roll_overlap"], lower["roll_overlap"]) == summary["roll_overlap"]
    assert summary["contact_unresolved"] is False
