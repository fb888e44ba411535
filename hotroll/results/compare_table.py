"""The FE-against-slab comparison as text: the table's columns, the notes on regimes and
means, the definitions, and the CSV and Markdown renderings of ``workflows/compare.py``'s
result (compare.csv, compare.md)."""
from __future__ import annotations

import csv
import io

REGIME_NOTE = ("Regimes: Sims (1954) is the thin-strip closed form (sticking friction, small "
               "angles, constant mean flow stress, homogeneous slabs), meant for L/h_mean > ~1. "
               "Ford-Alexander is shown for the thicker passes, L/h_mean < ~1; caveat "
               "(theory/ford_alexander.py): the simplified form used, p_mean/2k = pi/4 + "
               "L/(4 h_mean), is a linearisation of Sims and does not reproduce the load rise "
               "of thick plates (L/h_mean below ~0.5-1, indentation-like deformation). Both "
               "are for sticking friction and are shown whatever the case's friction law.")

SIMS_MEAN_NOTE = ("Sims and Ford-Alexander take the mean uniaxial flow stress along the arc: "
                  "sigma_mean = (1/alpha) int_0^alpha sigma_f(strain(phi), strain_rate(phi), T) "
                  "dphi (mean over the roll angle) along the slab's homogeneous-compression path "
                  "(strain = entry_strain + 2/sqrt3 ln(h0/h), strain rate = 2/sqrt3 v |dh/dx| / h "
                  "with v = v1 h1/h, v1 the slab's exit speed, or omega R if the slab solve "
                  "failed); 2k = 2 sigma_mean/sqrt3.")


# ----------------------------------------------------------------------------- mapping

COLUMNS = ["quantity", "unit", "FE", "slab (Orowan)", "Sims", "Ford-Alexander", "FE/slab", "note"]


def number_text(v) -> str:
    if v is None:
        return "-"
    if v == 0.0:
        return "0"
    a = abs(v)
    return f"{v:.4g}" if 1e-3 <= a < 1e5 else f"{v:.4e}"


def csv_text(rows: list[dict]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(COLUMNS)
    for r in rows:
        w.writerow(["" if r[c] is None else (repr(r[c]) if isinstance(r[c], float) else r[c])
                    for c in COLUMNS])
    return buf.getvalue()


def md_text(case, result: dict) -> str:
    rows, s = result["rows"], result["inputs"]
    head = "| " + " | ".join(COLUMNS) + " |"
    lines = [f"# FE versus slab theory: {case.name}", "",
             "Per unit width, SI units (unit of each row in its label). FE: hotroll "
             f"({result['fe']['method']} solver, status {result['fe']['status']}, converged "
             f"{result['fe']['converged']}, h_contact = {result['fe']['h_contact']:.4g} m), "
             f"files in `fe/`.", "",
             head, "|" + "---|" * len(COLUMNS)]
    for r in rows:
        lines.append("| " + " | ".join(
            [r["quantity"], r["unit"]] + [number_text(r[c]) for c in COLUMNS[2:7]] + [r["note"]]) + " |")
    lines += ["", "## Inputs of the theory (mapped from the case)", ""]
    lines += [f"- roll radius R = {s['roll_radius_m']:g} m; thicknesses (full) h0 = "
              f"{s['h0_m (full)']:g} m, h1 = {s['h1_m (full)']:g} m; roll surface speed "
              f"omega R = {s['roll_speed_m_per_s (omega R)']:g} m/s",
              f"- tensions: back {s['back_tension_Pa']:g} Pa, front {s['front_tension_Pa']:g} Pa "
              "(slab only; Sims and Ford-Alexander have none)",
              f"- flow stress: the case's law, sigma_f(strain, strain rate, T) in Pa "
              f"({law_text(s['flow_stress'])}), T = {s['temperature_K']:g} K, entry strain "
              f"{s['entry_strain']:g}",
              f"- slab friction: {result['slab_friction']}",
              f"- {SIMS_MEAN_NOTE}",
              f"- {REGIME_NOTE}"]
    if result["slab_error"]:
        lines += ["", f"**Slab (Orowan) not solved:** {result['slab_error']}"]
    for key in ("sims_error", "ford_alexander_error"):
        if result.get(key):
            lines += ["", f"**{key.split('_error')[0]} not evaluated:** {result[key]}"]
    lines += ["", "## Definitions (checked in the code)", ""] + [f"- {d}" for d in DEFINITIONS]
    return "\n".join(lines) + "\n"


def law_text(d) -> str:
    if isinstance(d, dict):
        keys = [k for k in d if k not in ("validity", "units")]
        return ", ".join(f"{k} = {d[k]}" for k in keys)
    return str(d)


DEFINITIONS = [
    "FE roll force = summary.json `roll_force` = -int T_y ds over the upper roll contact "
    "(fem/quantities.py `integrals`, docs/theory.md 4.2): the vertical force of the upper roll "
    "on the strip. The FE models the upper half strip, which is all the upper roll touches, so "
    "this is one roll's separating force; the slab `force` is the same (vertical force on one "
    "roll, R int (p cos phi - s tau sin phi) dphi). No factor 2.",
    "FE roll torque = `roll_torque` = int tau r ds of the upper roll; slab `torque` = "
    "R^2 int (-s) tau dphi per roll. FE `roll_power` is one roll; slab `power` is both rolls "
    "(the table halves it).",
    "Neutral angle: both from the roll's vertical centre line, positive towards the entry; "
    "the FE's none (-) where its arc sticks and the slip's sign is noise (summary.json "
    "`neutral` says so, docs/theory.md 1e). "
    "Forward slip: both (v_exit - omega R)/(omega R); the slab's is h_n cos(phi_n)/h1 - 1 "
    "(uniform velocity over the section at the neutral point), the FE's the mean exit velocity.",
    "FE pressure = -normal_stress of contact.csv (the contact penalty's reaction, Pa, negative "
    "= compressive, written as positive pressure here); the peak is taken from "
    "`normal_stress_smooth` (P1 projection along the arc); the raw nodal peak is a separate row.",
    "Mean pressure = roll force / projected contact length (FE: the x extent of its contact, "
    "which starts where the free entry top meets the roll).",
]
