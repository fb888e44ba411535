"""Commands on one pass: ``hotroll run | compare | example | sweep | meshes`` (registered on
the app in ``cli/__init__.py``; ``validate`` is ``cli/validate.py``)."""

import shutil
import time
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.text import Text

from hotroll.cli.common import (
    Column,
    EndOpt,
    ForceOpt,
    Format,
    FormatOpt,
    MeshOpt,
    MethodOpt,
    NonlinOpt,
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
    print_table,
    print_warnings,
    run_warnings,
)
from hotroll.cli.run_display import SUMMARY_KEYS  # noqa: F401 (re-exported)
from hotroll.cli.run_display import Progress as _Progress  # old names: the tests patch them
from hotroll.cli.run_display import run_end_time as _end_time
from hotroll.cli.run_display import summary_table as _summary_table
from hotroll.config.case import MESH_TABLE, Case, CaseError, load_case
from hotroll.examples import EXAMPLES, example_path
from hotroll.fem.amg import NAME as AMG
from hotroll.fem.mirror import abort_on_error, world
from hotroll.results.outcome import EXIT_CODES
from hotroll.results.output import write_csv
from hotroll.workflows.build import asymmetric_refusal
from hotroll.workflows.estimate import ResourceError, check
from hotroll.workflows.runner import run_case
from hotroll.workflows.sweep import Sweep


def run_compare(*args, **kwargs):
    """``workflows.compare.run_compare``, imported when a comparison runs (the slab theory
    brings scipy.integrate: 0.4 s of every command's start otherwise)."""
    from hotroll.workflows.compare import run_compare as run

    return run(*args, **kwargs)


def plot_compare(*args, **kwargs):
    """``results.figures.plot_compare``, imported when drawn (matplotlib)."""
    from hotroll.results.figures import plot_compare as plot

    return plot(*args, **kwargs)


def _overrides(mesh: str | None, end_time: float | None, nonlinear: str | None,
               **extra: Any) -> dict[str, Any]:
    """Dotted overrides from command-line options (unset options left out)."""
    over: dict[str, Any] = dict(extra)
    if mesh is not None:
        try:
            over["mesh.h_contact"] = float(mesh)
        except ValueError:
            over["mesh.h_contact"] = mesh
    if end_time is not None:
        over["solver.end_time"] = end_time
    if nonlinear is not None:
        over["solver.nonlinear"] = nonlinear
    return over


def _load(path: Path, over: dict[str, Any]) -> Case:
    """Load and override a case; bad input ends the command with exit code 2."""
    try:
        return load_case(path, over)
    except CaseError as e:
        raise fail(str(e)) from None



def _run(case: Case, out: Path, resume: bool, printer: Printer, sweep=None) -> dict:
    refusal = asymmetric_refusal(case)       # before anything is estimated or written
    if refusal is not None:
        raise fail(str(refusal))
    try:
        est = check(case)
    except ResourceError as e:
        raise fail(f"{case.name}: refused: {e}", code=8) from None
    console.print(Text(f"running {case.name} -> {out} ({est.text()})", style="bold"))
    summary = run_case(case, out, resume=resume, progress=_Progress(end_time=_end_time(case)),
                       sweep=sweep)
    printer.table(_summary_table(case, summary))
    code = summary["exit_code"]
    if code:
        err_console.print(Text(f"{case.name}: {EXIT_CODES[code]} (exit code {code}; status "
                               f"{summary.get('status')}"
                               + (f": {summary['failure']}" if summary.get("failure") else "")
                               + ")", style="yellow"), soft_wrap=True)
    return summary


def _runs(cases: list[tuple[Case, Path]], resume: bool, printer: Printer,
          sweep=None) -> list[dict]:
    """Several runs one after the other; after each, the time left for the others from the
    measured wall time of those done."""
    clock, summaries = RunClock(len(cases)), []
    for k, (case, out) in enumerate(cases, 1):
        t0 = time.monotonic()
        summaries.append(_run(case, out, resume, printer, sweep))
        clock.done(time.monotonic() - t0)
        left = clock.left()
        if k < len(cases) and left is not None:
            console.print(Text(f"{k} of {len(cases)} runs done; " + eta_text(
                left, f"the {k} run{'s' * (k > 1)} so far") + f" for the {len(cases) - k} left"),
                soft_wrap=True)
    return summaries


def _exit(summaries: list[dict], printer: Printer, names: list[str]) -> None:
    """Write the tables of a csv or json output and the runs' warnings (on stderr: each
    summary's ``warnings``, each text once; ``names``: the runs'), then end the command with
    the worst run's exit code (0 when every run converged)."""
    printer.finish()
    print_warnings([(name, s.get("warnings") or []) for name, s in zip(names, summaries)])
    code = max((s.get("exit_code", 0) for s in summaries), default=0)
    if code:
        raise typer.Exit(code)


