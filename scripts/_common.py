"""Helpers shared by scripts/agreement.py and benchmarks/bench_example1.py.

Example 1 with dotted overrides, command-line options common to them, a run that skips
finished outputs and survives a failing case, and tables written as CSV and Markdown.
"""
from __future__ import annotations

import argparse
import json
import math
import time
import traceback
from pathlib import Path
from typing import Any, Iterable, Sequence

from hotroll.config.case import MESH_TABLE, Case, CaseError, load_case
from hotroll.examples import example_path
from hotroll.results.output import write_csv

#: Summary statuses after which re-running the same case would change nothing.
FINISHED = ("steady", "end_time", "max_steps", "failed")


# ------------------------------------------------------------------------ cases & options

def example1(**overrides: Any) -> Case:
    """Example 1 (report: m = 0.2, omega = pi/3) with ``{"section.key": value}`` overrides."""
    return load_case(example_path("example1")).with_overrides(**overrides)


def mesh_arg(text: str) -> str | float:
    """A contact mesh given as a Table 2 name (C1..F2, any case), "auto" or a size h in m."""
    text = text.strip()
    if text.upper() in MESH_TABLE:
        return text.upper()
    if text.lower() == "auto":
        return "auto"
    try:
        h = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{text!r}: not a Table 2 mesh ({', '.join(MESH_TABLE)}) nor a size in m") from None
    if not (math.isfinite(h) and h > 0):
        raise argparse.ArgumentTypeError(f"{text!r}: a mesh size must be > 0")
    return h


def list_arg(item):
    """argparse type for a comma-separated list whose items are converted by ``item``."""
    def parse(text: str) -> list:
        return [item(t) for t in text.split(",") if t.strip()]
    return parse


def mesh_label(mesh: str | float) -> str:
    return mesh if isinstance(mesh, str) else f"{mesh:g}"


def add_common_args(p: argparse.ArgumentParser, out: str, *, resume: bool = True) -> None:
    p.add_argument("--end-time", type=float, default=None,
                   help="simulated end time in s (default: automatic; runs stop when steady)")
    p.add_argument("--out", type=Path, default=Path(out), help=f"output directory (default {out})")
    p.add_argument("--threads", type=int, default=None,
                   help="NGSolve threads per run (default: the case file's)")
    p.add_argument("--figures", action="store_true", help="also write each run's own figures")
    p.add_argument("--resume", action=argparse.BooleanOptionalAction, default=resume,
                   help="reuse finished runs and resume interrupted ones from their checkpoint")


def common_overrides(args: argparse.Namespace) -> dict[str, Any]:
    over: dict[str, Any] = {"output.figures": bool(args.figures)}
    if args.end_time is not None:
        over["solver.end_time"] = args.end_time
    if args.threads is not None:
        over["solver.threads"] = args.threads
    return over


def make_case(p: argparse.ArgumentParser, **overrides: Any) -> Case:
    """Example 1 with overrides; an invalid combination ends the script with its message."""
    try:
        return example1(**overrides)
    except CaseError as e:
        p.error(str(e))


# ------------------------------------------------------------------------------- running

class _Progress:
    def __init__(self, label: str, every: float = 10.0):
        self.label, self.every, self.last = label, every, -math.inf

    def __call__(self, row: dict) -> None:
        now = time.monotonic()
        if now - self.last < self.every and row.get("step", 1) != 0:
            return
        self.last = now
        print(f"  [{self.label}] step {row.get('step')}  t={row.get('time', math.nan):.4g} s  "
              f"a_f={row.get('a_f', math.nan):.4g}  it={row.get('iterations')}  "
              f"F={row.get('roll_force', math.nan):.5g}  "
              f"angle={row.get('neutral_angle', math.nan):.4g}", flush=True)


def finished_summary(case: Case, out: Path) -> dict | None:
    """summary.json of an earlier, finished run of ``case`` in ``out`` (else None): same
    fingerprint (the physics; threads, limits and output options may differ)."""
    import json

    from hotroll.workflows.runner import fingerprint

    toml, summ = Path(out) / "case.toml", Path(out) / "summary.json"
    try:
        if (fingerprint(load_case(toml)) != fingerprint(case)
                or summ.stat().st_mtime < toml.stat().st_mtime):
            return None
        summary = json.loads(summ.read_text())
    except (OSError, ValueError, CaseError):
        return None
    return summary if summary.get("status") in FINISHED else None


