"""One neutral point (issue 51, item 4): every place that shows a neutral point (the summary,
the figures, the history, the HTML page, the command line's table) tells the summary's one
story: a point at its angle, or "none: sticking zone from ... to ...". The figures are read
back from what their code draws (the lines and spans of the matplotlib axes, captured before
they are saved), the page from its HTML text, the command line from the summary values it
prints. Two coarse Example 1 passes: a_f from (3.15), the report's case, whose whole arc sticks
(no neutral point), and a_f = 5, a clean sign change inside a sticking stretch (a point). Also:
a steady solve reports Newton solves and coupling updates, not time steps; the figures draw the
contact pressure positive; an isothermal K = 1 case shows no plate temperature."""
from __future__ import annotations

import html
import math
import re
from pathlib import Path

import numpy as np
import pytest
from casebuild import build_case, example1_coarse, shared_scope

#: Example 1 as the report runs it (a 4 m plate, a_f from (3.15)) on the coarse mesh
STICKING = example1_coarse("example1", plate={"length": 4.0},
                           friction={"law": "viscoplastic", "a_f": "estimate"})


@pytest.fixture(scope=shared_scope)
def sticking(tmp_path_factory):
    """Example 1 with (3.15) solved once, its progress reports kept."""
    from hotroll.workflows.runner import run_case

    out = tmp_path_factory.mktemp("neutral") / "example1"
    events: list[dict] = []
    run_case(build_case(STICKING), out, progress=events.append)
    return out, events


@pytest.fixture(params=["sticking", "point"])
def case(request, sticking, solved_example1):
    """(kind, run directory): the sticking arc, or the point (conftest's EXAMPLE1_COARSE)."""
    return request.param, (sticking[0] if request.param == "sticking" else solved_example1)


def _summary(d: Path) -> dict:
    from hotroll.results.run_dir import RunDir

    return dict(RunDir(d).summary())


def _story(s: dict, kind: str) -> None:
    """The summary's own story, checked against its numbers with this test's formats."""
    if kind == "sticking":
        a, b = s["sticking_zone"]
        assert s["neutral_angle"] is None and s["neutral_point"] is None
        assert s["neutral"] == (f"none: sticking zone from {math.degrees(a):.4g}° to "
                                f"{math.degrees(b):.4g}° ({a:.4g} to {b:.4g} rad)")
    else:
        ang, (cx, cy), R = s["neutral_angle"], s["roll_centre"], s["roll_radius"]
        assert 0.0 < ang < s["contact_start_angle"]
        assert s["neutral"].startswith(f"{math.degrees(ang):.4g}° ({ang:.4g} rad)")
        assert s["neutral_point"] == pytest.approx([cx - R * math.sin(ang),
                                                    cy - R * math.cos(ang)], abs=1e-12)


