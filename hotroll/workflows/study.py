"""Running a study on dask.distributed (issue 18): the cases in groups, a table of results.

The valid cases, those on one mesh next to each other, are cut into contiguous groups, about
two per worker; a group is one task: its cases run one after another in one worker process,
each starting from the nearest case the group has solved on its mesh, else from the last one
mapped onto its mesh (``workflows/sweep.py``, ``solvers/transfer.py``).
The same groups run in the same order serially (``serial=True``) or on a
cluster, so both give the same table to the digit. A task whose worker dies is run again by
dask elsewhere; the cases it had finished are read back (each case's directory is its
checkpoint: ``summary.json`` beside the ``case.toml`` it was solved for, and the final state
the group's next case starts from, ``warm_state.npz``), as they are when the study is run
again: a study killed at any moment and run again ends with the table of an uninterrupted run.

Each case writes ``DIR/cases/<label>/``; the table ``DIR/study.csv`` and ``DIR/study.parquet``
(one row per combination: its index and label, a column per varied key named as the key, the
status, the exit code, the reason of a failure, the summary's scalar fields) is rewritten
atomically after every finished group.
"""
from __future__ import annotations

import json
import math
import os
import socket
import time
import traceback
from pathlib import Path
from typing import Callable

from hotroll.config.case import CaseError, case_from_dict
from hotroll.config.schedule import schedule_from_dict
from hotroll.config.study import Study, StudyCase, expand, key_unit
from hotroll.files import DiskFullError, atomic
from hotroll.results.outcome import EXIT_CODES
from hotroll.results.output import write_csv, write_json, write_text
from hotroll.results.units import UNITS
from hotroll.solvers.steady_settings import WarmStart
from hotroll.workflows.estimate import ResourceError
from hotroll.workflows.runner import finished_summary, run_case
from hotroll.workflows.schedule import ScheduleError, run_schedule
from hotroll.workflows.sweep import Sweep, form_key, parameters
from hotroll.workflows.warm_state import WARM_FILE, load_warm, restore_run, save_warm

#: status of a row: "done", "not_converged" (the run ended with a non-zero exit code),
#: "bad_input" (the case schema refused the combination), "too_large" (the memory estimate is
#: over the limit, workflows/estimate.py), "error" (an exception).
FAILED = ("not_converged", "bad_input", "too_large", "error")


def groups(cases: list[StudyCase], workers: int) -> list[list[StudyCase]]:
    """Groups of the valid cases, about two per worker; the cases on one mesh next to each
    other (ordered by ``sweep.form_key``, then by their combination), so that a group's case
    starts from its neighbour on the same mesh where it can."""
    def key(c: StudyCase):
        return (form_key(c.case) if hasattr(c.case, "pass_") else "", c.index)

    valid = sorted((c for c in cases if c.case is not None), key=key)
    if not valid:
        return []
    n = min(len(valid), max(1, 2 * workers))
    size = math.ceil(len(valid) / n)
    return [valid[i:i + size] for i in range(0, len(valid), size)]


