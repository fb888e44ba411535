"""What every command shares: the consoles, the error exit, the runs' warnings, the option
types, the bundled files by name, the result tables in three formats and the estimate of the
time left."""

from __future__ import annotations

import csv
import io
import json
import math
import sys
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import Annotated, Any, Optional

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table
from rich.text import Text

from hotroll.examples import EXAMPLES, HERE, example_path, schedule_path, study_path
from hotroll.results.run_dir import RunDir

#: The width of a console that is not a terminal (a pipe, a file, a log): a table is printed
#: at the width it needs anyway (``print_table``); this keeps rich from wrapping text at 80.
WIDE = 1000


def _console(stderr: bool = False) -> Console:
    """A console on stdout (stderr); when that is not a terminal, wide and without wrapping, so
    that nothing is cut or broken at 80 columns in a pipe or a log."""
    probe = Console(stderr=stderr)
    if probe.is_terminal:
        return probe
    return Console(stderr=stderr, width=WIDE, soft_wrap=True)


console = _console()
err_console = _console(stderr=True)

OutOpt = Annotated[Path, typer.Option("--out", "-o", help="Output directory.")]
MeshOpt = Annotated[Optional[str], typer.Option(help="Contact mesh: Table 2 name (C1..F2) or h in m.")]
EndOpt = Annotated[Optional[float], typer.Option(help="Simulated end time in s.")]
NonlinOpt = Annotated[Optional[str], typer.Option(help="Nonlinear solver: newton or picard.")]
MethodOpt = Annotated[Optional[str], typer.Option(
    help="Solution method: steady (direct steady state) or transient (the report's scheme).")]
ResumeOpt = Annotated[bool, typer.Option("--resume/--no-resume", help="Resume from a checkpoint.")]
ForceOpt = Annotated[bool, typer.Option(
    "--force", help="Run even when the memory estimate is above the limit or the case looks "
                    "like a unit slip (solver.force).")]


class Format(str, Enum):
    """How a command prints its result table."""

    table = "table"
    csv = "csv"
    json = "json"


FormatOpt = Annotated[Format, typer.Option(
    "--format", case_sensitive=False,
    help="How the result table is printed: table (for a person, rounded), csv or json (every "
         "figure unrounded, each with its unit; the progress and messages then go to stderr).")]


def fail(msg: str, code: int = 2) -> typer.Exit:
    """Print ``msg`` in red on stderr; the exit to raise (code 2: bad input)."""
    err_console.print(Text(msg, style="red"), soft_wrap=True)
    return typer.Exit(code)


def run_warnings(run_dir: Path) -> list[str]:
    """The ``warnings`` of the run written in ``run_dir`` (its summary.json; none without
    one)."""
    if not (Path(run_dir) / "summary.json").is_file():
        return []
    return list(RunDir(run_dir).summary(strict=False).get("warnings") or [])


def print_warnings(found: list[tuple[str, list[str]]]) -> None:
    """The plausibility warnings of the runs a command made (``found``: (run or pass name,
    its summary's ``warnings``)), each text once, on stderr after a yellow ``warning:``
    (stdout may be a csv or json table). A text that not every run has names the runs that
    have it."""
    where: dict[str, list[str]] = {}
    for name, warnings in found:
        for text in warnings or []:
            where.setdefault(str(text), [])
            if name not in where[str(text)]:
                where[str(text)].append(name)
    names = list(dict.fromkeys(name for name, _ in found))
    for text, runs in where.items():
        line = Text.assemble(("warning: ", "bold yellow"), text)
        if len(runs) < len(names):
            line.append(f" ({', '.join(runs)})")
        err_console.print(line, soft_wrap=True)


# ------------------------------------------------------------------ bundled files by name
#: The bundled files' folders by kind (hotroll/examples).
BUNDLED = {"case": HERE / "cases", "schedule": HERE / "schedules", "study": HERE / "studies"}


def bundled_names(kind: str) -> list[str]:
    """The names of the bundled files of ``kind`` (case, schedule, study)."""
    return sorted(p.stem for p in BUNDLED[kind].glob("*.toml"))


def find_file(path: Path, command: str, kinds: tuple[str, ...] = ("case",)) -> Path:
    """``path`` if it is a file, else the bundled file of that name among ``kinds`` (a case
    also by its example's name: ``1`` is example1); refused (exit code 2) with the bundled
    names listed."""
    if Path(path).is_file():
        return Path(path)
    name = str(path)
    for kind in kinds:
        try:
            if kind == "case":
                files = EXAMPLES.get(name, [name])
                if len(files) != 1:
                    raise fail(f"{command}: example {name!r} has several cases "
                               f"({', '.join(files)}); name one of them")
                return example_path(files[0])
            return (schedule_path if kind == "schedule" else study_path)(name)
        except FileNotFoundError:
            continue
    what = " nor ".join(f"a bundled {k}" for k in kinds)
    plural = {"case": "cases", "schedule": "schedules", "study": "studies"}
    known = "; ".join(f"bundled {plural[k]}: {', '.join(bundled_names(k))}" for k in kinds)
    raise fail(f"{command}: {name} is neither a file nor {what} ({known})")


# ------------------------------------------------------------------ result tables
@dataclass
class Shown:
    """A cell shown to a person as ``text`` and written unrounded as ``value`` (csv, json)."""

    text: str
    value: Any


