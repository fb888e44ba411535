"""Commands on one pass: ``hotroll run | compare | example | sweep | validate | meshes``
(registered on the app in ``cli/__init__.py``)."""

import time
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.markup import escape
from rich.table import Table
from rich.text import Text

from hotroll.cli.common import (
    EndOpt,
    ForceOpt,
    MeshOpt,
    MethodOpt,
    NonlinOpt,
    OutOpt,
    ResumeOpt,
    console,
    err_console,
    fail,
)
from hotroll.config.case import MESH_TABLE, Case, CaseError, load_case
from hotroll.examples import EXAMPLES, example_path
from hotroll.results.engineering import display
from hotroll.results.outcome import EXIT_CODES
from hotroll.results.output import write_csv
from hotroll.results.units import UNITS
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

SUMMARY_KEYS = ["status", "free_surface", "h_contact", "neutral_point", "neutral_angle",
                "neutral_angle_reason", "sticking_zone",
                "roll_force", "roll_torque", "roll_power", "forward_slip", "mean_pressure",
                "mean_flow_stress", "mean_strain_rate", "exit_strain", "roll_force_total",
                "roll_torque_total", "mill_power", "a_f", "balance_error",
                "converged", "steps", "nonlinear_iterations", "wall_time_s"]
#: A flattening roll, a mill modulus, a roll gap: shown where the summary has them.
MILL_KEYS = ["contact_length", "roll_model", "roll_equivalent_radius", "roll_flattening",
             "roll_updates", "mill_stretch", "gap_setting", "roll_gap", "gauge_thickness",
             "gauge_solves"]
#: With [thermal]: shown after the mechanics' figures (units from summary.json's ``units``).
THERMAL_KEYS = ["exit_temperature_mean", "exit_temperature_surface", "plastic_heat",
                "friction_heat_to_strip", "heat_to_roll", "heat_to_air", "heat_balance_error"]

PROGRESS_KEYS = ["step", "time", "m", "a_f", "iterations", "roll_force", "neutral_angle",
                 "forward_slip", "message"]

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
        case = load_case(path)
        try:
            return case.with_overrides(**over)
        except CaseError as e:
            raise CaseError(e.problems, f"{path} (with command-line options)") from None
    except CaseError as e:
        raise fail(str(e)) from None


class _Progress:
    """Throttled one-line progress report from the runner's progress dicts."""

    def __init__(self, every: float = 2.0):
        self.every, self.last = every, 0.0

    def __call__(self, info: dict) -> None:
        now = time.monotonic()
        if now - self.last < self.every and "message" not in info:
            return
        self.last = now
        keys = [k for k in PROGRESS_KEYS if k in info] or list(info)
        parts = [f"{k}={_fmt(info[k])}" + (f" {UNITS[k]}" if k in UNITS and UNITS[k] != "-" else "")
                 for k in keys if isinstance(info[k], (int, float, str, bool))]
        console.print(Text("  " + "  ".join(parts), style="dim"), soft_wrap=True)


def _fmt(v: Any) -> str:
    if isinstance(v, bool) or not isinstance(v, (int, float, list, tuple)):
        return str(v)
    if isinstance(v, (list, tuple)):
        return ", ".join(_fmt(x) for x in v)
    return f"{v:.6g}" if isinstance(v, float) else str(v)


def _run(case: Case, out: Path, resume: bool, sweep=None) -> dict:
    try:
        est = check(case)
    except ResourceError as e:
        raise fail(f"{case.name}: refused: {e}", code=8) from None
    console.print(Text(f"running {case.name} -> {out} ({est.text()})", style="bold"))
    summary = run_case(case, out, resume=resume, progress=_Progress(), sweep=sweep)
    table = Table(title=escape(f"{case.name}: summary"))
    table.add_column("quantity")
    table.add_column("value", justify="right")
    table.add_column("unit")

    thermal = THERMAL_KEYS if summary.get("thermal") else []
    # absent keys are not shown; the contact length only beside a flattened roll's figures
    mill = [k for k in MILL_KEYS if k != "contact_length" or summary.get("roll_model")]
    keys = SUMMARY_KEYS[:-4] + mill + thermal + SUMMARY_KEYS[-4:]  # before the run's own figures
    for key in keys:
        if summary.get(key) is not None:
            text, unit = display(key, summary[key], summary.get("units", {}).get(key))
            table.add_row(key, escape(text if text is not None else _fmt(summary[key])),
                          escape(unit or UNITS.get(key, "")))
    console.print(table)

    code = summary["exit_code"]
    if code:
        err_console.print(Text(f"{case.name}: {EXIT_CODES[code]} (exit code {code}; status "
                               f"{summary.get('status')}"
                               + (f": {summary['failure']}" if summary.get("failure") else "")
                               + ")", style="yellow"), soft_wrap=True)
    return summary


