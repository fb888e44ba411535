"""The report's pages of many runs: a study (``study.csv``) and a pass schedule
(``schedule.json``); read from the files those commands wrote, with the units of the columns."""
from __future__ import annotations

import csv
import io
import math
from pathlib import Path
from urllib.parse import quote

from hotroll.results.report_run import (
    LABELS,
    case_inputs,
    finite,
    number,
    read_json,
    run_warnings,
    scale,
)
from hotroll.results.run_dir import RunDir
from hotroll.results.units import UNITS

#: A study's result columns shown (when the table has them), after the varied keys.
STUDY_KEYS = ("roll_force", "roll_force_total", "roll_torque", "forward_slip", "neutral_angle",
              "mean_pressure", "roll_power", "max_roll_force", "total_roll_power",
              "exit_temperature_mean", "outlet_temperature_mean", "exit_strain_mean",
              "nonlinear_iterations", "fe_solves",
              "wall_time_s")   # max_roll_force ...: a schedule study's (workflows/study.py)
#: Column heads of the tables (the summary's labels where not here).
SHORT = {"roll_force": "roll force", "roll_force_total": "roll force, whole width",
         "roll_torque": "roll torque", "roll_torque_total": "roll torque, whole width",
         "roll_power": "roll power", "mean_pressure": "mean pressure",
         "exit_temperature_mean": "exit temperature", "nonlinear_iterations": "iterations",
         "outlet_temperature_mean": "exit temperature after the last gap",
         "wall_time_s": "wall time", "entry_thickness": "entry", "exit_thickness": "exit",
         "roll_surface_speed": "roll speed", "exit_temperature_surface": "exit surface T",
         "exit_strain_mean": "exit strain", "transport_duration": "transport",
         "next_entry_temperature_mean": "next entry T", "fe_solves": "FE solves",
         "wall_time": "wall time", "max_roll_force": "largest roll force",
         "total_roll_power": "roll power, all passes"}
#: Columns of study.csv that are not a varied key (a row's bookkeeping).
_BOOK = ("worker", "status", "exit_code", "reason", "resumed")
#: every status but "done" is a failure (not_converged, bad_input, too_large, error, ...)
DONE = "done"


def _float(text: str):
    """A CSV cell as a number where it is one (empty: None), else the text."""
    if text == "":
        return None
    try:
        return float(text)
    except ValueError:
        return text


def read_table(path: Path) -> tuple[list[str], list[dict]]:
    with open(path, newline="") as fh:
        reader = csv.DictReader(fh)
        rows = [{k: _float(v or "") for k, v in r.items()} for r in reader]
        return list(reader.fieldnames or []), rows


def column(key: str, values: list, unit: str, label: str | None = None) -> dict:
    """A table column in one unit for all its rows (the largest magnitude chooses it)."""
    nums = [v for v in values if finite(v)]
    f, off, shown = scale(key, unit, max((abs(v) for v in nums), default=0.0))
    return {"key": key, "label": label or SHORT.get(key) or LABELS.get(key, key.replace("_", " ")),
            "unit": shown if nums else "", "scale": (f, off), "si_unit": unit,
            "cells": [number(v / f - off) if finite(v) else (v if isinstance(v, str) and v
                                                              else "-") for v in values],
            "values": [repr(float(v)) if finite(v) else "" for v in values]}


def _link(root: Path, sub: str) -> str | None:
    """Link (relative to ``root``) to the report of the run in ``root/sub``, if it has one."""
    return quote(f"{sub}/report.html") if (root / sub / "report.html").is_file() else None


