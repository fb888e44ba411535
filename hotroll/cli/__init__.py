"""The command line (typer): ``hotroll run|compare|example|sweep|meshes`` on one pass
(``passes.py``), ``validate`` of a case, schedule or study file (``validate.py``),
``schedule|study`` (``runs.py``) and ``report`` (``report.py``), assembled here on one app with
``--version`` and ``-h``. Imports: workflows and below."""

from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as _dist_version
from typing import Annotated, Optional

import typer
from rich.text import Text

from hotroll.cli import passes, report, runs, validate
from hotroll.cli.common import err_console
from hotroll.files import DiskFullError
from hotroll.workflows.estimate import ResourceError

# Help in typer's markdown mode: a docstring's paragraphs are reflowed to the terminal (no
# line broken where the source wraps) and [section] names are text, not rich markup.
app = typer.Typer(help="Finite-element simulation of hot flat rolling.", no_args_is_help=True,
                  add_completion=False, rich_markup_mode="markdown",
                  context_settings={"help_option_names": ["-h", "--help"]})
for _command in (passes.run, passes.compare, passes.example, passes.sweep, validate.validate,
                 passes.meshes, runs.schedule, runs.study, report.report):
    app.command()(_command)


def version() -> str:
    """hotroll's installed version (its package metadata)."""
    try:
        return _dist_version("hotroll")
    except PackageNotFoundError:            # a source tree that was never installed
        return "unknown (not installed)"


def _version(value: bool) -> None:
    if value:
        typer.echo(f"hotroll {version()}")
        raise typer.Exit()


@app.callback()
def _main(
    show_version: Annotated[Optional[bool], typer.Option(
        "--version", "-V", callback=_version, is_eager=True,
        help="Print hotroll's version and exit.")] = None,
) -> None:
    """Finite-element simulation of hot flat rolling."""


#: the launchers' variables that give the number of MPI ranks (Open MPI; MPICH's and Intel
#: MPI's Hydra; MVAPICH)
MPI_SIZE_VARIABLES = ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "MV2_COMM_WORLD_SIZE")


#: the commands that run over MPI ranks (``mpiexec -n N hotroll run ...``: the 3D pass's flow
#: solve shared between them, rank 0 writing; ``cli/passes.run``)
MPI_COMMANDS = ("run",)


def mpi_refusal(env, argv=()) -> str | None:
    """Why hotroll refuses to run under ``mpirun -n N`` with N > 1 (``env``: the process's
    environment, ``argv``: its arguments after the program), or None: ``hotroll run`` shares
    a case's 3D pass between the ranks (``MPI_COMMANDS``); any other command would solve the
    whole case on every rank into the same files."""
    if env.get("HOTROLL_ALLOW_MPI") == "1":       # a single hotroll under an MPI parent
        return None
    command = next((a for a in argv if not a.startswith("-")), None)
    if command in MPI_COMMANDS:
        return None
    for key in MPI_SIZE_VARIABLES:
        try:
            n = int(env.get(key, "1"))
        except ValueError:
            continue
        if n > 1:
            return (f"refused: launched on {n} MPI ranks ({key}={n}): only `hotroll run` "
                    "shares a case between MPI ranks (its 3D pass's flow solve: "
                    "mpiexec -n N hotroll run CASE); this command would solve the same case "
                    "on every rank into the same files. Run it without mpirun; many cases run "
                    "in parallel with `hotroll study` (dask.distributed). (One hotroll started "
                    "by an MPI program's rank inherits its variables: HOTROLL_ALLOW_MPI=1.)")
    return None


def main() -> None:
    """The ``hotroll`` command: the app, a full disk (exit code 9, ``files.DiskFullError``) or a
    mesh over the memory limit (exit code 8) ending it with its clear message instead of a
    traceback; refused under MPI with more than one rank but for ``hotroll run`` (exit code 2,
    ``mpi_refusal``)."""
    import os
    import sys

    why = mpi_refusal(os.environ, sys.argv[1:])
    if why is not None:
        err_console.print(Text(why, style="red"), soft_wrap=True)
        raise SystemExit(2)
    try:
        app()
    except DiskFullError as e:
        err_console.print(Text(str(e.strerror or e), style="red"), soft_wrap=True)
        raise SystemExit(9) from None
    except ResourceError as e:          # a schedule's or compare's pass (run/example: _run)
        err_console.print(Text(f"refused: {e}", style="red"), soft_wrap=True)
        raise SystemExit(8) from None
