"""One schedule three ways (issue 17): hotroll's own schedule, PyRolL with the hotroll plugin,
and PyRolL with its own force/torque and thermal plugins; a table per pass.

    python scripts/pyroll_compare.py [--schedule finishing_mill] [--out results/pyroll_compare]

(a) ``hotroll schedule``: the FE pass, profiles of temperature and strain handed from pass to
    pass, tandem mass flow, interpass cooling through the thickness; the strain reset to 0
    in the transports (``strain_retained = 0``) as PyRolL's Transport does.
(b) PyRolL 3 (pyroll-core) with ``import hotroll.pyroll``: the same FE pass per roll pass, the
    roll speeds and transport times of (a), PyRolL's state between units (mean temperature,
    strain reset to 0 by its Transport), the plugin's transport cooling of the mean.
(c) PyRolL with pyroll-lippmann-mahrenholz-force-torque (slab-type force and torque) and
    pyroll-integral-thermal (lumped heat balance of passes and transports), with the flow
    stress of pyroll-freiberg-flow-stress (Spittel's coefficients at strain + 0.1 and rate +
    0.1), as a PyRolL user would run it; and (c') the same models with hotroll's flow stress
    (the same S355J2 law as (a) and (b)), which separates the models from the flow stress.

Every PyRolL variant runs in its own process (a plugin cannot be unloaded). The schedule's
thermal data are given to PyRolL's thermal plugin (roll contact heat transfer, roll
temperature, air convection and emissivity, the share of plastic work that heats). Needs the
extras: ``pip install -e '.[pyroll-compare]'``.
"""
from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _schedule(name: str):
    from hotroll.config.schedule import load_schedule
    from hotroll.examples import schedule_path

    path = Path(name)
    return load_schedule(path if path.exists() else schedule_path(name))


def run_hotroll(sch, out: Path) -> list[dict]:
    from hotroll.workflows.schedule import run_schedule

    sch.output.figures = False
    for p in sch.passes:            # as PyRolL's Transport: full recrystallisation
        if p.transport is not None:
            p.transport.strain_retained = 0.0
    # solved afresh: a resumed run reused the passes of an earlier one and its wall time
    # read 0.0 s in the comparison (session 6)
    return run_schedule(sch, out / "hotroll", resume=False)


def run_pyroll(sch, plan: list[dict], variant: str) -> list[dict]:
    """The schedule in a PyRolL PassSequence: speeds and transport times from ``plan``."""
    import pyroll.core as pr

    if variant == "plugin":
        import hotroll.pyroll as hp

        hp.Config.FRICTION = sch.friction.model_dump(exclude_none=True)
        hp.Config.THERMAL = {k: getattr(sch.thermal, k) for k in
                             ("htc_contact", "roll_temperature", "htc_air", "emissivity",
                              "ambient_temperature")}
        hp.Config.PROPERTIES = {"density": sch.material.density,
                                "specific_heat": sch.material.specific_heat,
                                "conductivity": sch.material.conductivity}
    else:
        import pyroll.integral_thermal  # noqa: F401
        import pyroll.lippmann_mahrenholz_force_torque  # noqa: F401

        if variant == "pyroll":
            import pyroll.freiberg_flow_stress  # noqa: F401
        else:                                  # hotroll's flow stress as PyRolL's
            from pyroll.core import DeformationUnit

            law = sch.material.flow_stress()

            @DeformationUnit.Profile.flow_stress
            def hotroll_flow_stress(self):
                return float(law.sigma(self.strain, self.unit.strain_rate, self.temperature))

    th, st = sch.thermal, sch.strip
    width = st.width or 1.0
    units = []
    for k, (p, row) in enumerate(zip(sch.passes, plan)):
        R = p.roll_radius
        units.append(pr.RollPass(
            label=row["name"], gap=p.exit_thickness, rotation=False,
            coulomb_friction_coefficient=sch.friction.mu or 0.3,
            deformation_heat_efficiency=th.taylor_quinney,
            roll=pr.Roll(groove=pr.FlatGroove(usable_width=width), nominal_radius=R,
                         rotational_frequency=row["roll_surface_speed"] / (2 * math.pi * R),
                         temperature=th.roll_temperature,
                         contact_heat_transfer_coefficient=th.htc_contact)))
        if "transport_duration" in row:
            tr = p.transport
            units.append(pr.Transport(
                label=f"T{k + 1}", duration=row["transport_duration"],
                environment_temperature=th.ambient_temperature,
                convection_heat_transfer_coefficient=th.htc_air if tr.htc_air is None
                else tr.htc_air,
                relative_radiation_coefficient=th.emissivity if tr.emissivity is None
                else tr.emissivity))
    seq = pr.PassSequence(units)
    ip = pr.Profile.box(height=st.thickness, width=width, temperature=st.temperature,
                        strain=st.strain, material=sch.material.grade or "S355J2",
                        density=sch.material.density,
                        specific_heat_capacity=sch.material.specific_heat,
                        thermal_conductivity=sch.material.conductivity)
    import time

    t0 = time.perf_counter()
    seq.solve(ip)
    wall = time.perf_counter() - t0
    rows = []
    for u in seq.units:
        if isinstance(u, pr.RollPass):
            rows.append({"name": u.label, "roll_force_total": float(u.roll_force),
                         "roll_torque_total": float(u.roll.roll_torque),
                         "entry_temperature": float(u.in_profile.temperature),
                         "exit_temperature": float(u.out_profile.temperature),
                         "exit_strain": float(u.out_profile.strain),
                         "exit_velocity": float(u.out_profile.velocity)})
    rows.append({"stats": dict(hp.STATS) if variant == "plugin" else {}, "wall_time": wall})
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--schedule", default="finishing_mill")
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "pyroll_compare")
    ap.add_argument("--variant", choices=["plugin", "pyroll", "pyroll_hotroll_law"],
                    help=argparse.SUPPRESS)   # one PyRolL variant (a subprocess of main)
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    sch = _schedule(args.schedule)
    plan_file = args.out / "hotroll_rows.json"
    if args.variant:
        plan = json.loads(plan_file.read_text())
        rows = run_pyroll(sch, plan, args.variant)
        (args.out / f"{args.variant}.json").write_text(json.dumps(rows, indent=1))
        return 0
    plan = run_hotroll(sch, args.out)
    plan_file.write_text(json.dumps(plan, indent=1))
    for variant in ("plugin", "pyroll", "pyroll_hotroll_law"):
        proc = subprocess.run([sys.executable, __file__, "--schedule", args.schedule,
                               "--out", str(args.out), "--variant", variant],
                              capture_output=True, text=True)
        if proc.returncode != 0:
            raise SystemExit(f"{variant}: {proc.stderr.strip()[-1500:]}")
    results = {v: json.loads((args.out / f"{v}.json").read_text())
               for v in ("plugin", "pyroll", "pyroll_hotroll_law")}
    table = _table(sch, plan, results)
    (args.out / "compare.md").write_text(table)
    print(table)
    return 0