def study_context(d: Path, title: str | None = None) -> dict:
    """Everything the study page shows (``templates/report.html.j2``, kind "study")."""
    heads, rows = read_table(d / "study.csv")
    stop = next((i for i, h in enumerate(heads) if h in _BOOK), len(heads))
    varied = heads[heads.index("case") + 1:stop] if "case" in heads else []
    units = _input_units(d / "cases", [str(r.get("case")) for r in rows])
    meta = read_json(d / "study.json") if (d / "study.json").is_file() else {}
    varied = [k for k in meta.get("varied") or varied if k in heads]   # hotroll study's list
    units.update(meta.get("units") or {})          # written by hotroll study (all its keys)
    title = title or meta.get("name")
    keys = [k for k in STUDY_KEYS if any(finite(r.get(k)) for r in rows)]
    cols = ([column(k, [r.get(k) for r in rows], units.get(k, ""), label=k) for k in varied]
            + [column(k, [r.get(k) for r in rows],
                      units.get(k) or UNITS.get(k, "-")) for k in keys])
    table = [{"case": str(r.get("case")), "status": str(r.get("status")),
              "index": int(r["index"]) if finite(r.get("index")) else i,
              "failed": r.get("status") != DONE, "reason": r.get("reason") or "",
              "link": _link(d, f"cases/{r.get('case')}"),
              "cells": [c["cells"][i] for c in cols],
              "values": [c["values"][i] for c in cols]} for i, r in enumerate(rows)]
    n_failed = sum(t["failed"] for t in table)
    wall = sum(r["wall_time_s"] for r in rows if finite(r.get("wall_time_s")))
    figure = study_figure(rows, varied, cols[:len(varied)])
    return {"kind": "study", "title": title or d.name, "ok": n_failed == 0,
            "status": f"{len(rows) - n_failed} of {len(rows)} cases done",
            "varied": varied, "columns": cols, "lead": len(varied), "table": table,
            "wall_time": wall, "figure_png": figure, "warnings": _failures(table),
            "figure_x": varied[figure_x(rows, varied)] if varied else None}


def _failures(table: list[dict]) -> list[dict]:
    """One line for the failed cases of a study, by status (their reasons are in the table)."""
    failed = [t for t in table if t["failed"]]
    if not failed:
        return []
    kinds = dict.fromkeys(t["status"] for t in failed)
    counts = ", ".join(f"{sum(t['status'] == k for t in failed)} {k}" for k in kinds)
    names = ", ".join(f"#{t['index']}" for t in failed[:12]) + (", ..." if len(failed) > 12 else "")
    return [{"level": "error", "text": f"{len(failed)} of {len(table)} cases failed ({counts}): "
             f"{names}; the reasons are in the red rows of the table"}]


def _input_units(cases: Path, labels: list[str]) -> dict:
    """Units of the varied keys, from the comments of a solved case's case.toml."""
    for label in labels:
        path = cases / label / "case.toml"
        if path.is_file():
            return {f"{sec}.{r['key']}": r["unit"] for sec, rs in case_inputs(path)[1] for r in rs}
    return {}


def figure_x(rows: list[dict], varied: list[str]) -> int:
    """The varied key the study figure is drawn against: the first with numbers only."""
    return next((i for i, k in enumerate(varied)
                 if all(isinstance(r.get(k), float) for r in rows)), 0)


def study_figure(rows: list[dict], varied: list[str], vcols: list[dict]) -> bytes | None:
    """Roll force, torque and forward slip against a varied key (``figure_x``), a line per
    value of the others (the finished cases); a PNG, or None when there is nothing to draw."""
    done = [r for r in rows if r.get("status") == "done"]
    if not varied or not done:
        return None
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    i = figure_x(rows, varied)
    vcols = [vcols[i]] + vcols[:i] + vcols[i + 1:]
    x_key, others = varied[i], varied[:i] + varied[i + 1:]
    xs = list(dict.fromkeys(r[x_key] for r in rows))
    numeric = all(isinstance(x, float) for x in xs)
    xf, xoff = vcols[0]["scale"] if numeric else (1.0, 0.0)
    panels = [k for k in ("roll_force", "roll_torque", "forward_slip")
              if any(finite(r.get(k)) for r in done)]
    if not panels:
        return None
    fig, axes = plt.subplots(1, len(panels), figsize=(4.2 * len(panels), 3.6), squeeze=False)
    lines = list(dict.fromkeys(tuple(r[k] for k in others) for r in rows))
    for ax, key in zip(axes[0], panels):
        unit = UNITS.get(key, "-")
        f, off, shown = scale(key, unit, max(abs(r[key]) for r in done if finite(r.get(key))))
        for line in lines:
            pts = sorted((xs.index(r[x_key]) if not numeric else r[x_key] / xf - xoff,
                          r[key] / f - off)
                         for r in done if tuple(r[k] for k in others) == line
                         and finite(r.get(key)))
            if pts:
                label = ", ".join(_value(c, v) for c, v in zip(vcols[1:], line)) or None
                ax.plot(*zip(*pts), "o-", label=label)
        ax.set_xlabel(_axis(x_key, vcols[0]["unit"] if numeric else ""))
        ax.set_ylabel(f"{SHORT.get(key) or LABELS.get(key, key)} [{_mpl(shown)}]")
        if not numeric:
            ax.set_xticks(range(len(xs)), [_text(x) for x in xs])
        ax.grid(alpha=0.3)
    fig.tight_layout()
    if others:
        handles, labels = axes[0][0].get_legend_handles_labels()
        fig.subplots_adjust(bottom=0.30 if len(labels) > 4 else 0.24)
        fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 4), fontsize=9,
                   frameon=False)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    plt.close(fig)
    return buf.getvalue()


