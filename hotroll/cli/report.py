"""The command line's ``hotroll report DIR``, registered on ``cli.app`` when ``cli`` imports
this module; the page itself is ``results/report.py``."""

from pathlib import Path
from typing import Annotated

import typer
from rich.text import Text

from hotroll.cli.common import console, fail
from hotroll.files import DiskFullError


def report(
    directory: Annotated[Path, typer.Argument(
        help="Output directory of hotroll run, example, compare, study or schedule.")],
    open_: Annotated[bool, typer.Option(
        "--open/--no-open", help="Open the page in the web browser when written.")] = False,
) -> None:
    """Write DIR/report.html: one self-contained page (inputs, results with units, figures,
    slab theory where compared, warnings); a study's or schedule's page links each run's own."""
    from hotroll.results.report import ReportError, kind, write_report  # matplotlib, jinja2

    try:
        kind(directory)                 # refused before anything is written
    except ReportError as e:
        raise fail(str(e)) from None
    try:
        path = write_report(directory)
    except DiskFullError:
        raise                           # cli.main: its message, exit code 9
    except ValueError as e:             # a file of the directory not readable as written
        raise fail(f"report: {directory}: {e}") from None
    except OSError as e:
        raise fail(f"report: {directory}: {e}", code=1) from None
    console.print(Text(str(path)))
    if open_:
        import webbrowser

        if not webbrowser.open(path.resolve().as_uri()):
            console.print(Text("no web browser found: open the file yourself", style="yellow"))


def study_report(out: Path, title: str) -> None:
    """The study's page at the end of ``hotroll study`` (a failure to write it is reported,
    the study's exit code stays the study's)."""
    from hotroll.results.report import write_report

    try:
        console.print(Text(f"report: {write_report(out, title)}"))
    except DiskFullError:
        raise
    except Exception as e:  # noqa: BLE001 - the page must not cost the study's exit code
        console.print(Text(f"report: not written ({type(e).__name__}: {e})", style="yellow"))
