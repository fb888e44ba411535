"""The bundled finishing mill with recrystallisation kinetics against no and full softening
(issue 33; docs/validation/microstructure.md).

Rolls finishing_mill_microstructure (Hodgson and Gibbs' kinetics), and the same schedule
without a model with strain_retained = 1 (no softening) and 0 (full softening), at its own
entry temperature (1050 degC) and again entering at 950 degC; prints the Markdown tables of
forces and microstructure per stand.

    python scripts/microstructure_compare.py --out results/ms_compare     # about 3 minutes
"""
from __future__ import annotations

import argparse
import copy
import tomllib
from pathlib import Path

from hotroll.config.schedule import schedule_from_dict
from hotroll.examples import schedule_path
from hotroll.workflows.schedule import run_schedule


def variant(base: dict, kinetics: bool, retained: float | None, T: float | None) -> dict:
    d = copy.deepcopy(base)
    if not kinetics:
        d.pop("microstructure", None)
        for p in d["pass"]:
            if "transport" in p:
                p["transport"]["strain_retained"] = retained
    if T is not None:
        d["strip"]["temperature"] = T
    return d


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("results/ms_compare"))
    args = ap.parse_args()
    base = tomllib.loads(schedule_path("finishing_mill_microstructure").read_text())
    runs = {}
    for T, label in ((None, "1050"), (1223.15, "950")):
        for name, kin, ret in (("none", False, 1.0), ("full", False, 0.0), ("kinetics", True,
                                                                            None)):
            if label == "950" and name == "none":
                continue
            sch = schedule_from_dict(variant(base, kin, ret, T), f"{name}_{label}")
            runs[(label, name)] = run_schedule(sch, args.out / f"{name}_{label}", figure=True)
    for label in ("1050", "950"):
        names = [n for n in ("none", "full", "kinetics") if (label, n) in runs]
        print(f"\nEntry {label} degC: force per unit width (MN/m) and the kinetics' figures\n")
        print("| stand | " + " | ".join(f"F {n}" for n in names) + " | kinetics / full | "
              "DRX share | X mean | X surface | d mean (um) | d surface (um) | d centre (um) |"
              " retained strain mean | mechanism surface / centre |")
        print("|" + "---|" * (len(names) + 9))
        for i, k in enumerate(runs[(label, "kinetics")]):
            f = [runs[(label, n)][i]["roll_force"] for n in names]
            cells = [k["name"]] + [f"{1e-6 * x:.3f}" for x in f]
            cells.append(f"{f[-1] / f[names.index('full')] - 1:+.2%}")
            cells.append(f"{k['drx_onset_share']:.2f}")
            if "recrystallised_fraction_mean" in k:
                cells += [f"{k['recrystallised_fraction_mean']:.4f}",
                          f"{k['recrystallised_fraction_surface']:.4f}",
                          f"{1e6 * k['grain_size_mean']:.1f}",
                          f"{1e6 * k['grain_size_surface']:.1f}",
                          f"{1e6 * k['grain_size_centre']:.1f}",
                          f"{k['retained_strain_mean']:.4f}",
                          f"{k['mechanism_surface']} / {k['mechanism_centre']}"]
            else:
                cells += ["-"] * 7
            print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