CaseArg = Annotated[Path, typer.Argument(
    metavar="CASE", show_default=False,
    help=f"Case file (TOML) or a bundled case's name ({', '.join(bundled_names('case'))}), "
         f"or a report example's number (1, 2).")]


def run(
    case_file: CaseArg,
    out: OutOpt,
    mesh: MeshOpt = None,
    end_time: EndOpt = None,
    nonlinear: NonlinOpt = None,
    method: MethodOpt = None,
    no_figures: Annotated[bool, typer.Option("--no-figures", help="Do not write figures.")] = False,
    resume: ResumeOpt = True,
    force: ForceOpt = False,
    fmt: FormatOpt = Format.table,
) -> None:
    """Run one case file into OUT (the method is the file's [solver] method unless given)."""
    case_file = find_file(case_file, "run")
    extra = {"output.figures": False} if no_figures else {}
    if force:
        extra["solver.force"] = True
    if method is not None:
        extra["solver.method"] = method
    comm = world()
    if comm is not None:                   # mpiexec -n N hotroll run: rank 0 writes OUT
        out, extra = _mpi_rank(comm, out, extra)
    try:
        case = _load(case_file, _overrides(mesh, end_time, nonlinear, **extra))
        if comm is not None and case.spread is not None and case.spread.linear_solver == AMG:
            raise fail(f"spread.linear_solver = {AMG!r} runs on one process (its AMG is "
                       "scipy's): under mpiexec use a direct solver's name (umfpack)")
        with Printer(fmt, console) as printer:
            summary = _run(case, out, resume, printer)
    finally:
        if comm is not None and comm.rank > 0:
            shutil.rmtree(out, ignore_errors=True)
    _exit([summary], printer, [case.name])


def _mpi_rank(comm, out: Path, extra: dict) -> tuple[Path, dict]:
    """A run started by ``mpiexec -n N`` (``fem/mirror.world``): every rank runs the case (the
    3D pass's flow solve is shared between them: ``solvers/spread_mpi.py``; the rest is the
    same serial work on each), rank 0 writes OUT and prints (the ranks on stderr: stdout keeps
    --format csv/json's tables alone); the others write to a temporary
    directory, removed after, and print nothing (their stdout is os.devnull; stderr stays for
    a traceback). An exception on one rank ends all."""
    import os
    import sys
    import tempfile

    abort_on_error(comm)
    if comm.rank == 0:
        err_console.print(Text(f"MPI: {comm.size} ranks (netgen's rank 0 keeps no elements of the "
                           f"3D strip: {comm.size - 1} assemble its flow)"))
        return out, extra
    console.quiet = err_console.quiet = True
    sys.stdout = open(os.devnull, "w")      # noqa: SIM115 - --format csv/json's tables: rank 0's
    return (Path(tempfile.mkdtemp(prefix=f"hotroll-rank{comm.rank}-")),
            {**extra, "output.figures": False})