def run_group(items: list[dict], out: str, warm: bool) -> list[dict]:
    """Solve a group's cases in this process (a dask task); one row per case."""
    sweep = Sweep(similar=True, history=False) if warm else None
    rows, pending = [], None
    for item in items:
        cdir = Path(out) / "cases" / item["label"]
        row = {"index": item["index"], "case": item["label"], **item["values"],
               "worker": f"{socket.gethostname()}:{os.getpid()}"}
        if "schedule" in item:
            try:
                row.update(run_schedule_item(item, cdir))
            except DiskFullError:
                raise
            except Exception as e:  # noqa: BLE001 - a case's failure is its row
                row.update(status="error", exit_code=1, reason=f"{type(e).__name__}: {e}",
                           resumed=False)
                cdir.mkdir(parents=True, exist_ok=True)
                write_text(cdir / "error.txt", traceback.format_exc())
            rows.append(row)
            continue
        case = case_from_dict(item["case"])
        try:
            summary = finished_summary(case, cdir)
            if (summary is not None and sweep is not None and summary.get("exit_code") == 0
                    and not (cdir / WARM_FILE).exists()):
                # killed between its summary and its final state: solved again (from the same
                # start, so to the same numbers), else the group's next case would start cold
                summary = None
            resumed = summary is not None
            if summary is None:
                cdir.mkdir(parents=True, exist_ok=True)
                write_text(cdir / "worker.txt", row["worker"] + "\n")   # who solves it
                if pending is not None:        # the last case was read back: its run too
                    if isinstance(pending[1], WarmStart):     # (the half strip's: schedules)
                        sweep._last = (pending[0].name, restore_run(*pending))
                    pending = None
                summary = run_case(case, cdir, resume=False, sweep=sweep)
                if sweep is not None and sweep.solved and sweep.solved[-1][0] == case.name:
                    save_warm(cdir / WARM_FILE, sweep.solved[-1][2])
            elif sweep is not None and (cdir / WARM_FILE).exists():
                # the state it ended in, for the group's next case (as if solved just now)

                warm_state = load_warm(cdir / WARM_FILE)
                sweep.solved.append((case.name, parameters(case), warm_state))
                if isinstance(warm_state, WarmStart):    # the half strip's: a similar pass's
                    pending = (case, warm_state)         # start (Sweep.add keeps it too)
            code = int(summary.get("exit_code", 1))
            row.update(status="done" if code == 0 else "not_converged", exit_code=code,
                       reason=None if code == 0 else _reason(summary), resumed=resumed)
            row.update(_scalars(summary))
        except DiskFullError:            # every next case would fail too: the study stops
            raise
        except ResourceError as e:       # refused before meshing: the estimate is its reason
            row.update(status="too_large", exit_code=8, reason=str(e), resumed=False)
        except Exception as e:  # noqa: BLE001 - a case's failure is its row, not the study's
            row.update(status="error", exit_code=1, reason=f"{type(e).__name__}: {e}",
                       resumed=False)
            (cdir).mkdir(parents=True, exist_ok=True)
            write_text(cdir / "error.txt", traceback.format_exc())
        rows.append(row)
    return rows


def _reason(summary: dict) -> str:
    code = summary.get("exit_code")
    text = f"{EXIT_CODES.get(code, '?')} (status {summary.get('status')})"
    return text + (f": {summary['failure']}" if summary.get("failure") else "")


def _scalars(summary: dict) -> dict:
    """The summary's scalar fields (numbers, text, booleans), not its lists and tables."""
    skip = ("case_name", "exit_code", "status")
    return {k: v for k, v in summary.items() if k not in skip
            and (v is None or isinstance(v, (int, float, str, bool)))}


def _payload(group: list[StudyCase]) -> list[dict]:
    return [{"index": c.index, "label": c.label, "values": c.values,
             **({"case": c.case.to_dict()} if hasattr(c.case, "pass_") else
                {"schedule": c.case.model_dump(by_alias=True, exclude_none=True)})}
            for c in group]



#: a schedule study's columns per pass (``<pass name>.<key>``)
PASS_KEYS = ("roll_force", "roll_torque", "roll_power", "forward_slip", "roll_surface_speed",
             "exit_temperature_mean", "exit_strain_mean", "roll_force_total")


def run_schedule_item(item: dict, cdir: Path) -> dict:
    """A schedule study's case: the schedule rolled into ``cdir`` (finished passes read back);
    its row: per-pass columns and the schedule's totals."""
    sch = schedule_from_dict(item["schedule"])
    try:
        rows = run_schedule(sch, cdir, resume=True, figure=False)
    except ScheduleError as e:          # the passes before the failed one keep their columns
        code = int(e.summary.get("exit_code") or 1)
        return {"status": "not_converged", "exit_code": code, "reason": str(e),
                "resumed": False, **_pass_columns(e.rows)}
    except ResourceError as e:
        return {"status": "too_large", "exit_code": 8, "reason": str(e), "resumed": False}
    except CaseError as e:              # a later pass's case, built from the exit state
        return {"status": "bad_input", "exit_code": 2, "reason": "; ".join(e.problems),
                "resumed": False}
    out = {"status": "done", "exit_code": 0, "reason": None,
           "resumed": all(r["fe_solves"] == 0 for r in rows), "passes": len(rows),
           "exit_thickness": rows[-1]["exit_thickness"],
           "outlet_temperature_mean": rows[-1].get("outlet_temperature_mean"),
           "exit_strain_mean": rows[-1]["exit_strain_mean"],
           "max_roll_force": max(r["roll_force"] for r in rows),
           "total_roll_power": sum(r["roll_power"] for r in rows),
           "fe_solves": sum(r["fe_solves"] for r in rows),
           "wall_time_s": sum(r["wall_time"] for r in rows)}
    return out | _pass_columns(rows)


