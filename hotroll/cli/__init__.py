"""The command line (typer): ``hotroll run|compare|example|sweep|validate|meshes`` on one pass
(``passes.py``), ``schedule|study`` (``runs.py``) and ``report`` (``report.py``), assembled here
on one app. Imports: workflows and below."""

import typer
from rich.text import Text

from hotroll.cli import passes, report, runs
from hotroll.cli.common import err_console
from hotroll.files import DiskFullError
from hotroll.workflows.estimate import ResourceError

app = typer.Typer(help="Finite-element simulation of hot flat rolling.", no_args_is_help=True,
                  add_completion=False)
for _command in (passes.run, passes.compare, passes.example, passes.sweep, passes.validate,
                 passes.meshes, runs.schedule, runs.study, report.report):
    app.command()(_command)


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
