"""``hotroll validate FILE``: a case, schedule or study file checked before anything runs, its
kind told from its keys (registered on the app in ``cli/__init__.py``)."""

import tomllib
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.text import Text

from hotroll.cli.common import (
    Column,
    ResultTable,
    console,
    err_console,
    fail,
    find_file,
    print_table,
)
from hotroll.config.case import CaseError, load_case
from hotroll.config.schedule import Schedule, load_schedule
from hotroll.config.study import expand, key_unit, load_study

#: The keys that tell a study and a schedule from a case (a case's [pass] is one table).
STUDY_KEYS = ("base", "vary", "cases", "cases_file")
SCHEDULE_KEYS = ("strip", "mill")


def file_kind(data: dict) -> str:
    """"study" (a [base], [vary], [[cases]] or cases_file), "schedule" (a [[pass]] list, a
    [strip] or [mill]) or "case" (anything else: the case schema names what is wrong)."""
    if any(k in data for k in STUDY_KEYS):
        return "study"
    if isinstance(data.get("pass"), list) or any(k in data for k in SCHEDULE_KEYS):
        return "schedule"
    return "case"


def validate(
    file: Annotated[Path, typer.Argument(
        metavar="FILE", show_default=False,
        help="A case, schedule or study file (TOML), or a bundled one's name. The kind is told "
             "from the keys: a [base], [vary] or [[cases]] is a study; a [[pass]] list, a "
             "[strip] or a [mill] a schedule; anything else a case.")],
) -> None:
    """Check a case, schedule or study file before anything runs: every key against its
    schema (type, unit, allowed range) and the rules between the keys.

    A case is printed resolved as TOML (the defaults filled in; the derived figures with
    their units in a comment line, then each plausibility warning a run would report in a
    comment line of its own); a schedule's passes and a study's combinations are listed. Exit
    code 0 when valid, 2 when not, each problem named by its field."""
    path = find_file(file, "validate", ("case", "schedule", "study"))
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise fail(str(CaseError(f"cannot read the file: {e.strerror or e}", str(path),
                                 "file"))) from None
    except tomllib.TOMLDecodeError as e:
        raise fail(str(CaseError(f"TOML syntax error: {e}", str(path), "TOML file"))) from None
    kind = file_kind(data)
    try:
        {"case": _case, "schedule": _schedule, "study": _study}[kind](path)
    except CaseError as e:
        raise fail(f"{path}: read as a {kind} file (from its keys)\n{e}") from None


def _case(path: Path) -> None:
    case = load_case(path)
    p = case.pass_
    typer.echo(f"# {path}: a valid case file: every key checked against the case schema "
               f"(type, unit, allowed range) and the rules between the keys; resolved below "
               f"with the defaults")
    typer.echo(case.to_toml())
    typer.echo(f"# derived: contact_length = {p.contact_length:.6g} m, bite_angle = "
               f"{p.bite_angle:.6g} rad, roll_surface_speed = {p.roll_surface_speed:.6g} m/s, "
               f"h_contact = {case.mesh.h:g} m, dt = {case.dt:.6g} s")
    gap = case.roll_gap()
    if not gap.symmetric:
        rolls = "; ".join(f"{name}: R = {1e3 * r.radius:g} mm, omega = {r.omega:.6g} rad/s, "
                          f"U = {r.surface_speed:.6g} m/s, {r.model}"
                          for name, r in (("upper", gap.upper), ("lower", gap.lower)))
        dh1, dh2 = gap.draft_split()
        typer.echo(f"# roll gap: asymmetric (the rolls differ in {', '.join(gap.differences())}"
                   f"); {rolls}; speed ratio {gap.speed_ratio:.6g}; R_e = "
                   f"{1e3 * gap.equivalent_radius:.6g} mm; pass line {1e3 * gap.pass_line:.6g} "
                   f"mm, draft shares {1e3 * dh1:.6g} / {1e3 * dh2:.6g} mm; the derived values "
                   f"above are the upper roll's; a run solves the full-thickness strip between the "
                   f"two rolls")
    # what a run would report and go on with (config/plausibility.py), as TOML comments
    for text in case.warnings():
        typer.echo("# warning: " + str(text).replace("\n", "\n# "))