def test_the_summary_decides_once(case):
    """The summary's story: Example 1 with (3.15) sticks over the whole arc (no point, the
    zone from the contact's start to its end); a_f = 5 has its point inside a sticking stretch.
    The zone's x positions are the contact profile's at its angles."""
    import csv

    kind, d = case
    s = _summary(d)
    _story(s, kind)
    with open(d / "contact.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    at = {float(r["angle"]): float(r["x"]) for r in rows}
    assert s["sticking_zone_x"] == pytest.approx([at[a] for a in s["sticking_zone"]], abs=1e-12)
    if kind == "sticking":       # the whole arc: the story is not the contact's entry's
        assert s["sticking_zone"] == pytest.approx([s["contact_start_angle"],
                                                    s["contact_end_angle"]], abs=1e-12)


def _drawn(monkeypatch, figure, run):
    """The matplotlib figure ``figure(run, path)`` draws, kept open instead of saved."""
    import matplotlib.pyplot as plt

    from hotroll.results.figures import history, profiles, slab

    kept = []

    def keep(fig, path):
        kept.append(fig)
        return path

    for mod in (profiles, history, slab):
        monkeypatch.setattr(mod, "save_figure", keep)
    figure(run, Path("unused.png"))
    (fig,) = kept
    plt.close(fig)
    return fig


def _neutral_artists(ax):
    """(lines, spans) of an axis labelled as the neutral story: vertical lines as their x,
    spans as (x from, x to), each with its label."""
    lines = [(float(ln.get_xdata()[0]), ln.get_label()) for ln in ax.get_lines()
             if "neutral point" in ln.get_label() and len(set(ln.get_xdata())) == 1]
    spans = [((p.get_x(), p.get_x() + p.get_width()), p.get_label()) for p in ax.patches
             if "neutral point" in str(p.get_label())]
    return lines, spans


@pytest.mark.parametrize("name", ["fig_contact", "fig_top", "fig_contact_angle"])
def test_the_figures_draw_the_summary_story(case, name, monkeypatch):
    """fig_contact (every panel), fig_top (both) and fig_contact_angle (both) draw the
    summary's neutral point at its x (its angle in degrees) with the story as the label, or,
    where there is none, the sticking zone's span and no neutral line anywhere (the line at the
    contact's entry of the old fallback, a sign change of the figure's own)."""
    from hotroll.results import figures
    from hotroll.results.figures import RunFiles

    kind, d = case
    s = _summary(d)
    fig = _drawn(monkeypatch, getattr(figures.profiles, name), RunFiles(d))
    axes = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    assert len(axes) == {"fig_contact": 4, "fig_top": 2, "fig_contact_angle": 2}[name]
    angle = name == "fig_contact_angle"
    for ax in axes:
        lines, spans = _neutral_artists(ax)
        if kind == "point":
            assert not spans and len(lines) == 1, (name, lines, spans)
            x, label = lines[0]
            want = math.degrees(s["neutral_angle"]) if angle else s["neutral_point"][0]
            assert x == pytest.approx(want, rel=1e-12)
        else:
            assert not lines and len(spans) == 1, (name, lines, spans)
            (lo, hi), label = spans[0]
            zone = np.degrees(s["sticking_zone"]) if angle else s["sticking_zone_x"]
            assert (lo, hi) == pytest.approx(sorted(zone), rel=1e-12)
        assert label.endswith(f"neutral point: {s['neutral']}")


def test_the_history_tells_the_summary_story(case, monkeypatch):
    """The history's neutral panel: the summary's story as its title; each row's angle and
    the summary's (in degrees) where it has a point, no angle at all where it has none (the
    rows' splits of the slip's signs settled at 0.050 rad on a sticking arc: noise)."""
    from hotroll.results.figures import RunFiles
    from hotroll.results.figures.history import fig_history, neutral_history

    kind, d = case
    s = _summary(d)
    run = RunFiles(d)
    title, rows, final = neutral_history(run)
    assert title == f"neutral point: {s['neutral']}"
    fig = _drawn(monkeypatch, fig_history, run)
    (ax,) = [ax for ax in fig.axes if ax.get_title() == title]
    if kind == "sticking":
        assert rows is None and final is None and not ax.get_lines()
    else:
        assert final == pytest.approx(math.degrees(s["neutral_angle"]), rel=1e-12)
        # the steady solver's last row is its solution: the summary's angle
        assert rows[-1] == pytest.approx(final, rel=1e-12)
        drawn = [ln for ln in ax.get_lines() if ln.get_label() == "the summary's"]
        assert len(drawn) == 1 and drawn[0].get_ydata()[0] == pytest.approx(final, rel=1e-12)


def test_the_figures_draw_the_contact_pressure_positive(case, monkeypatch):
    """fig_contact and fig_contact_angle both draw p = -T_n.n (compressive positive), in the
    same unit (a K = 1 case's stresses of about 1 Pa in Pa, not 1e-6 MPa)."""
    from hotroll.results.figures import RunFiles
    from hotroll.results.figures.profiles import fig_contact, fig_contact_angle

    _, d = case
    run = RunFiles(d)
    p = -np.asarray(run.contact["normal_stress"])
    assert np.median(p) > 0
    top = _drawn(monkeypatch, fig_contact, run).axes[1]
    arc = _drawn(monkeypatch, fig_contact_angle, run).axes[0]
    for ax in (top, arc):
        assert "[Pa]" in ax.get_ylabel() and "pressure" in ax.get_ylabel().lower() + (
            ax.get_title().lower())
        ys = [np.asarray(ln.get_ydata(), float) for ln in ax.get_lines()
              if len(ln.get_ydata()) == len(p)]
        assert any(np.allclose(y, p, rtol=1e-12) for y in ys), ax.get_ylabel()


def _page(d: Path) -> tuple[dict, str]:
    from hotroll.results.report import context, render

    ctx = context(d, draw=False)
    return ctx, html.unescape(" ".join(render(ctx).split()))


def test_the_page_tells_the_summary_story(case):
    """The HTML page: the neutral point's key figure (the angle in degrees, or "none" and the
    zone) beside the contact length's, the story's words on the page, the summary table's
    neutral rows only where there is a point; the flux angle labelled as what it is, not as a
    neutral angle; no plate temperature on an isothermal K = 1 case."""
    kind, d = case
    s = _summary(d)
    ctx, text = _page(d)
    cards = {c["key"]: c for c in ctx["headline"]}
    assert "contact_length" in cards and "neutral" in cards
    card = cards["neutral"]
    assert card["label"] == "neutral point"
    assert s["neutral"] in text
    rows = set(re.findall(r'data-key="(\w+)"', text))
    if kind == "sticking":
        assert card["text"] == "none" and f"none: {card['si']}" == s["neutral"]
        assert not {"neutral_angle", "neutral_point"} & rows
        assert f"neutral point: {s['neutral']}" in text     # the note beside the warnings
    else:
        assert float(card["text"]) == pytest.approx(math.degrees(s["neutral_angle"]), rel=6e-4)
        assert card["unit"] == "°" and card["si"] == s["neutral"]
        assert {"neutral_angle", "neutral_point"} <= rows
    assert "neutral angle (flux)" not in text
    flux = [r for _, group in ctx["groups"] for r in group if r["key"] == "neutral_angle_flux"]
    assert flux and "neutral" not in flux[0]["label"] and "mean speed" in flux[0]["label"]
    # the case's inputs list the plate temperature it was given; the results do not
    assert s["temperature"] is None and "temperature" not in rows


def test_the_command_line_table_tells_the_summary_story(case):
    """The summary values the command line's table prints (``cli/passes.py: SUMMARY_KEYS``)
    that are about the neutral point agree with the story; ``neutral`` is the one to print."""
    from hotroll.cli.passes import SUMMARY_KEYS

    kind, d = case
    s = _summary(d)
    shown = {k: s[k] for k in SUMMARY_KEYS if "neutral" in k or "sticking" in k}
    assert shown, SUMMARY_KEYS
    if kind == "sticking":
        assert shown.get("neutral_angle") is None and shown.get("neutral_point") is None
        if "neutral_angle_reason" in shown:
            assert "no point is neutral" in shown["neutral_angle_reason"]
    else:
        assert shown.get("neutral_angle", s["neutral_angle"]) == s["neutral_angle"]
        assert shown.get("neutral_angle_reason") is None
    assert "neutral" in shown and not {"neutral_angle", "neutral_point", "neutral_angle_reason",
                                       "sticking_zone"} & set(SUMMARY_KEYS), SUMMARY_KEYS
    assert shown["neutral"] == s["neutral"]


def test_a_steady_solve_reports_newton_solves_and_coupling_updates(sticking):
    """The steady solve's progress: one report per Newton solve (its iterations, residual and
    last update) and per coupling update (the Newton update it came at, each coupling's change
    in its tolerances), each in words; no time step (no ``step``, no ``time`` of NaN)."""
    d, events = sticking
    s = _summary(d)
    assert events and all("step" not in e and "time" not in e for e in events)
    newton = [e for e in events if e["stage"] == "newton"]
    coupling = [e for e in events if e["stage"] == "coupling"]
    assert len(newton) + len(coupling) == len(events)
    assert len(newton) == s["newton_solves"]
    assert sum(e["newton_iterations"] for e in newton) == s["nonlinear_iterations"]
    assert [e["coupling_update"] for e in coupling] == list(range(1, len(coupling) + 1))
    assert len(coupling) >= s["coupling_updates"] > 0
    last = newton[-1]
    assert last["newton_converged"] and last["newton_residual"] < 1e-6
    assert re.match(rf"Newton solve {len(newton)} at m = 0\.2: converged after "
                    rf"{last['newton_iterations']} iterations, residual norm ", last["message"])
    assert f"roll force {s['roll_force']:.6g} N/m" in last["message"]
    assert coupling[-1]["coupling_settled"] and "a_f " in coupling[-1]["message"]
    assert all(e["message"].startswith(f"coupling update {e['coupling_update']} at a Newton "
                                       "update of ") for e in coupling)


def test_the_plate_temperature_only_where_something_depends_on_it():
    """Norton-Hoff's K and m do not depend on the temperature: an isothermal case has none to
    show; Hensel-Spittel's do, and a [thermal] section makes any case depend on it."""
    from hotroll.results.run_summary import uses_temperature

    assert not uses_temperature(build_case(STICKING))
    assert uses_temperature(build_case(STICKING, "material", {"law": "hensel-spittel",
                                                             "grade": "C45"}))
    thermal = build_case(STICKING, "thermal", {
        "roll_temperature": 373.15, "htc_contact": 2e4, "htc_air": 10.0, "emissivity": 0.8},
        **{"material.density": 7800.0, "material.specific_heat": 650.0,
           "material.conductivity": 30.0})
    assert uses_temperature(thermal) and thermal.material.law == "norton-hoff"