@dataclass
class Column:
    """A result table's column: its name, its unit ("" for none), how a number is shown
    (a format spec), left-aligned or right; ``parts``: a cell holding a tuple is shown as one
    and written as one column per part (``name part``)."""

    name: str
    unit: str = ""
    spec: str = ""
    left: bool = False
    parts: tuple[str, ...] = ()

    @property
    def head(self) -> str:
        return f"{self.name} {self.unit}".strip()


@dataclass
class ResultTable:
    """A table of results: its title, columns and rows of cells (a number, a text, None for
    none, a ``Shown`` or a tuple for a column with ``parts``)."""

    title: str
    columns: list[Column]
    rows: list[list[Any]] = field(default_factory=list)

    def shown(self, cell: Any, col: Column) -> str:
        if isinstance(cell, Shown):
            return cell.text
        if cell is None:
            return "-"
        if isinstance(cell, tuple):
            return ">".join(self.shown(c, col) for c in cell)
        if isinstance(cell, float) and not math.isfinite(cell):
            return str(cell)
        return format(cell, col.spec) if col.spec and not isinstance(cell, str) else str(cell)

    def rich(self) -> Table:
        table = Table(title=escape(self.title))
        for col in self.columns:
            table.add_column(escape(col.head), justify="left" if col.left else "right")
        for row in self.rows:
            table.add_row(*(escape(self.shown(c, col)) for c, col in zip(row, self.columns)))
        return table

    def machine(self) -> tuple[list[str], list[list[Any]]]:
        """(column names with the unit in brackets, rows of unrounded values)."""
        names, rows = [], []
        for col in self.columns:
            unit = f" [{col.unit}]" if col.unit else ""
            names += [f"{col.name} {p}{unit}" for p in col.parts] or [f"{col.name}{unit}"]
        for row in self.rows:
            out: list[Any] = []
            for c, col in zip(row, self.columns):
                c = c.value if isinstance(c, Shown) else c
                if col.parts:
                    out += list(c) if isinstance(c, tuple) else [c] + [None] * (len(col.parts) - 1)
                else:
                    out.append(c)
            rows.append([_plain(v) for v in out])
        return names, rows


def _plain(v: Any) -> Any:
    """A value JSON and CSV can hold: a non-finite number as None, numpy scalars as Python."""
    if hasattr(v, "item") and not isinstance(v, (str, bytes)):
        v = v.item()
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def print_table(table: Table, out: Console) -> None:
    """Print a rich table at the width it needs when the console is narrower (a terminal of 80
    columns): the terminal may fold a long line, but no figure is cut to "16.…"."""
    need = out.measure(table, options=out.options.update_width(10 * WIDE)).maximum
    if need > out.width:
        table.width = need
        out.print(table, crop=False)
    else:
        out.print(table)


class Printer:
    """A command's result tables in its ``--format``: ``table`` prints each at once on
    ``out``; ``csv`` and ``json`` collect them and ``finish`` writes them to stdout, the
    console's messages going to stderr meanwhile (``with Printer(...)``)."""

    def __init__(self, fmt: Format | str, out: Console):
        self.fmt, self.out, self.tables = Format(fmt), out, []

    def __enter__(self) -> Printer:
        self._file = getattr(self.out, "_file", None)     # None: rich's stdout of the moment
        if self.fmt is not Format.table:
            self.out.file = sys.stderr
        return self

    def __exit__(self, *exc) -> None:
        self.out.file = self._file

    def table(self, result: ResultTable) -> None:
        if self.fmt is Format.table:
            print_table(result.rich(), self.out)
        else:
            self.tables.append(result)

    def finish(self) -> None:
        """Write the collected tables to stdout (csv: a first column ``table`` with the
        title when there are several; json: a list of {title, columns, rows})."""
        if self.fmt is Format.table or not self.tables:
            return
        if self.fmt is Format.json:
            doc = []
            for t in self.tables:
                names, rows = t.machine()
                doc.append({"title": t.title, "columns": names,
                            "rows": [dict(zip(names, r)) for r in rows]})
            sys.stdout.write(json.dumps(doc, indent=1) + "\n")
            return
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        several = len(self.tables) > 1
        for k, t in enumerate(self.tables):
            names, rows = t.machine()
            if k == 0:
                writer.writerow((["table"] if several else []) + names)
            for r in rows:
                writer.writerow(([t.title] if several else []) + ["" if v is None else v
                                                                  for v in r])
        sys.stdout.write(buf.getvalue())


# ------------------------------------------------------------------ the time left
def duration(seconds: float) -> str:
    """A duration with its unit: s below 2 min, min below 2 h, else h."""
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.1f} min"
    return f"{seconds / 3600:.1f} h"


def eta_text(left: float, basis: str) -> str:
    """The time left as a person reads it: labelled an estimate, with its unit and what it was
    measured from."""
    return f"ETA about {duration(left)} (estimate from {basis})"


class RunClock:
    """The time left of a batch of ``total`` similar pieces (runs, passes) from the wall time of
    those measured so far: ``done(seconds)`` records one."""

    def __init__(self, total: int):
        self.total, self.seconds = total, []

    def done(self, seconds: float) -> None:
        self.seconds.append(seconds)

    def left(self, remaining: int | None = None) -> float | None:
        """Seconds for the ``remaining`` pieces (default: total - measured) at the mean
        measured rate; None before the first piece."""
        if not self.seconds:
            return None
        n = self.total - len(self.seconds) if remaining is None else remaining
        return max(n, 0) * sum(self.seconds) / len(self.seconds)