def _value(col: dict, v) -> str:
    """A varied key's value in its column's unit, for a legend."""
    if not finite(v):
        return f"{col['key']} = {v}"
    f, off = col["scale"]
    unit = col["unit"].replace("^", "") if col["unit"] not in ("-", "") else ""
    return f"{col['key']} = {number(v / f - off)} {unit}".rstrip()


def _text(v) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)


def _mpl(unit: str) -> str:
    return unit.replace("^", "") if unit else "-"


def _axis(key: str, unit: str) -> str:
    return f"{key} [{_mpl(unit)}]" if unit else key


#: A schedule's columns shown (when present), in this order.
SCHEDULE_KEYS = ("entry_thickness", "exit_thickness", "reduction", "roll_surface_speed",
                 "roll_force_total", "roll_force", "roll_torque_total", "roll_torque",
                 "forward_slip", "exit_temperature_mean", "exit_temperature_surface",
                 "exit_strain_mean", "transport_duration", "fe_solves", "wall_time")


def schedule_context(d: Path, title: str | None = None) -> dict:
    """Everything the schedule page shows (kind "schedule")."""
    data = read_json(d / "schedule.json")
    passes, units = data.get("passes") or [], data.get("units") or {}
    keys = [k for k in SCHEDULE_KEYS if any(finite(p.get(k)) for p in passes)]
    if "roll_force_total" in keys:                     # a width: the whole strip's figures
        keys = [k for k in keys if k not in ("roll_force", "roll_torque")]
    cols = [column(k, [p.get(k) for p in passes], units.get(k) or UNITS.get(k, "-"),
                   label=SHORT.get(k, "").removesuffix(", whole width") or None) for k in keys]
    warns, table = [], []
    for i, p in enumerate(passes):
        sub = str(p.get("case") or "")
        s = d / sub / "summary.json"
        w = run_warnings(RunDir(d / sub).summary()) if sub and s.is_file() else []
        warns += [{"level": x["level"], "text": f"pass {p.get('name')}: {x['text']}"} for x in w]
        table.append({"case": str(p.get("name")), "failed": any(x["level"] == "error" for x in w),
                      "status": "warnings" if w else "ok", "reason": "", "link": _link(d, sub),
                      "cells": [c["cells"][i] for c in cols],
                      "values": [c["values"][i] for c in cols]})
    png = d / "schedule.png"
    wall = data.get("wall_time")
    return {"kind": "schedule", "title": title or data.get("name") or d.name,
            "ok": not any(t["failed"] for t in table),
            "status": f"{len(passes)} passes" + (f", {data.get('fe_solves')} FE solves"
                                                  if data.get("fe_solves") else ""),
            "columns": cols, "lead": len(cols), "table": table, "warnings": warns,
            "wall_time": wall if finite(wall) else math.nan,
            "figures": [("The schedule pass by pass", png)] if png.is_file() else []}
