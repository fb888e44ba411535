"""Benchmark (not a test): the cost of the thermal coupling (issue 16's target: a coupled steady
pass at most 1.5 times the isothermal one).

For each case, one fresh process each (`hotroll run`, figures and VTK off; cold: meshing and
form compilation included) for the pass without `[thermal]` and with it, `--repeat` times; the
table keeps the median of the solver's wall times, the coupled / isothermal ratio, the coupling
updates and Newton iterations of both, the DOFs (mechanics + strip mesh) and the thermal
figures.

    python benchmarks/bench_thermal.py                   # thermal_pass and the finishing pass
    python benchmarks/bench_thermal.py --repeat 5 --threads 2
"""
from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "scripts"))

from _common import list_arg, print_table, write_table  # noqa: E402

CASES = ["thermal_pass", "hot_strip_finishing_thermal"]   # bundled cases
COLUMNS = ["case", "dofs", "strip_dofs", "iso_s", "coupled_s", "ratio", "iso_updates",
           "coupled_updates", "iso_newton", "coupled_newton", "roll_force_iso_MN",
           "roll_force_coupled_MN", "exit_T_mean_K", "exit_T_surface_K", "heat_balance_error"]


def _path(name: str) -> Path:
    from hotroll.app.examples import example_path

    return example_path(name)


def _run(path: Path, threads: int, isothermal: bool) -> dict:
    """One cold `hotroll run` of ``path`` (without [thermal] if ``isothermal``)."""
    import tomllib

    with tempfile.TemporaryDirectory() as tmp:
        data = tomllib.loads(path.read_text())
        if isothermal:                    # the same pass without its [thermal] section
            data.pop("thermal", None)
        data.setdefault("solver", {})["threads"] = threads
        data.setdefault("output", {}).update(figures=False, vtk=False)
        case = Path(tmp) / "case.toml"
        case.write_text(_toml(data))
        cmd = [sys.executable, "-m", "hotroll.app.cli", "run", str(case), "--out",
               str(Path(tmp) / "out")]
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode != 0:
            raise SystemExit(f"{path.name}: {proc.stderr.strip()[-300:]}")
        return json.loads((Path(tmp) / "out" / "summary.json").read_text())


def _toml(data: dict) -> str:
    """A case dict back to TOML (tables of scalars and lists: all a case has)."""
    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return repr(v)
    lines = [f"{k} = {value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for sec, table in data.items():
        if isinstance(table, dict):
            lines += [f"\n[{sec}]"] + [f"{k} = {value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


def one(name: str, repeat: int, threads: int) -> dict:
    path = _path(name)
    iso = [_run(path, threads, True) for _ in range(repeat)]
    cpl = [_run(path, threads, False) for _ in range(repeat)]
    ti = statistics.median(s["wall_time_s"] for s in iso)
    tc = statistics.median(s["wall_time_s"] for s in cpl)
    s, i = cpl[-1], iso[-1]
    return {"case": name, "dofs": s["dofs"], "strip_dofs": s["thermal_dofs"], "iso_s": ti,
            "coupled_s": tc, "ratio": tc / ti, "iso_updates": i["coupling_updates"],
            "coupled_updates": s["coupling_updates"], "iso_newton": i["nonlinear_iterations"],
            "coupled_newton": s["nonlinear_iterations"],
            "roll_force_iso_MN": i["roll_force"] / 1e6, "roll_force_coupled_MN": s["roll_force"] / 1e6,
            "exit_T_mean_K": s["exit_temperature_mean"],
            "exit_T_surface_K": s["exit_temperature_surface"],
            "heat_balance_error": s["heat_balance_error"]}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cases", type=list_arg(str), default=list(CASES))
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--out", type=Path, default=HERE / "results" / "bench_thermal")
    args = p.parse_args(argv)
    rows = [one(name, args.repeat, args.threads) for name in args.cases]
    title = (f"Thermal coupling cost: median of {args.repeat} cold runs each, "
             f"{args.threads} threads")
    write_table(rows, COLUMNS, args.out, title=title,
                notes=["iso_s / coupled_s: the solver's wall time (meshing and compilation "
                       "included), the pass without and with [thermal]; ratio = coupled / iso "
                       "(target 1.5)."])
    print_table(rows, COLUMNS, title)
    return 0


if __name__ == "__main__":
    sys.exit(main())