def run(case: Case, out: Path, label: str, *, resume: bool = True) -> dict:
    """Run (or reuse) one case; an exception becomes ``status = "error: ..."`` in the result."""
    from hotroll.workflows.runner import run_case

    out = Path(out)
    if resume and (done := finished_summary(case, out)) is not None:
        print(f"[{label}] finished earlier ({done['status']}), reusing {out}/summary.json",
              flush=True)
        return done
    print(f"[{label}] running -> {out}  (h = {case.mesh.h:g} m, dt = {case.dt:.4g} s, "
          f"{case.solver.nonlinear})", flush=True)
    try:
        summary = run_case(case, out, resume=resume, progress=_Progress(label))
    except Exception as e:  # noqa: BLE001 - one failing case must not end a study
        traceback.print_exc()
        return {"status": f"error: {type(e).__name__}: {e}"}
    print(f"[{label}] {summary['status']} after {summary['steps']} steps, "
          f"{summary['wall_time_s']:.1f} s", flush=True)
    return summary


def has_output(summary: dict) -> bool:
    return not str(summary.get("status", "error")).startswith("error")


def flat(summary: dict, **extra: Any) -> dict:
    """Summary with the neutral point split into neutral_x, neutral_y (plus ``extra``)."""
    row = dict(summary)
    pt = summary.get("neutral_point") or [None, None]
    row["neutral_x"], row["neutral_y"] = pt[0], pt[1]
    row.update(extra)
    return row


# -------------------------------------------------------------------------------- tables

def fmt(v: Any) -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "n/a"
    if isinstance(v, bool):
        return str(v).lower()
    if isinstance(v, float):
        return f"{v:.5g}"
    return str(v)


def to_toml(data: dict, prefix: str = "") -> str:
    """A case or schedule dict back to TOML: scalars and lists, tables, arrays of tables
    (with their sub-tables), the benchmarks' edited copies of the bundled files."""
    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return repr(v)
    out = [f"{k} = {value(v)}" for k, v in data.items()
           if not isinstance(v, (dict, list)) or (isinstance(v, list) and not
                                                   (v and isinstance(v[0], dict)))]
    for k, v in data.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            out += [f"\n[{name}]", to_toml(v, name + ".")]
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            for item in v:
                out += [f"\n[[{name}]]", to_toml(item, name + ".")]
    return "\n".join(out)


def markdown(rows: Sequence[dict], columns: Sequence[str]) -> str:
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(fmt(r.get(c)).replace("|", "/") for c in columns) + " |"
              for r in rows]
    return "\n".join(lines) + "\n"


def write_table(rows: Sequence[dict], columns: Sequence[str], stem: Path, *, title: str = "",
                notes: Iterable[str] = (), csv: bool = True) -> tuple[Path | None, Path]:
    """Write ``stem``.csv (full precision; unless ``csv`` is false) and ``stem``.md (title,
    table, notes); return both paths."""
    stem = Path(stem)
    stem.parent.mkdir(parents=True, exist_ok=True)
    csv_path, md_path = stem.with_suffix(".csv") if csv else None, stem.with_suffix(".md")
    if csv_path and rows:
        write_csv(csv_path, [{c: _cell(r.get(c)) for c in columns} for r in rows])
    elif csv_path:
        csv_path.write_text(",".join(columns) + "\n")
    md = (f"# {title}\n\n" if title else "") + markdown(rows, columns)
    notes = list(notes)
    if notes:
        md += "\n" + "\n".join(f"- {n}" for n in notes) + "\n"
    md_path.write_text(md)
    return csv_path, md_path


def _cell(v: Any) -> Any:
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def print_table(rows: Sequence[dict], columns: Sequence[str], title: str = "") -> None:
    """Print with rich when available, else as Markdown."""
    try:
        from rich.console import Console
        from rich.table import Table
    except ImportError:
        print((f"{title}\n" if title else "") + markdown(rows, columns))
        return
    table = Table(title=title or None)
    for c in columns:
        table.add_column(c, justify="left" if c in ("mesh", "method", "status") else "right",
                         min_width=len(c))
    for r in rows:
        table.add_row(*(fmt(r.get(c)) for c in columns))
    Console(width=sum(max(len(c), 10) + 3 for c in columns) + 1).print(table)
