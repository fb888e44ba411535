"""The command line's batch commands (``hotroll schedule``, ``hotroll study``), registered on
``cli.app`` when ``cli`` imports this module."""

import time
from pathlib import Path
from typing import Annotated, Optional

import typer
from rich.text import Text

from hotroll.cli.common import (
    Column,
    Format,
    FormatOpt,
    OutOpt,
    Printer,
    ResultTable,
    ResumeOpt,
    RunClock,
    bundled_names,
    console,
    err_console,
    eta_text,
    fail,
    find_file,
    print_warnings,
    run_warnings,
)
from hotroll.config.case import CaseError
from hotroll.config.schedule import load_schedule
from hotroll.config.study import load_study, parse_value
from hotroll.workflows.schedule import ScheduleError, run_schedule
from hotroll.workflows.study import FAILED, run_study
from hotroll.workflows.tandem import TensionError


def study_report(out: Path, title: str) -> None:
    """``cli.report.study_report``, imported when a study ends (the report: matplotlib, jinja2)."""
    from hotroll.cli.report import study_report as report

    report(out, title)


class _PassClock:
    """The schedule's progress lines, each finished pass's with the time left of this roll
    through the mill, estimated from the measured wall time of the passes so far. A pass's line
    starts with its name (a second line with the same name, a warning, is not a pass);
    ``tensions ...`` lines (``mill.tensions = "from_speeds"``) come between whole rolls, some
    of them not printed, whose count is not known in advance."""

    def __init__(self, names: list[str], clock=None):
        self.names, self.clock = names, clock or time.monotonic
        self.last, self.k, self.tensions = self.clock(), -1, False
        self.passes = RunClock(len(names))

    def __call__(self, line: str) -> None:
        now = self.clock()
        head = line.split(":", 1)[0]
        text = "  " + line
        if line.startswith("tensions "):
            self.tensions, self.k = True, -1
        elif self.k >= 0 and head == self.names[self.k]:
            pass                        # a further line of the same pass (a warning)
        elif head in self.names:
            k = 0 if head == self.names[0] else self.k + 1
            if k == self.k + 1 and (k > 0 or not self.passes.seconds):   # measured alone
                self.passes.done(now - self.last)
            self.k = k
            left = self.passes.left(len(self.names) - k - 1)
            if k < len(self.names) - 1 and left is not None:
                n = len(self.passes.seconds)
                text += "; " + eta_text(left, f"{n} pass{'es' * (n > 1)} so far") + (
                    " for this roll through the mill; the tensions' iterations follow"
                    if self.tensions else "")
        self.last = now
        console.print(Text(text), soft_wrap=True)


def schedule(
    schedule_file: Annotated[Path, typer.Argument(
        metavar="SCHEDULE", show_default=False,
        help=f"Schedule file (TOML) or a bundled schedule's name "
             f"({', '.join(bundled_names('schedule'))}).")],
    out: OutOpt,
    no_figures: Annotated[bool, typer.Option("--no-figures", help="Do not write figures.")] = False,
    resume: ResumeOpt = True,
    fmt: FormatOpt = Format.table,
) -> None:
    """Roll a pass schedule: every pass from the previous exit state (thickness, temperature
    and strain through the thickness), interpass cooling; OUT/schedule.csv, schedule.json,
    schedule.png and one directory per pass."""
    schedule_file = find_file(schedule_file, "schedule", ("schedule",))
    try:
        sch = load_schedule(schedule_file)
        if no_figures:
            sch.output.figures = False
    except CaseError as e:
        raise fail(str(e)) from None
    with Printer(fmt, console) as printer:
        console.print(Text(f"rolling {sch.name}: {len(sch.passes)} passes -> {out}",
                           style="bold"))
        clock = _PassClock([sch.pass_name(k) for k in range(len(sch.passes))])
        try:
            rows = run_schedule(sch, out, resume=resume, figure=not no_figures, progress=clock)
        except ScheduleError as e:
            err_console.print(Text(str(e), style="yellow"), soft_wrap=True)
            _pass_warnings(out, e.rows, [(sch.pass_name(e.k), e.summary.get("warnings") or [])])
            raise typer.Exit(int(e.summary.get("exit_code") or 1)) from None
        except TensionError as e:          # the speeds ask for an impossible interstand pull
            err_console.print(Text(str(e), style="yellow"), soft_wrap=True)
            raise typer.Exit(5) from None
        printer.table(_schedule_table(sch, rows))
        width = sch.strip.width
        if any("roll_equivalent_radius" in r or "gap_setting" in r for r in rows):
            console.print("R'/R: the flattened roll's equivalent radius over its radius; gap: "
                          "the no-load roll gap to set (exit thickness - F/M)")
        if any("drx_onset_share" in r for r in rows):
            console.print(Text(
                "DRX: share of the section where dynamic recrystallisation started (strain >= "
                "eps_c); after the transport, section means: X recrystallised (-), d grain "
                f"size (um), e ret the strain handed on (-); figure {out / 'microstructure.png'}"))
        if any("speed_ratio" in r for r in rows):
            console.print(Text(
                "an asymmetric pass (r: speed ratio upper/lower): F and M the two rolls' "
                "means, M up / M low each roll's torque; kappa: the exit curvature (1/m, > 0 "
                "curls up; 0 for a symmetric pass); T out '-': an isothermal pass"))
        console.print(Text(
            f"force and torque per roll{', whole width' if width else ''}; exit temperature: "
            f"mixing-cup mean after the gap; all columns (power, surface temperature, "
            f"transports) in {out / 'schedule.csv'}; figure {out / 'schedule.png'}"))
    printer.finish()
    _pass_warnings(out, rows)