def _table(sch, plan, results) -> str:
    width = sch.strip.width or 1.0
    b, c, c2 = (results[v] for v in ("plugin", "pyroll", "pyroll_hotroll_law"))
    stats, walls = b[-1]["stats"], [r[-1]["wall_time"] for r in (b, c, c2)]
    lines = [
        f"Schedule {sch.name}: (a) hotroll schedule, (b) PyRolL + hotroll plugin, (c) PyRolL + "
        f"Lippmann-Mahrenholz + integral-thermal with Freiberg's flow stress, (c') the same "
        f"with hotroll's flow stress. Whole width {width:g} m, force per roll, torque per roll.",
        "",
        "| pass | force MN (a) / (b) / (c) / (c') | torque kN m (a) / (b) / (c) / (c') | "
        "entry T K (a) / (b) / (c) / (c') | exit T K (a) / (b) / (c) / (c') | "
        "exit strain (a) / (b) / (c) |",
        "|---|---|---|---|---|---|"]
    for r, rb, rc, rc2 in zip(plan, b, c, c2):
        F = [r["roll_force"] * width, rb["roll_force_total"], rc["roll_force_total"],
             rc2["roll_force_total"]]
        M = [r["roll_torque"] * width, rb["roll_torque_total"], rc["roll_torque_total"],
             rc2["roll_torque_total"]]
        lines.append(
            f"| {r['name']} | " + " / ".join(f"{1e-6 * f:.2f}" for f in F)
            + " | " + " / ".join(f"{1e-3 * m:.0f}" for m in M)
            + f" | {r['entry_temperature_mean']:.1f} / {rb['entry_temperature']:.1f} / "
              f"{rc['entry_temperature']:.1f} / {rc2['entry_temperature']:.1f}"
            + f" | {r['outlet_temperature_mean']:.1f} / {rb['exit_temperature']:.1f} / "
              f"{rc['exit_temperature']:.1f} / {rc2['exit_temperature']:.1f}"
            + f" | {r['exit_strain_mean']:.3f} / {rb['exit_strain']:.3f} / "
              f"{rc['exit_strain']:.3f} |")
    t_a = sum(r["wall_time"] for r in plan)
    lines += ["", f"Wall time of the six passes (s): (a) {t_a:.1f}, (b) {walls[0]:.1f} "
              f"(PassSequence.solve; {stats['fe_solves']} FE solves, {stats['cache_hits']} "
              f"cache hits), (c) {walls[1]:.2f}, (c') {walls[2]:.2f}."]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(main())