def _pass_columns(rows: list[dict]) -> dict:
    """``<pass name>.<key>`` of a schedule's finished passes."""
    return {f"{r['name']}.{k}": r.get(k) for r in rows for k in PASS_KEYS
            if r.get(k) is not None}


def run_study(study: Study, base: dict, out: Path, *, scheduler: str | None = None,
              workers: int | None = None, serial: bool = False,
              progress: Callable[[dict], None] | None = None) -> list[dict]:
    """Run every combination (module docstring); returns the table's rows by index.
    ``scheduler``: an existing dask scheduler's address (else ``DASK_SCHEDULER_ADDRESS``, else
    a local cluster of ``workers`` processes, one per core, one thread each); with a
    scheduler and no ``workers``, the groups are cut for the workers it has."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    cases = expand(study, base)
    rows = {c.index: {"index": c.index, "case": c.label, **c.values, "status": "bad_input",
                      "exit_code": 2, "reason": c.problem, "resumed": False}
            for c in cases if c.case is None}
    scheduler = scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS")
    if workers is None and scheduler is not None and not serial:
        workers = _scheduler_workers(scheduler)
    workers = workers or os.cpu_count() or 1
    work = groups(cases, workers)
    total, t0 = len(cases), time.perf_counter()

    running = min(workers, len(work)) if not serial else min(1, len(work))
    left = [len(work)]                    # groups not finished

    def done(new: list[dict], group_done: bool = False) -> None:
        for r in new:
            rows[r["index"]] = r
        left[0] -= group_done
        write_table(out, [rows[i] for i in sorted(rows)])
        if progress:
            busy = min(running, left[0])
            progress({**_progress(rows, total, t0), "running": busy})

    keys = list(dict.fromkeys(k for c in cases for k in c.values))
    write_json(out / "study.json", {"name": study.name, "cases": total, "varied": keys,
                                    "units": {k: key_unit(k) for k in keys}})
    done([])
    if serial:
        for g in work:
            done(run_group(_payload(g), str(out), study.run.warm_start), True)
    elif work:
        from distributed import Client, LocalCluster, as_completed

        cluster = None
        if scheduler is None:
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
        try:
            with Client(scheduler or cluster) as client:
                futures = {client.submit(run_group, _payload(g), str(out.resolve()),
                                         study.run.warm_start, pure=False): g for g in work}
                for fut in as_completed(futures):
                    try:
                        new_rows = fut.result()
                    except DiskFullError:
                        raise
                    except Exception as e:  # noqa: BLE001 - KilledWorker (memory), ...: the
                        new_rows = [_lost(c, e) for c in futures[fut]]   # group's rows
                    done(new_rows, True)
        finally:
            if cluster is not None:
                cluster.close()
    table = [rows[i] for i in sorted(rows)]
    units = column_units(out, table, {k: key_unit(k) for k in keys})
    write_json(out / "study.json", {"name": study.name, "cases": total, "varied": keys,
                                    "units": units})
    figures(study, out, table, units)
    return table


def column_units(out: Path, rows: list[dict], varied: dict[str, str]) -> dict[str, str]:
    """The unit of every column of the table: the varied keys' (``varied``), the summary's
    from the first finished case (a schedule's ``schedule.json``, a pass's column
    ``F1.roll_force`` with the unit of ``roll_force``), a schedule row's own (``results/units.py``)."""
    units = {}
    for r in rows:
        cdir = Path(out) / "cases" / str(r.get("case"))
        found = [cdir / n for n in ("summary.json", "schedule.json") if (cdir / n).is_file()]
        if r.get("status") == "done" and found:
            units = dict(json.loads(found[0].read_text()).get("units", {}))
            if found[0].name == "schedule.json":
                units = {**UNITS, **units}
            break
    cols = {k for r in rows for k in r}
    units.update({c: units[c.split(".")[-1]] for c in cols
                  if "." in c and c not in varied and c.split(".")[-1] in units})
    return {**{k: u for k, u in units.items() if k in cols}, **varied}


