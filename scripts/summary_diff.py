"""Every bundled example's, schedule's and study's summary before and after a change.

    python scripts/summary_diff.py run OUT [--only NAME,...]     # solve them all into OUT
    python scripts/summary_diff.py compare BEFORE AFTER [--rtol 1e-9] [--residuals-atol A]

``run`` calls the command line (``hotroll example|schedule|study``), so the same script runs
on any commit. ``compare`` walks every summary.json, schedule.json, study.json and the
study/schedule CSV tables under BEFORE and compares the same files under AFTER: the keys and
the units must be identical; numbers equal to ``--rtol`` (1e-9: an unchanged arithmetic; the
solver's tolerance, e.g. 1e-5, where a step changes the iteration path). ``--residuals-atol``:
the figures that measure a residual (a key with "error" or "residual": zero up to the solver's
tolerance, so their relative change says nothing) compared absolutely to A instead; wall
times, paths and dates are skipped. Exit code 1 and the differences listed when they differ.
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: The bundled runs: (kind, name); examples by the CLI's names.
RUNS = [("example", n) for n in ("1", "2", "hot_strip_finishing", "roughing_slab",
                                 "hot_aluminium", "tension_pass", "hot_strip_finishing_thermal",
                                 "asymmetric_plate", "asymmetric_radii")]
RUNS += [("schedule", "finishing_mill"), ("study", "af_study")]
#: Keys that change from run to run by nature (time, place), not by the arithmetic.
VOLATILE = ("wall_time", "wall_s", "seconds", "elapsed", "path", "dir", "out", "date",
            "created", "version", "python", "host", "commit", "traceback", "worker",
            "checkpoint", "estimated_memory", "peak_memory", "_file", "files",
            "solver_threads")


def run(out: Path, only: list[str]) -> int:
    """Each bundled run into OUT/<kind>/<name> through the command line."""
    exe = Path(sys.executable).with_name("hotroll")
    bad = 0
    for kind, name in RUNS:
        if only and name not in only:
            continue
        target = out / kind / name
        if target.exists() and any(target.iterdir()):
            # a schedule or a study resumes the passes it finds there: another commit's
            # results would be compared as this one's (it happened: a /tmp kept from a session
            # before held a schedule solved by older code)
            print(f"  {target} is not empty: a schedule or study would resume from it; "
                  "give an empty OUT", flush=True)
            bad += 1
            continue
        cmd = [str(exe), kind, name, "--out", str(target)]
        if kind == "study":
            cmd.append("--serial")
        print(" ".join(cmd[1:]), flush=True)
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if proc.returncode not in (0, 7) and not (kind == "study" and proc.returncode > 64):
            print(f"  exit code {proc.returncode}\n{proc.stderr[-2000:]}", flush=True)
            bad += 1
    return bad


def _volatile(key: str) -> bool:
    return any(v in key.lower() for v in VOLATILE)


def _number(v):
    if isinstance(v, bool) or v is None:
        return None
    if isinstance(v, (int, float)):
        return float(v)
    if isinstance(v, str):
        try:
            return float(v)
        except ValueError:
            return None
    return None


def _close(a: float, b: float, rtol: float) -> bool:
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    return abs(a - b) <= rtol * max(abs(a), abs(b)) + 1e-300


def unit_scales(summary: dict) -> dict[str, float]:
    """Per key, the largest magnitude among the summary's numbers of the same unit (1 for
    dimensionless ones): a difference below rtol x that scale is rounding (threaded assembly
    sums in a different order), e.g. a horizontal force of 3e-7 N/m beside a roll force of
    0.5 N/m."""
    units = summary.get("units") or {}
    biggest: dict[str, float] = {}
    for k, u in units.items():
        v = _number(summary.get(k))
        if v is not None and math.isfinite(v):
            biggest[u] = max(biggest.get(u, 0.0), abs(v))
    return {k: (1.0 if u in ("-", "") else biggest.get(u, 0.0)) for k, u in units.items()}


#: Keys of figures that measure a residual (zero up to the solver's tolerance).
RESIDUALS = ("error", "residual")


def diff(a, b, rtol: float, where: str, out: list[str], scale: float = 0.0,
         scales: dict | None = None, atol: float | None = None) -> None:
    """Differences of two JSON-like values (keys, then numbers to rtol of themselves or of
    their unit's scale, then text)."""
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            out.append(f"{where}: keys only before {sorted(set(a) - set(b))}, only after "
                       f"{sorted(set(b) - set(a))}")
        if scales is None and "units" in a:
            scales = unit_scales(a)
        for k in sorted(set(a) & set(b)):
            if not _volatile(k):
                diff(a[k], b[k], rtol, f"{where}.{k}", out, (scales or {}).get(k, scale), scales,
                     atol)
        return
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{where}: length {len(a)} -> {len(b)}")
            return
        for i, (x, y) in enumerate(zip(a, b)):
            diff(x, y, rtol, f"{where}[{i}]", out, scale, scales, atol)
        return
    x, y = _number(a), _number(b)
    if x is not None and y is not None:
        key = where.rsplit(".", 1)[-1]
        if atol is not None and any(r in key for r in RESIDUALS):
            if not (abs(x - y) <= atol or (math.isnan(x) and math.isnan(y))):
                out.append(f"{where}: {a!r} -> {b!r} (abs {abs(x - y):.2e})")
        elif not _close(x, y, rtol) and not abs(x - y) <= rtol * scale:
            out.append(f"{where}: {a!r} -> {b!r} (rel {abs(x - y) / max(abs(x), abs(y)):.2e})")
    elif a != b:
        out.append(f"{where}: {a!r} -> {b!r}")


def _read(path: Path):
    if path.suffix == ".json":
        return json.loads(path.read_text())
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def compare(before: Path, after: Path, rtol: float, atol: float | None = None) -> list[str]:
    """Every differing value of the result files under BEFORE against AFTER."""
    out: list[str] = []
    files = sorted(p for pat in ("summary.json", "schedule.json", "study.json", "schedule.csv",
                                 "study.csv") for p in before.rglob(pat))
    if not files:
        return [f"{before}: no result files"]
    for p in files:
        rel = p.relative_to(before)
        q = after / rel
        if not q.is_file():
            out.append(f"{rel}: missing after")
            continue
        diff(_read(p), _read(q), rtol, str(rel), out, atol=atol)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("out", type=Path)
    r.add_argument("--only", default="")
    c = sub.add_parser("compare")
    c.add_argument("before", type=Path)
    c.add_argument("after", type=Path)
    c.add_argument("--rtol", type=float, default=1e-9)
    c.add_argument("--residuals-atol", type=float, default=None)
    args = ap.parse_args()
    if args.cmd == "run":
        sys.exit(1 if run(args.out, [n for n in args.only.split(",") if n]) else 0)
    problems = compare(args.before, args.after, args.rtol, args.residuals_atol)
    print("\n".join(problems) if problems else f"identical to {args.rtol:g}")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
