"""The 3D strip's cost (issue 53: a narrow-bar pass, b0/h0 = 1, in under 3 minutes; a
quarter-model roughing pass in under 10 minutes cold and 6 GB), at three or four width gradings.

    python benchmarks/bench_3d.py [--case narrow|roughing] [--sizes coarsest,coarse,medium,fine]
                                  [--solver umfpack|sparsecholesky+gmres|amg+gmres] [--corner 1]

``narrow``: Case R of ../shared/notes/asymmetric-rolling.md (R = 250 mm, 10 -> 8 mm, Tresca
0.3, Norton-Hoff m = 0.05, h = 1 mm) with a stock 10 mm wide. ``roughing``: the bundled
roughing_slab (R = 0.6 m, 200 -> 170 mm, its Hensel-Spittel grade and friction) with the
issue's width 1.5 m (the 3D strip carries the strain through its own flow, the default).
Each size is one process's run after the 2D pass: ``Spread3D`` set-up and solve
(solvers/spread_3d.py), cold (the first 3D forms of the process are compiled in it). Sizes:
the edge layer and the largest layer in units of the 2D contact mesh size h: coarse (2h, 8h),
medium (h, 4h), fine (h/2, 2h), and coarsest (4h, 16h) for a third size of the roughing
pass (its fine grading does not fit in 24 GB). Prints a table: DOFs, layers, Newton iterations,
rounds, the Jacobian's factorisations (and in brackets the Newton directions solved on kept
factors, ``Spread3D.reuse_steps``), wall s (2D, 3D set-up, 3D solve), peak resident memory of
the process (GB), spread, and the mass balance (out + edge - in) / in (``SpreadResult``'s
sign). The linear solver: UMFPACK by default, or ``--solver`` (solvers/spread_3d.py: LINEAR_SOLVERS_3D);
``--corner``: the 2D mesh refined at the contact's start (``mesh.corner_refinement``, default
16 as a case's; 1: none). Time on 2 cores with nothing else running. Under
``mpiexec -n N`` the 3D flow solve runs over the ranks (solvers/spread_mpi.py; netgen's rank 0
holds no elements: N - 1 assemble), rank 0 prints.
"""
from __future__ import annotations

import argparse
import json
import resource
import sys
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))

from asymmetric_case_r import case_r  # noqa: E402

from hotroll.config.case import load_case  # noqa: E402
from hotroll.examples import example_path  # noqa: E402
from hotroll.fem.mirror import abort_on_error, world  # noqa: E402
from hotroll.solvers.spread_3d import LINEAR_SOLVERS_3D, Spread3D  # noqa: E402
from hotroll.solvers.steady import SteadyRun  # noqa: E402
from hotroll.workflows.build import build_model, steady_settings  # noqa: E402

SIZES = {"coarsest": (4.0, 16.0), "coarse": (2.0, 8.0), "medium": (1.0, 4.0),
         "fine": (0.5, 2.0)}


def two_d(kind: str, corner: float = 16.0):
    if kind == "narrow":
        case, problem, st = case_r(0.05, 1e-3)
        problem = replace(problem, mesh=replace(problem.mesh, corner=corner))
        half_width = 0.005
    else:
        case = load_case(example_path("roughing_slab"), {"output.figures": False,
                                                         "mesh.corner_refinement": corner})
        problem, _ = build_model(case)
        st = steady_settings(case)
        half_width = 0.75
    t0 = time.perf_counter()
    run = SteadyRun(problem, st, case.plate.length)
    status = run.run().status
    return run, half_width, status, time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--case", default="narrow", choices=("narrow", "roughing"))
    ap.add_argument("--sizes", default="coarse,medium,fine")
    ap.add_argument("--solver", default="umfpack", choices=LINEAR_SOLVERS_3D,
                    help="the 3D Newton's linear solver (solvers/spread_3d.py: LINEAR_SOLVERS_3D)")
    ap.add_argument("--corner", type=float, default=16.0,
                    help="mesh.corner_refinement of the 2D mesh the 3D one is extruded from")
    ap.add_argument("--figures", default=None, help="write each size's figures (JSON) here")
    a = ap.parse_args()
    comm = world()                 # mpiexec -n N: the 3D flow solve over the ranks
    if comm is not None:
        abort_on_error(comm)
    say = print if comm is None or comm.rank == 0 else (lambda *args, **kw: None)
    run, half_width, status, wall2 = two_d(a.case, a.corner)
    h = run.problem.h
    if comm is not None:
        say(f"MPI: {comm.size} ranks (rank 0 holds no elements); peak GB: the largest rank's "
            "and, in brackets, all ranks'")
    say(f"{a.case}: 3D linear solver {a.solver}; 2D pass {status}, {run.form.fes.ndof} DOFs, "
          f"h = {h * 1e3:.3g} mm, corner refinement {a.corner:g}, "
          f"{wall2:.1f} s")
    say("| size | layers | DOFs | Newton its | rounds | factorisations (kept) | 3D set-up s | "
          "3D solve s | peak GB | spread mm | (out + edge - in) / in |")
    say("|---|---|---|---|---|---|---|---|---|---|---|")
    for size in a.sizes.split(","):
        edge, largest = SIZES[size]
        s3 = Spread3D(run, half_width, edge=min(edge * h, half_width), largest=largest * h,
                      linear_solver=a.solver, comm=comm)
        s3.solve()
        fig = s3.figures()
        if a.figures and (comm is None or comm.rank == 0):
            keep = {k: v for k, v in fig.items() if isinstance(v, (bool, int, float, str))}
            Path(a.figures).write_text(json.dumps(dict(size=size, **keep)) + "\n")
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
        mem = f"{peak:.2f}"
        if comm is not None:
            peaks = comm.gather(peak)
            mem = "" if peaks is None else f"{max(peaks):.2f} ({sum(peaks):.2f})"
        say(f"| {size} | {len(s3.z) - 1} | {fig['dofs']} | {fig['newton_iterations']} | "
            f"{fig['rounds']} | {fig['factorisations']} ({fig['reused']}) | "
            f"{s3.setup_time:.1f} | {s3.solve_time:.1f} | {mem} | "
            f"{fig.get('spread', float('nan')) * 1e3:.3f} | "
            f"{(fig['flux_out'] + fig['flux_edge'] - fig['flux_in']) / fig['flux_in']:.1e} |",
            flush=True)


if __name__ == "__main__":
    main()