def _pass_warnings(out: Path, rows: list[dict], more: list | None = None) -> None:
    """The passes' warnings (each pass's summary.json in ``OUT/<case>``; ``more``: (pass,
    warnings) of a pass without a row, the one that failed), each text once on stderr with the
    passes that have it (the negative gaps' warnings of schedule.json are in the progress
    lines already)."""
    print_warnings([(r["name"], run_warnings(out / r["case"])) for r in rows if r.get("case")]
                   + (more or []))


def _schedule_table(sch, rows: list[dict]) -> ResultTable:
    """The passes' figures: thicknesses in mm, forces in MN (MN/m without a width), torques in
    kN m (kN m/m), the gap to set in mm, ..., and the wall time in s."""
    width = sch.strip.width
    w = width or 1.0
    tensions = sch.mill.tensions == "from_speeds"
    flat = any("roll_equivalent_radius" in r for r in rows)
    gaps = any("gap_setting" in r for r in rows)
    micro = any("drx_onset_share" in r for r in rows)
    asym = any("speed_ratio" in r for r in rows)      # an asymmetric pass: the curl, per roll
    cols = [Column("pass", left=True), Column("h", "mm", ".1f", parts=("in", "out")),
            Column("U", "m/s", ".2f")]
    cols += [Column("t front", "MPa", ".2f")] if tensions else []
    cols += [Column("F", "MN" if width else "MN/m", ".2f"),
             Column("M", "kNm" if width else "kNm/m", ".0f"), Column("T out", "K", ".1f"),
             Column("strain", spec=".3f")]
    cols += [Column("R'/R", spec=".4f")] if flat else []
    cols += [Column("gap", "mm", ".3f")] if gaps else []
    cols += [Column("DRX", spec=".2f"), Column("X", spec=".3f"), Column("d", "um", ".1f"),
             Column("e ret", spec=".3f")] if micro else []
    cols += [Column("kappa", "1/m", ".3g"), Column("r", spec=".3g"),
             Column("M up", "kNm" if width else "kNm/m", ".0f"),
             Column("M low", "kNm" if width else "kNm/m", ".0f")] if asym else []
    cols += [Column("FE"), Column("s", spec=".1f")]
    table = ResultTable(f"{sch.name}: schedule", cols)
    for r in rows:
        cells = [r["name"], (1e3 * r["entry_thickness"], 1e3 * r["exit_thickness"]),
                 r["roll_surface_speed"]]
        cells += [1e-6 * r["front_tension"]] if tensions else []
        cells += [1e-6 * w * r["roll_force"], 1e-3 * w * r["roll_torque"],
                  r["exit_temperature_mean"], r["exit_strain_mean"]]
        if flat:
            cells.append(r["roll_equivalent_radius"] / r["roll_radius"]
                         if "roll_equivalent_radius" in r else None)
        if gaps:
            cells.append(1e3 * r["gap_setting"] if "gap_setting" in r else None)
        if micro:
            after = "recrystallised_fraction_mean" in r
            cells += [r.get("drx_onset_share"),
                      r["recrystallised_fraction_mean"] if after else None,
                      1e6 * r["grain_size_mean"] if after else None,
                      r["retained_strain_mean"] if after else None]
        if asym:
            two = "speed_ratio" in r
            cells += [r["exit_curvature"], r.get("speed_ratio")]
            cells += [1e-3 * w * r[f"{side}_roll_torque"] if two else None
                      for side in ("upper", "lower")]
        cells += [r["fe_solves"], r["wall_time"]]
        table.rows.append(cells)
    return table


