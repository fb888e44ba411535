"""What every command shares: the consoles, the error exit and the option types."""

from pathlib import Path
from typing import Annotated, Optional

import typer
from rich.console import Console
from rich.text import Text

console = Console()
err_console = Console(stderr=True)

OutOpt = Annotated[Path, typer.Option("--out", "-o", help="Output directory.")]
MeshOpt = Annotated[Optional[str], typer.Option(help="Contact mesh: Table 2 name (C1..F2) or h in m.")]
EndOpt = Annotated[Optional[float], typer.Option(help="Simulated end time in s.")]
NonlinOpt = Annotated[Optional[str], typer.Option(help="Nonlinear solver: newton or picard.")]
MethodOpt = Annotated[Optional[str], typer.Option(
    help="Solution method: steady (direct steady state) or transient (the report's scheme).")]
ResumeOpt = Annotated[bool, typer.Option("--resume/--no-resume", help="Resume from a checkpoint.")]
ForceOpt = Annotated[bool, typer.Option(
    "--force", help="Run even when the memory estimate is above the limit (solver.force).")]


def fail(msg: str, code: int = 2) -> typer.Exit:
    """Print ``msg`` in red on stderr; the exit to raise (code 2: bad input)."""
    err_console.print(Text(msg, style="red"), soft_wrap=True)
    return typer.Exit(code)
