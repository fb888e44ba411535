"""The command line's batch commands (``hotroll schedule``, ``hotroll study``), registered on
``cli.app`` when ``cli`` imports this module."""

from pathlib import Path
from typing import Annotated, Optional

import typer
from rich.markup import escape
from rich.table import Table
from rich.text import Text

from hotroll import examples as sched_examples
from hotroll.cli.common import OutOpt, ResumeOpt, console, err_console, fail
from hotroll.config.case import CaseError
from hotroll.config.schedule import load_schedule
from hotroll.config.study import load_study, parse_value
from hotroll.examples import find_study
from hotroll.workflows.schedule import ScheduleError, run_schedule
from hotroll.workflows.study import FAILED, run_study
from hotroll.workflows.tandem import TensionError


def study_report(out: Path, title: str) -> None:
    """``cli.report.study_report``, imported when a study ends (the report: matplotlib, jinja2)."""
    from hotroll.cli.report import study_report as report

    report(out, title)


def schedule(
    schedule_file: Annotated[Path, typer.Argument(
        help="Schedule file (TOML) or a bundled schedule's name (finishing_mill, ...).")],
    out: OutOpt,
    no_figures: Annotated[bool, typer.Option("--no-figures", help="Do not write figures.")] = False,
    resume: ResumeOpt = True,
) -> None:
    """Roll a pass schedule: every pass from the previous exit state (thickness, temperature
    and strain through the thickness), interpass cooling; OUT/schedule.csv, schedule.json,
    schedule.png and one directory per pass."""
    if not schedule_file.exists():
        try:
            schedule_file = sched_examples.schedule_path(str(schedule_file))
        except FileNotFoundError as e:
            raise fail(f"schedule: {schedule_file} is neither a file nor a bundled schedule "
                        f"({e})") from None
    try:
        sch = load_schedule(schedule_file)
        if no_figures:
            sch.output.figures = False
    except CaseError as e:
        raise fail(str(e)) from None
    console.print(Text(f"rolling {sch.name}: {len(sch.passes)} passes -> {out}", style="bold"))
    try:
        rows = run_schedule(sch, out, resume=resume, figure=not no_figures,
                            progress=lambda line: console.print(Text("  " + line)))
    except ScheduleError as e:
        err_console.print(Text(str(e), style="yellow"), soft_wrap=True)
        raise typer.Exit(int(e.summary.get("exit_code") or 1)) from None
    except TensionError as e:          # the speeds ask for an impossible interstand pull
        err_console.print(Text(str(e), style="yellow"), soft_wrap=True)
        raise typer.Exit(5) from None
    width = sch.strip.width
    table = Table(title=escape(f"{sch.name}: schedule"))
    tensions = sch.mill.tensions == "from_speeds"
    heads = ["pass", "h mm", "U m/s", "F MN" if width else "F MN/m",
             "M kNm" if width else "M kNm/m", "T out K", "strain", "FE", "s"]
    if tensions:
        heads.insert(3, "t front MPa")
    flat = any("roll_equivalent_radius" in r for r in rows)
    gaps = any("gap_setting" in r for r in rows)
    micro = any("drx_onset_share" in r for r in rows)
    heads[-2:-2] = (["R'/R"] if flat else []) + (["gap mm"] if gaps else []) + (
        ["DRX", "X", "d um", "e ret"] if micro else [])
    for h in heads:
        table.add_column(h, justify="left" if h == "pass" else "right")
    for r in rows:
        w = width or 1.0
        cells = [
            escape(r["name"]), f"{1e3 * r['entry_thickness']:.1f}>{1e3 * r['exit_thickness']:.1f}",
            f"{r['roll_surface_speed']:.2f}", f"{1e-6 * w * r['roll_force']:.2f}",
            f"{1e-3 * w * r['roll_torque']:.0f}", f"{r['exit_temperature_mean']:.1f}",
            f"{r['exit_strain_mean']:.3f}", str(r["fe_solves"]), f"{r['wall_time']:.1f}"]
        if tensions:
            cells.insert(3, f"{1e-6 * r['front_tension']:.2f}")
        extra = []
        if flat:
            extra.append(f"{r['roll_equivalent_radius'] / r['roll_radius']:.4f}"
                         if "roll_equivalent_radius" in r else "-")
        if gaps:
            extra.append(f"{1e3 * r['gap_setting']:.3f}" if "gap_setting" in r else "-")
        if micro:
            extra += [f"{r['drx_onset_share']:.2f}" if "drx_onset_share" in r else "-"] + (
                [f"{r['recrystallised_fraction_mean']:.3f}",
                 f"{1e6 * r['grain_size_mean']:.1f}", f"{r['retained_strain_mean']:.3f}"]
                if "recrystallised_fraction_mean" in r else ["-", "-", "-"])
        cells[-2:-2] = extra
        table.add_row(*cells)
    console.print(table)
    if flat or gaps:
        console.print("R'/R: the flattened roll's equivalent radius over its radius; gap: the "
                      "no-load roll gap to set (exit thickness - F/M)")
    if micro:
        console.print("DRX: share of the section where dynamic recrystallisation started "
                      "(strain >= eps_c); after the transport, section means: X recrystallised "
                      "(-), d grain size (um), e ret the strain handed on (-); figure "
                      f"{out / 'microstructure.png'}")
    console.print(f"force and torque per roll{', whole width' if width else ''}; exit "
                  f"temperature: mixing-cup mean after the gap; all columns (power, surface "
                  f"temperature, transports) in {out / 'schedule.csv'}; figure "
                  f"{out / 'schedule.png'}")



def study(
    study_file: Annotated[Path, typer.Argument(
        help="Study file (TOML): [base] and [vary]/[[cases]], or a bundled study's name "
             "(mesh_table, report_examples, af_study).")],
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

    try:
        study_file = find_study(study_file)
    except FileNotFoundError as e:
        raise fail(f"study: {e}") from None
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
            eta = p["remaining_s"]
            info = f"failed {p['failed']}, running {p.get('running', 0)}"
            bar.update(task, completed=p["done"], info=info + (
                f", about {eta:.0f} s left" if eta == eta else ""))

        rows = run_study(st, base, out, scheduler=scheduler, workers=workers, serial=serial,
                         progress=progress)
    failed = [r for r in rows if r["status"] in FAILED]
    for r in failed:
        err_console.print(Text(f"{r['case']}: {r['status']}: {r['reason']}", style="yellow"),
                          soft_wrap=True)
    console.print(f"{len(rows) - len(failed)} of {len(rows)} cases done; table "
                  f"{out / 'study.csv'} and {out / 'study.parquet'}")
    for name in ("study.png", "study_profiles.png"):
        if st.plot is not None and (out / name).is_file():
            console.print(f"figure {out / name}")
    study_report(out, st.name)
    if failed:
        raise typer.Exit(64 + min(len(failed), 63))


def _key_values(items: list[str]) -> dict:
    """``KEY=VALUE`` options as a dict (``studies.config.parse_value``)."""
    out = {}
    for item in items:
        key, sep, text = item.partition("=")
        if not sep or "." not in key:
            raise fail(f"--set {item!r}: expected section.key=value, e.g. solver.method=steady")
        out[key.strip()] = parse_value(text)
    return out