def study(
    study_file: Annotated[Path, typer.Argument(
        metavar="STUDY", show_default=False,
        help=f"Study file (TOML: [base] and [vary] or [[cases]]) or a bundled study's name "
             f"({', '.join(bundled_names('study'))}).")],
    out: OutOpt,
    scheduler: Annotated[Optional[str], typer.Option(
        help="Address of a running dask scheduler (default: DASK_SCHEDULER_ADDRESS, else a "
             "local cluster).")] = None,
    workers: Annotated[Optional[int], typer.Option(
        help="Workers the groups are cut for; a local cluster starts that many processes, one "
             "thread each (default: one per core, or the workers a --scheduler has).")] = None,
    serial: Annotated[bool, typer.Option("--serial", help="No cluster: the groups one after "
                                         "another in this process.")] = False,
    set_: Annotated[Optional[list[str]], typer.Option(
        "--set", help="KEY=VALUE: a dotted case key set on the base case (repeatable), e.g. "
                      "--set solver.method=transient.")] = None,
) -> None:
    """Run every combination of a study's vary lists on dask.distributed into OUT/cases/;
    the table OUT/study.csv and OUT/study.parquet (a column per varied key). Finished cases
    are read back when run again. Exit code: 0, or 64 + the number of failed cases (max 63)."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    study_file = find_file(study_file, "study", ("study",))
    try:
        st, base = load_study(study_file, overrides=_key_values(set_ or []))
    except CaseError as e:
        raise fail(str(e)) from None
    n = len(st.combinations())
    console.print(Text(f"study {st.name}: {n} cases -> {out}", style="bold"))
    with Progress(TextColumn("{task.description}"), BarColumn(), TextColumn(
            "{task.completed}/{task.total}"), TimeElapsedColumn(), TextColumn("{task.fields[info]}"),
            console=console) as bar:
        task = bar.add_task("cases", total=n, info="")

        def progress(p: dict) -> None:
            bar.update(task, completed=p["done"], info=_study_info(p))

        rows = run_study(st, base, out, scheduler=scheduler, workers=workers, serial=serial,
                         progress=progress)
    failed = [r for r in rows if r["status"] in FAILED]
    for r in failed:
        err_console.print(Text(f"{r['case']}: {r['status']}: {r['reason']}", style="yellow"),
                          soft_wrap=True)
    console.print(Text(f"{len(rows) - len(failed)} of {len(rows)} cases done; table "
                       f"{out / 'study.csv'} and {out / 'study.parquet'}"))
    for name in ("study.png", "study_profiles.png"):
        if st.plot is not None and (out / name).is_file():
            console.print(Text(f"figure {out / name}"))
    study_report(out, st.name)
    if failed:
        raise typer.Exit(64 + min(len(failed), 63))


def _study_info(p: dict) -> str:
    """The progress bar's text: failed and running cases, and the time left estimated by the
    study from the cases solved so far (``remaining_s``, NaN before the first)."""
    eta = p.get("remaining_s", float("nan"))
    info = f"failed {p['failed']}, running {p.get('running', 0)}"
    if eta == eta:
        info += ", " + eta_text(eta, "the cases solved so far")
    return info


def _key_values(items: list[str]) -> dict:
    """``KEY=VALUE`` options as a dict (``studies.config.parse_value``)."""
    out = {}
    for item in items:
        key, sep, text = item.partition("=")
        if not sep or "." not in key:
            raise fail(f"--set {item!r}: expected section.key=value, e.g. solver.method=steady")
        out[key.strip()] = parse_value(text)
    return out
