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


def main() -> None:
    """The ``hotroll`` command: the app, a full disk (exit code 9, ``files.DiskFullError``) or a
    mesh over the memory limit (exit code 8) ending it with its clear message instead of a
    traceback."""
    try:
        app()
    except DiskFullError as e:
        err_console.print(Text(str(e.strerror or e), style="red"), soft_wrap=True)
        raise SystemExit(9) from None
    except ResourceError as e:          # a schedule's or compare's pass (run/example: _run)
        err_console.print(Text(f"refused: {e}", style="red"), soft_wrap=True)
        raise SystemExit(8) from None
