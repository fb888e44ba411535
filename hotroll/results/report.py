"""``hotroll report DIR``: one self-contained HTML page of a finished run, comparison, study or
schedule (issue 18): inputs, results with their units, figures, warnings.

The page is made from the files the commands wrote (no solver, no case schema): a run's
``summary.json`` and ``case.toml`` (``report_run.py``), a study's ``study.csv`` and a schedule's
``schedule.json`` (``report_table.py``). Figures are embedded as data URIs and the style is
inline: the file opens anywhere, offline, without scripts or other files.
"""
from __future__ import annotations

import base64
import datetime
import tempfile
from pathlib import Path

from hotroll import __version__
from hotroll.files import DiskFullError, atomic
from hotroll.results.figures import FIGURES, RunFiles
from hotroll.results.report_run import FIGURE_CAPTIONS, run_context
from hotroll.results.report_table import schedule_context, study_context

EXPECTED = ("summary.json (hotroll run, hotroll example), compare.json with fe/ (hotroll compare), "
            "study.csv (hotroll study) or schedule.json (hotroll schedule)")


class ReportError(ValueError):
    """The directory is not one the report can be made of (names it and what is expected)."""


def kind(d: Path) -> str:
    """"run", "study" or "schedule": what the output directory ``d`` holds."""
    d = Path(d)
    if not d.is_dir():
        raise ReportError(f"report: {d} is not a directory; expected a hotroll output "
                          f"directory with {EXPECTED}")
    if (d / "study.csv").is_file():
        return "study"
    if (d / "schedule.json").is_file():
        return "schedule"
    if (d / "summary.json").is_file() or ((d / "compare.json").is_file()
                                          and (d / "fe" / "summary.json").is_file()):
        return "run"
    runs = sorted(p.parent.name for p in d.glob("*/summary.json"))
    hint = (f"; it holds runs ({', '.join(runs[:4])}{', ...' if len(runs) > 4 else ''}): "
            f"report each of them" if runs else "")
    raise ReportError(f"report: {d} is not a hotroll output directory: expected {EXPECTED}"
                      + hint)


def context(d: Path, title: str | None = None, draw: bool = True) -> dict:
    """The page's content (``templates/report.html.j2``); ``draw``: draw a run's contact and
    flow-stress figures when the run wrote none."""
    d = Path(d)
    k = kind(d)
    if k == "study":
        ctx = study_context(d, title)
        own = [(cap, d / name) for name, cap in (
            ("study.png", "The study's plot ([plot] of the study file)"),
            ("study_profiles.png", "Contact profiles of the cases")) if (d / name).is_file()]
        ctx["figures"] = own + ([("Roll force, torque and forward slip against "
                                  f"{ctx['figure_x']}", ctx["figure_png"])]
                                if ctx.get("figure_png") else [])
    elif k == "schedule":
        ctx = schedule_context(d, title)
    else:
        ctx = run_context(d)
        if title:
            ctx["title"] = title
        if draw and not any(p.name.startswith("fig_") for _, p in ctx["figures"]):
            names = ("fig_sigma_ef.png",) if ctx["compare"] else (
                "fig_contact_angle.png", "fig_sigma_ef.png")   # compare.png has the contact
            ctx["figures"] = _drawn(ctx["run_dir"], names) + ctx["figures"]

    ctx.update(directory=str(d.resolve()), version=__version__,
               made=datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
               figures=[(cap, _data_uri(fig)) for cap, fig in ctx.get("figures", [])])
    return ctx


def _drawn(run_dir: Path, names: tuple[str, ...]) -> list[tuple[str, bytes]]:
    """The figures ``names`` of ``results/figures/`` drawn from the run's files."""
    draw = dict(FIGURES)
    run, out = RunFiles(run_dir), []
    with tempfile.TemporaryDirectory(prefix="hotroll-report-") as tmp:
        for name in names:
            try:
                path = draw[name](run, Path(tmp) / name)
            except Exception:  # noqa: BLE001 - a figure the files do not allow is left out
                path = None
            if path is not None and Path(path).is_file():
                out.append((FIGURE_CAPTIONS[name] + " (drawn for this report)",
                            Path(path).read_bytes()))
    return out


def _data_uri(fig: Path | bytes) -> str:
    data = fig if isinstance(fig, bytes) else Path(fig).read_bytes()
    return "data:image/png;base64," + base64.b64encode(data).decode("ascii")


def _unit(text) -> str:
    """A unit for HTML: m^2/s as m<sup>2</sup>/s, "-" as a dash (dimensionless)."""
    from markupsafe import Markup, escape

    text = str(text or "")
    if text in ("-", ""):
        return Markup('<span class="dimless" title="dimensionless">&ndash;</span>') if text \
            else Markup("")
    parts = str(escape(text)).split("^")
    out = parts[0]
    for p in parts[1:]:
        exp = p.split("/", 1)[0].split(" ", 1)[0]
        out += f"<sup>{exp}</sup>{p[len(exp):]}"
    return Markup(out)


def render(ctx: dict) -> str:
    import jinja2

    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(Path(__file__).with_name("templates")),
        autoescape=True, undefined=jinja2.StrictUndefined, trim_blocks=True, lstrip_blocks=True)
    env.filters["unit"] = _unit
    return env.get_template("report.html.j2").render(**ctx)


def write_report(d: Path, title: str | None = None, *, runs: bool = True,
                 draw: bool = True) -> Path:
    """Write ``d/report.html`` (atomically) and return its path. ``runs``: for a study or a
    schedule, first each run's own page (linked from the table; figures not drawn)."""
    d = Path(d)
    k = kind(d)
    if runs and k in ("study", "schedule"):
        subs = d.glob("*/summary.json") if k == "schedule" else [
            *(d / "cases").glob("*/summary.json"), *(d / "cases").glob("*/schedule.json")]
        for s in sorted(subs):
            try:                        # a schedule study's case: its schedule's page
                write_report(s.parent, runs=s.name == "schedule.json", draw=False)
            except DiskFullError:
                raise
            except (OSError, ValueError):   # a run that cannot be shown has no link
                pass
    html = render(context(d, title, draw=draw))
    path = d / "report.html"
    with atomic(path) as tmp:          # whole or not at all; a full disk named (files.py)
        tmp.write_text(html, encoding="utf-8")
    return path