def _exit(summaries: list[dict]) -> None:
    """End the command with the worst run's exit code (0 when every run converged)."""
    code = max((s.get("exit_code", 0) for s in summaries), default=0)
    if code:
        raise typer.Exit(code)


def run(
    case_file: Annotated[Path, typer.Argument(help="Case description (TOML).")],
    out: OutOpt,
    mesh: MeshOpt = None,
    end_time: EndOpt = None,
    nonlinear: NonlinOpt = None,
    method: MethodOpt = None,
    no_figures: Annotated[bool, typer.Option("--no-figures", help="Do not write figures.")] = False,
    resume: ResumeOpt = True,
    force: ForceOpt = False,
) -> None:
    """Run one case file into OUT (the method is the file's [solver] method unless given)."""
    extra = {"output.figures": False} if no_figures else {}
    if force:
        extra["solver.force"] = True
    if method is not None:
        extra["solver.method"] = method
    case = _load(case_file, _overrides(mesh, end_time, nonlinear, **extra))
    _exit([_run(case, out, resume)])


def compare(
    case_file: Annotated[Path, typer.Argument(
        help="Case description (TOML) or the name of a bundled example.")],
    out: OutOpt,
    mesh: MeshOpt = None,
    method: MethodOpt = None,
) -> None:
    """Run the FE model (steady unless --method) and slab theory (Orowan, Sims, Ford-Alexander)
    on one case; write OUT/compare.{md,csv,json,png} side by side (FE run in OUT/fe)."""
    if not case_file.exists():               # a bundled example by name (or file stem)
        name = str(case_file)
        files = EXAMPLES.get(name, [name])
        if len(files) != 1:
            raise fail(f"compare: example {name!r} has several cases ({', '.join(files)}); "
                        f"name one of them")
        try:
            case_file = example_path(files[0])
        except FileNotFoundError as e:
            raise fail(f"compare: {case_file} is neither a file nor a bundled example ({e})")
    # the FE side of a comparison is the steady answer unless asked otherwise
    extra = {"output.figures": False, "solver.method": method or "steady"}
    case = _load(case_file, _overrides(mesh, None, None, **extra))
    console.print(Text(f"comparing {case.name} -> {out}", style="bold"))
    result = run_compare(case, out, progress=_Progress())
    table = Table(title=escape(f"{case.name}: FE and slab theory"))
    for col in ("quantity", "unit", "FE", "slab (Orowan)", "Sims", "Ford-Alexander", "FE/slab"):
        table.add_column(col, justify="left" if col in ("quantity", "unit") else "right")
    for row in result["rows"]:
        name = str(row["quantity"]).rsplit(" [", 1)[0]
        vals = [f"{row[c]:.4g}" if isinstance(row.get(c), float) else "-"
                for c in ("FE", "slab (Orowan)", "Sims", "Ford-Alexander", "FE/slab")]
        table.add_row(escape(name), escape(str(row["unit"])), *vals)
    console.print(table)
    if result.get("slab_error"):
        console.print(Text(f"slab theory: {result['slab_error']}", style="yellow"))
    console.print(f"table: {out / 'compare.md'}, figure: {out / 'compare.png'}")