def compare(
    case_file: CaseArg,
    out: OutOpt,
    mesh: MeshOpt = None,
    method: MethodOpt = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Run the FE model (steady unless --method) and slab theory (Orowan, Sims,
    Ford-Alexander) on one case; write OUT/compare.{md,csv,json,png} side by side (the FE run
    in OUT/fe)."""
    case_file = find_file(case_file, "compare")
    # the FE side of a comparison is the steady answer unless asked otherwise
    extra = {"output.figures": False, "solver.method": method or "steady"}
    case = _load(case_file, _overrides(mesh, None, None, **extra))
    theories = ("FE", "slab (Orowan)", "Sims", "Ford-Alexander", "FE/slab")
    with Printer(fmt, console) as printer:
        console.print(Text(f"comparing {case.name} -> {out}", style="bold"))
        result = run_compare(case, out, progress=_Progress(end_time=_end_time(case)))
        table = ResultTable(f"{case.name}: FE and slab theory",
                            [Column("quantity", left=True), Column("unit", left=True)]
                            + [Column(c, spec=".4g") for c in theories])
        for row in result["rows"]:
            name = str(row["quantity"]).rsplit(" [", 1)[0]
            table.rows.append([name, str(row["unit"])] + [
                row[c] if isinstance(row.get(c), float) else None for c in theories])
        printer.table(table)
        if result.get("slab_error"):
            console.print(Text(f"slab theory: {result['slab_error']}", style="yellow"))
        console.print(Text(f"table: {out / 'compare.md'}, figure: {out / 'compare.png'}"))
    printer.finish()
    print_warnings([(case.name, run_warnings(out / "fe"))])


def example(
    number: Annotated[str, typer.Argument(
        metavar="EXAMPLE", show_default=False,
        help=f"Report example 1, 2 or 3, or a realistic pass: "
             f"{', '.join(k for k in EXAMPLES if not k.isdigit())}.")],
    out: OutOpt,
    mesh: MeshOpt = None,
    end_time: EndOpt = None,
    nonlinear: NonlinOpt = None,
    method: Annotated[str, typer.Option(
        help="steady (default: direct steady state) or transient (the report's time stepping).")
    ] = "steady",
    resume: ResumeOpt = True,
    force: ForceOpt = False,
    fmt: FormatOpt = Format.table,
) -> None:
    """Run an example by name: the report's 1, 2, 3 (3 runs m = 0.15, 0.2, 0.25 and compares
    them) or one of the realistic passes."""
    if number not in EXAMPLES:
        raise fail(f"example: unknown example {number!r} (allowed: {', '.join(EXAMPLES)})")
    extra = {"solver.method": method, **({"solver.force": True} if force else {})}
    over = _overrides(mesh, end_time, nonlinear, **extra)
    cases = [_load(example_path(name), over) for name in EXAMPLES[number]]  # validate all first
    with Printer(fmt, console) as printer:
        if len(cases) == 1:
            summaries = [_run(cases[0], out, resume, printer)]
        else:
            summaries = _runs([(c, out / c.name) for c in cases], resume, printer, Sweep())
            runs = {f"m = {c.material.rate_exponent(c.plate.temperature):g}": out / c.name
                    for c in cases}
            png = plot_compare(runs, out / "compare.png")
            console.print(Text(f"comparison plot: {png or out / 'compare.png'}"))
    _exit(summaries, printer, [c.name for c in cases])


def _value(text: str) -> Any:
    """A sweep value from the command line: a number where it parses as one, else the text."""
    try:
        return float(text)
    except ValueError:
        return text.strip()


def sweep(
    case_file: CaseArg,
    param: Annotated[str, typer.Option(help='Dotted key to vary, e.g. "material.m".')],
    values: Annotated[str, typer.Option(help='Comma-separated values, e.g. "0.15,0.2,0.25".')],
    out: OutOpt,
    mesh: MeshOpt = None,
    method: MethodOpt = None,
    no_figures: Annotated[bool, typer.Option("--no-figures", help="Do not write figures.")] = False,
    warm: Annotated[bool, typer.Option(
        "--warm/--cold", help="Start each steady solve from the nearest solved case (default) "
        "or from scratch.")] = True,
    resume: ResumeOpt = True,
    fmt: FormatOpt = Format.table,
) -> None:
    """Run a case for several values of one parameter into OUT/PARAM=VALUE, each steady
    solve started from the nearest solved one on the same mesh (--warm, the default) or cold;
    the table in OUT/sweep.csv."""
    case_file = find_file(case_file, "sweep")
    vals = [_value(v) for v in values.split(",") if v.strip()]
    if not vals:
        raise fail("sweep: --values is empty (give comma-separated values)")
    extra = {} if method is None else {"solver.method": method}
    if no_figures:
        extra["output.figures"] = False
    base = _overrides(mesh, None, None, **extra)
    cases = [_load(case_file, base | {param: v}) for v in vals]   # validate all first
    labels = [f"{param}={v:g}" if isinstance(v, float) else f"{param}={v}" for v in vals]
    named = [(case.with_overrides(name=f"{case.name} {label}"), out / label)
             for case, label in zip(cases, labels)]
    with Printer(fmt, console) as printer:
        summaries = _runs(named, resume, printer, Sweep() if warm else None)
        rows = [{"param": param, "value": v, **{k: s.get(k) for k in SWEEP_KEYS}}
                for v, s in zip(vals, summaries)]
        out.mkdir(parents=True, exist_ok=True)
        write_csv(out / "sweep.csv", rows)
        console.print(Text(f"sweep table: {out / 'sweep.csv'}"))
    _exit(summaries, printer, [case.name for case, _ in named])


#: ``neutral``: the story in words beside ``neutral_angle`` (null where no point is neutral)
SWEEP_KEYS = ["status", "exit_code", "converged", "neutral_angle", "neutral", "roll_force",
              "roll_torque", "roll_power", "forward_slip", "a_f", "nonlinear_iterations",
              "wall_time_s", "warm_start_from", "warm_start_failed"]


def meshes() -> None:
    """List the contact mesh sizes of the report's Table 2."""
    table = ResultTable("Table 2: contact mesh sizes", [
        Column("name", left=True), Column("h_contact [m]", spec="g"),
        Column("dt = h/6 [s]", spec=".4g")])
    for name, h in MESH_TABLE.items():
        table.rows.append([name + (" (default)" if name == "C2" else ""), h, h / 6])
    print_table(table.rich(), console)