def _scheduler_workers(address: str) -> int | None:
    """How many workers (threads) a running scheduler has, or None if it has none yet."""
    from distributed import Client

    with Client(address, timeout="30s") as client:
        info = client.scheduler_info().get("workers", {})
    return sum(int(w.get("nthreads", 1)) for w in info.values()) or None


def plot_table(*args, **kwargs):
    """``results.study_plot.plot_table``, imported when drawn (matplotlib)."""
    from hotroll.results.study_plot import plot_table as plot

    return plot(*args, **kwargs)


def plot_profiles(*args, **kwargs):
    """``results.study_plot.plot_profiles``, imported when drawn (matplotlib)."""
    from hotroll.results.study_plot import plot_profiles as plot

    return plot(*args, **kwargs)


def figures(study: Study, out: Path, rows: list[dict], units: dict[str, str]) -> list[Path]:
    """The study's figures drawn from its table (``[plot]``): study.png, study_profiles.png."""
    if study.plot is None:
        return []

    made = []
    try:
        made.append(plot_table(rows, study.plot, out / "study.png", units=units,
                               title=f"study {study.name}"))
        if study.plot.profiles:
            made.append(plot_profiles(rows, out, out / "study_profiles.png",
                                      title=f"study {study.name}: contact profiles"))
    except DiskFullError:
        raise
    except Exception as e:  # noqa: BLE001 - a figure must not cost the finished table
        import warnings

        warnings.warn(f"study figures: not drawn ({type(e).__name__}: {e})")
    return [p for p in made if p is not None]


def _lost(c: StudyCase, e: Exception) -> dict:
    """The row of a case whose group the cluster gave up on (its worker killed again and
    again, e.g. out of memory: dask's KilledWorker)."""
    return {"index": c.index, "case": c.label, **c.values, "status": "error", "exit_code": 1,
            "reason": f"the cluster gave up on its group: {type(e).__name__}: {e}",
            "resumed": False}


def _progress(rows: dict, total: int, t0: float) -> dict:
    n_done = len(rows)
    failed = sum(r["status"] in FAILED for r in rows.values())
    elapsed = time.perf_counter() - t0
    solved = sum(not r.get("resumed") and r["status"] != "bad_input" for r in rows.values())
    rate = solved / elapsed if solved and elapsed > 0 else float("nan")
    left = total - n_done
    return {"done": n_done, "failed": failed, "total": total, "elapsed": elapsed,
            "remaining_s": left / rate if rate == rate and rate > 0 else float("nan")}


def write_table(out: Path, rows: list[dict]) -> None:
    """study.csv and study.parquet, atomically (the columns: the union of the rows' keys)."""
    keys = list(dict.fromkeys(k for r in rows for k in r))
    table = [{k: r.get(k) for k in keys} for r in rows]
    write_csv(out / "study.csv", table)
    _write_parquet(out / "study.parquet", keys, table)


def _write_parquet(path: Path, keys: list[str], rows: list[dict]) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    cols = {}
    for k in keys:
        vals = [r.get(k) for r in rows]
        kinds = {type(v) for v in vals if v is not None}
        if kinds <= {int, float} and kinds:
            vals = [None if v is None else float(v) for v in vals] if float in kinds else vals
        elif len(kinds) > 1:
            vals = [None if v is None else str(v) for v in vals]
        cols[k] = vals
    with atomic(path) as tmp:
        pq.write_table(pa.table(cols), tmp)