def example(
    number: Annotated[str, typer.Argument(
        help="Report example 1, 2 or 3, or a realistic pass: hot_strip_finishing, roughing_slab, "
             "hot_aluminium, tension_pass.")],
    out: OutOpt,
    mesh: MeshOpt = None,
    end_time: EndOpt = None,
    nonlinear: NonlinOpt = None,
    method: Annotated[str, typer.Option(
        help="steady (default: direct steady state) or transient (the report's time stepping).")
    ] = "steady",
    resume: ResumeOpt = True,
    force: ForceOpt = False,
) -> None:
    """Run an example by name: the report's 1, 2, 3 (3 runs m = 0.15, 0.2, 0.25 and compares
    them) or one of the realistic passes."""
    if number not in EXAMPLES:
        raise fail(f"example: unknown example {number!r} (allowed: {', '.join(EXAMPLES)})")
    extra = {"solver.method": method, **({"solver.force": True} if force else {})}
    over = _overrides(mesh, end_time, nonlinear, **extra)
    cases = [_load(example_path(name), over) for name in EXAMPLES[number]]  # validate all first
    if len(cases) == 1:
        _exit([_run(cases[0], out, resume)])
        return

    runs, sweep, summaries = {}, Sweep(), []
    for case in cases:
        summaries.append(_run(case, out / case.name, resume, sweep))
        runs[f"m = {case.material.rate_exponent(case.plate.temperature):g}"] = out / case.name

    png = plot_compare(runs, out / "compare.png")
    console.print(Text(f"comparison plot: {png or out / 'compare.png'}"))
    _exit(summaries)


def _value(text: str) -> Any:
    """A sweep value from the command line: a number where it parses as one, else the text."""
    try:
        return float(text)
    except ValueError:
        return text.strip()


def sweep(
    case_file: Annotated[Path, typer.Argument(help="Case description (TOML).")],
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
) -> None:
    """Run a case for several values of one parameter into OUT/<param>=<value>, each steady
    solve started from the nearest solved one on the same mesh (--warm, the default) or cold;
    table in OUT/sweep.csv."""
    vals = [_value(v) for v in values.split(",") if v.strip()]
    if not vals:
        raise fail("sweep: --values is empty (give comma-separated values)")
    extra = {} if method is None else {"solver.method": method}
    if no_figures:
        extra["output.figures"] = False
    base = _overrides(mesh, None, None, **extra)
    cases = [_load(case_file, base | {param: v}) for v in vals]   # validate all first
    rows, sw, summaries = [], Sweep() if warm else None, []
    for v, case in zip(vals, cases):
        label = f"{param}={v:g}" if isinstance(v, float) else f"{param}={v}"
        case = case.with_overrides(name=f"{case.name} {label}")
        s = _run(case, out / label, resume, sw)
        summaries.append(s)
        rows.append({"param": param, "value": v, **{k: s.get(k) for k in SWEEP_KEYS}})
    out.mkdir(parents=True, exist_ok=True)
    write_csv(out / "sweep.csv", rows)
    console.print(Text(f"sweep table: {out / 'sweep.csv'}"))
    _exit(summaries)


SWEEP_KEYS = ["status", "exit_code", "converged", "neutral_angle", "roll_force", "roll_torque",
              "roll_power", "forward_slip", "a_f", "nonlinear_iterations", "wall_time_s", "warm_start_from",
              "warm_start_failed"]


def validate(case_file: Annotated[Path, typer.Argument(help="Case description (TOML).")]) -> None:
    """Check a case file; print the resolved case as TOML (exit 0) or the errors (exit 2)."""
    case = _load(case_file, {})
    p = case.pass_
    typer.echo(case.to_toml())
    typer.echo(f"# derived: contact_length = {p.contact_length:.6g} m, bite_angle = "
               f"{p.bite_angle:.6g} rad, roll_surface_speed = {p.roll_surface_speed:.6g} m/s, "
               f"h_contact = {case.mesh.h:g} m, dt = {case.dt:.6g} s")


def meshes() -> None:
    """List the contact mesh sizes of the report's Table 2."""
    table = Table(title="Table 2: contact mesh sizes")
    table.add_column("name")
    table.add_column(escape("h_contact [m]"), justify="right")
    table.add_column(escape("dt = h/6 [s]"), justify="right")
    for name, h in MESH_TABLE.items():
        table.add_row(name + (" (default)" if name == "C2" else ""), f"{h:g}", f"{h / 6:.4g}")
    console.print(table)
