"""The Newton iterations and coupling updates of every FE solve of a schedule (issue 34's
study of where the iterations go; docs/validation/speed.md).

    python scripts/newton_trace.py hotroll/examples/schedules/ten_stand_finishing.toml [--passes N]
    python scripts/newton_trace.py --example 2
    python scripts/newton_trace.py --case hotroll/examples/cases/thin_strip.toml

One line per FE solve: the roll speed, the wall time, the Newton steps as L(update, step
length) and each coupling update as a two-letter name and its change in tolerances (st
strain, te temperature, a_ a_f, fr free surface, co the contact's end, ro roll, sp a tandem
stand's speed).

``--flow-alone`` (a diagnosis, issue 34 session 10): every pass started from the previous one
is first solved with its couplings frozen at the warm start's values (the flow's own Newton
from that start, a line marked "flow alone"), then as usual (the schedule goes on from that).
``--freeze strain,free_surface,...`` (a diagnosis, physically wrong): those couplings are
updated once in each solve and then held (their change counted as 0); names as in
``solvers/couplings.py`` (strain, temperature, a_f, free_surface, roll, speed). Freezing the
speed breaks a tandem schedule's mass flow: the schedule then solves passes again.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
import time
import tomllib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("schedule", type=Path, nargs="?", default=None)
    p.add_argument("--example", default=None, help="a bundled example's name instead")
    p.add_argument("--case", type=Path, default=None, help="a case file instead")
    p.add_argument("--passes", type=int, default=None, help="the first N passes only")
    p.add_argument("--flow-alone", action="store_true",
                   help="each warm pass first solved with its couplings frozen")
    p.add_argument("--freeze", default="",
                   help="couplings held after their first update (comma-separated names)")
    args = p.parse_args(argv)

    from _common import to_toml

    import hotroll.fem.nonlinear as NL
    import hotroll.solvers.couplings as C
    import hotroll.solvers.steady as S
    from hotroll.cli import app
    from hotroll.fem.forms import NonlinearProblem

    log: list[str] = []

    def step(system, it, update, alpha, r0, r1):
        if isinstance(system, NonlinearProblem):        # the flow's, not the heat equation's
            log.append(f"L({update:.0e},{alpha:g})")

    NL.TRACE = step
    classes = (C.StrainTransport, C.Temperature, C.AfEstimate, C.FreeSurface, C.ContactEnd,
               C.RollFlattening, C.TandemSpeed)
    frozen = {n for n in args.freeze.split(",") if n}
    unknown = frozen - {cls.name for cls in classes}
    if unknown:
        p.error(f"--freeze: unknown coupling(s) {sorted(unknown)}")
    for cls in classes:
        def traced(orig, name, hold):
            def update(self, res):
                if hold and getattr(self, "_held", False):
                    return 0.0            # a new solve builds new coupling objects
                change = orig(self, res)
                log.append(f"{name[:2]}{change:.2g}")
                if hold:
                    self._held = True
                    return 0.0
                return change
            return update
        cls.update = traced(cls.update, cls.name, cls.name in frozen)
    run = S.SteadyRun.run

    def traced_run(self, *a, **k):
        warm = k.get("warm", a[1] if len(a) > 1 else None)
        if args.flow_alone and hasattr(warm, "apply"):
            from dataclasses import replace

            settings = self.s
            self.s = replace(settings, couple_below_warm=0.0)   # the couplings never update
            log.clear()
            t0 = time.perf_counter()
            out = run(self, *a, **k)
            print(f"{self.problem.rp.u_roll:.3f} m/s  {time.perf_counter() - t0:.2f} s  "
                  f"flow alone, {sum(1 for e in log if e[0] == 'L')} Newton: {' '.join(log)}",
                  flush=True)
            self.s = settings
        log.clear()
        t0 = time.perf_counter()
        out = run(self, *a, **k)
        steps = sum(1 for e in log if e[0] == "L")
        print(f"{self.problem.rp.u_roll:.3f} m/s  {time.perf_counter() - t0:.2f} s  "
              f"{steps} Newton: {' '.join(log)}", flush=True)
        return out

    S.SteadyRun.run = traced_run
    if args.case is not None:
        with tempfile.TemporaryDirectory() as tmp:
            app(["run", str(args.case), "--out", str(Path(tmp) / "out"), "--no-figures"],
                standalone_mode=False)
        return 0
    if args.example is not None:
        with tempfile.TemporaryDirectory() as tmp:
            app(["example", args.example, "--out", str(Path(tmp) / "out")], standalone_mode=False)
        return 0
    data = tomllib.loads(args.schedule.read_text())
    if args.passes:
        data["pass"] = data["pass"][: args.passes]
    data.setdefault("output", {}).update(figures=False, vtk=False)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "schedule.toml"
        path.write_text(to_toml(data))
        t0 = time.perf_counter()
        app(["schedule", str(path), "--out", str(Path(tmp) / "out"), "--no-figures"],
            standalone_mode=False)
        print(f"whole schedule: {time.perf_counter() - t0:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
