"""Benchmark (not a test): the cost of the thermal coupling (issue 16's target: a coupled steady
pass at most 1.5 times the isothermal one).

For each case, one fresh process each (`hotroll run`, figures and VTK off; cold: meshing and
form compilation included) for the pass without `[thermal]` and with it, `--repeat` times; the
table keeps the median of the solver's wall times, the coupled / isothermal ratio, the coupling
updates and Newton iterations of both, the DOFs (mechanics + strip mesh) and the thermal
figures.

    python benchmarks/bench_thermal.py                   # the six passes of CASES
    python benchmarks/bench_thermal.py --cases hot_strip_finishing_thermal
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

from _common import list_arg, print_table, to_toml, write_table  # noqa: E402

FINISHING = "hot_strip_finishing_thermal"
# name: (bundled case, overrides by section): the README's pass, the study case, and the
# finishing pass with the other friction laws, a lower speed and a heavier reduction (so that
# the ratio is not one Newton path's)
CASES = {
    "thermal_pass": ("thermal_pass", {}),
    FINISHING: (FINISHING, {}),
    "finishing_tresca": (FINISHING, {"friction": {"law": "tresca", "factor": 0.8}}),
    "finishing_viscoplastic": (FINISHING, {"friction": {"law": "viscoplastic"}}),
    "finishing_1.75m/s": (FINISHING, {"pass": {"roll_angular_velocity": 5.0}}),
    "finishing_8.5-5.5mm": (FINISHING, {"pass": {"entry_thickness": 0.0085,
                                                 "exit_thickness": 0.0055}}),
}
COLUMNS = ["case", "dofs", "strip_dofs", "iso_s", "coupled_s", "ratio", "iso_updates",
           "coupled_updates", "iso_newton", "coupled_newton", "roll_force_iso_MN",
           "roll_force_coupled_MN", "exit_T_mean_K", "exit_T_surface_K", "heat_balance_error"]


def _run(name: str, threads: int, isothermal: bool) -> dict:
    """One cold `hotroll run` of case ``name`` (without [thermal] if ``isothermal``)."""
    import tomllib

    from hotroll.examples import example_path

    example, overrides = CASES[name]
    with tempfile.TemporaryDirectory() as tmp:
        data = tomllib.loads(example_path(example).read_text())
        for section, values in overrides.items():
            if section == "friction":     # a friction law replaces the section
                data[section] = dict(values)
            else:
                data.setdefault(section, {}).update(values)
        if isothermal:                    # the same pass without its [thermal] section
            data.pop("thermal", None)
        data.setdefault("solver", {})["threads"] = threads
        data.setdefault("output", {}).update(figures=False, vtk=False)
        case = Path(tmp) / "case.toml"
        case.write_text(to_toml(data))
        cmd = [sys.executable, "-m", "hotroll.cli", "run", str(case), "--out",
               str(Path(tmp) / "out")]
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode != 0:
            raise SystemExit(f"{name}: {proc.stderr.strip()[-300:]}")
        return json.loads((Path(tmp) / "out" / "summary.json").read_text())


def one(name: str, repeat: int, threads: int) -> dict:
    iso, cpl = [], []
    for _ in range(repeat):               # alternated: slow spells of the machine hit both
        iso.append(_run(name, threads, True))
        cpl.append(_run(name, threads, False))
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
    unknown = [name for name in args.cases if name not in CASES]
    if unknown:
        p.error(f"--cases: unknown {unknown}; allowed: {', '.join(CASES)}")
    rows = [one(name, args.repeat, args.threads) for name in args.cases]
    rows.append({"case": "all (sum of medians)", "iso_s": sum(r["iso_s"] for r in rows),
                 "coupled_s": sum(r["coupled_s"] for r in rows),
                 "iso_newton": sum(r["iso_newton"] for r in rows),
                 "coupled_newton": sum(r["coupled_newton"] for r in rows)})
    rows[-1]["ratio"] = rows[-1]["coupled_s"] / rows[-1]["iso_s"]
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