def _schedule(path: Path) -> None:
    sch = load_schedule(path)
    console.print(Text(f"{path}: a valid schedule, {sch.name!r}, {len(sch.passes)} passes",
                       style="bold"), soft_wrap=True)
    console.print(Text(
        "checked: every key against the schedule schema (type, unit, allowed range), the rules "
        "between the passes (each exit below its entry, the roll speeds, the transports) and "
        "each pass as a case entering with the strip's state"), soft_wrap=True)
    print_table(_passes(sch).rich(), console)
    s = sch.strip
    console.print(Text(
        f"entry strip: {1e3 * s.thickness:g} mm at {s.temperature:g} K"
        + (f", {s.width:g} m wide" if s.width else ", per unit width")
        + f"; roll speeds: {sch.mill.speeds}; tensions: {sch.mill.tensions}"), soft_wrap=True)


def _passes(sch: Schedule) -> ResultTable:
    """The schedule's passes as given: radius, exit (or gap), speed, tensions, transport."""
    table = ResultTable(f"{sch.name}: passes", [
        Column("pass", left=True), Column("R", "mm", ".1f"), Column("exit h", "mm", ".2f"),
        Column("gap S", "mm", ".2f"), Column("U", "m/s", ".3g"), Column("omega", "rad/s", ".4g"),
        Column("t back", "MPa", ".3g"), Column("t front", "MPa", ".3g"),
        Column("transport", left=True)])

    def mm(x: float | None) -> float | None:
        return None if x is None else 1e3 * x

    for k, p in enumerate(sch.passes):
        t = p.transport
        moved = None if t is None else (f"{t.duration:g} s" if t.duration is not None
                                         else f"{t.distance:g} m")
        table.rows.append([sch.pass_name(k), 1e3 * p.roll_radius, mm(p.exit_thickness),
                           mm(p.roll_gap), p.roll_surface_speed, p.roll_angular_velocity,
                           1e-6 * p.back_tension, 1e-6 * p.front_tension, moved])
    return table


def _study(path: Path) -> None:
    st, base = load_study(path)
    combos = expand(st, base)
    b = st.base
    source = (f"the case file {b.file}" if b.file is not None else
              f"the bundled case {b.example}" if b.example is not None else
              f"the schedule {b.schedule}")
    console.print(Text(f"{path}: a valid study, {st.name!r}, {len(combos)} combinations",
                       style="bold"), soft_wrap=True)
    console.print(Text(
        f"checked: the study's keys (base, vary, cases, run, plot), its base ({source}"
        + (f" with {_pairs(b.set)}" if b.set else "") + ") and each combination as a "
        + ("schedule" if b.schedule is not None else "case")), soft_wrap=True)
    for key, values in st.vary.items():
        unit = key_unit(key)
        console.print(Text(f"varied: {key} [{unit}]: {', '.join(map(_short, values))}"),
                      soft_wrap=True)
    keys = sorted({k for row in st.cases for k in row})
    if keys:
        console.print(Text(f"[[cases]]: {len(st.cases)} rows of {', '.join(keys)}"),
                      soft_wrap=True)
    bad = [c for c in combos if c.case is None]
    for c in bad:
        err_console.print(Text(f"{c.label}: refused, would be a bad_input row of the study: "
                               f"{c.problem}", style="yellow"), soft_wrap=True)
    console.print(Text(f"{len(combos) - len(bad)} of {len(combos)} combinations valid"
                       + (f"; {len(bad)} refused (the study runs the others)" if bad else "")),
                  soft_wrap=True)


def _short(v: Any) -> str:
    return f"{v:.6g}" if isinstance(v, float) else str(v)


def _pairs(d: dict) -> str:
    return ", ".join(f"{k} = {_short(v)}" for k, v in d.items())
