"""The report's page of one run (``hotroll report DIR``): what the run's files say, for a person.

Read from the directory only (no solver, no case schema): ``summary.json`` (figures and their
SI units), ``case.toml`` (the case as run; each key's unit from the ``[unit]`` in its comment),
the ``fig_*.png`` figures, and a slab-theory comparison where ``hotroll compare`` wrote one
(``compare.json`` beside the FE run ``fe/``). Numbers are shown in an engineer's unit (MN/m,
kN m/m, MPa, mm, degrees C, %) next to the SI value.
"""
from __future__ import annotations

import json
import math
import re
import tomllib
from pathlib import Path

from hotroll.results.neutral import LABEL, Neutral
from hotroll.results.run_dir import RunDir
from hotroll.results.summary import Summary
from hotroll.results.units import UNITS

#: Summary keys of the table, by group (the remaining numbers follow under "other"), and their
#: labels: both declared with the keys (``results/summary.py``).
GROUPS = Summary.groups()
LABELS = Summary.labels()
#: Dimensionless ratios shown in percent.
PERCENT = ("forward_slip", "balance_error", "power_balance_error", "mass_flux_error",
           "heat_balance_error", "penalty_share", "free_top_force_share", "reduction",
           "exit_correction_normal_force_change", "transport_balance_error")
#: (factor, unit) steps for an SI unit, the largest the magnitude reaches is used.
PREFIXES = {
    "N/m": ((1e6, "MN/m"), (1e3, "kN/m")), "N": ((1e6, "MN"), (1e3, "kN")),
    "N m/m": ((1e6, "MN m/m"), (1e3, "kN m/m")), "N m": ((1e6, "MN m"), (1e3, "kN m")),
    "W/m": ((1e6, "MW/m"), (1e3, "kW/m")), "W": ((1e6, "MW"), (1e3, "kW")),
    "Pa": ((1e6, "MPa"), (1e3, "kPa")), "J/m^2": ((1e6, "MJ/m^2"), (1e3, "kJ/m^2")),
    "B": ((1e9, "GB"), (1e6, "MB"), (1e3, "kB")),
}
#: Limits above which a check becomes a warning (docs/testing.md; the force balance at 10 x
#: the tests' 1e-4: a coarse pass reaches 2e-4, immaterial to its force).
LIMITS = {"mass_flux_error": 0.01, "balance_error": 1e-3, "power_balance_error": 0.01,
          "heat_balance_error": 0.01}


def number(v: float) -> str:
    """About four significant digits; exponent form outside 1e-3 .. 1e6."""
    if v == 0:
        return "0"
    return f"{v:.4g}" if 1e-3 <= abs(v) < 1e6 else f"{v:.3e}"


def finite(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def scale(key: str, unit: str, magnitude: float) -> tuple[float, float, str]:
    """(factor, offset, unit) for showing a value of SI ``unit`` (shown = SI / factor - offset)."""
    if key in PERCENT and unit in ("-", ""):
        return 0.01, 0.0, "%"
    if unit == "K":
        return 1.0, 273.15, "°C"
    if unit == "rad":                    # angles and the sticking zone's, in degrees
        return math.pi / 180.0, 0.0, "°"
    if unit == "m" and 0 < magnitude < 1.0:
        return 1e-3, 0.0, "mm"
    for factor, name in PREFIXES.get(unit, ()):
        if magnitude >= factor:
            return factor, 0.0, name
    return 1.0, 0.0, unit


def show(key: str, value, unit: str) -> dict | None:
    """A figure as a row: shown text and unit, SI text and unit; None if not a number."""
    vals = value if isinstance(value, list) else [value]
    if not vals or len(vals) > 3 or not all(finite(v) for v in vals):
        return None
    f, off, shown = scale(key, unit, max(abs(v) for v in vals))
    return {"key": key, "label": LABELS.get(key, key.replace("_", " ")),
            "text": ", ".join(number(v / f - off) for v in vals), "unit": shown,
            "si": ", ".join(f"{v:.6g}" for v in vals), "si_unit": unit,
            "value": repr(float(vals[0])) if len(vals) == 1 else ""}


def unit_of(key: str, units: dict) -> str:
    """A summary key's SI unit: summary.json's ``units``, else results/units.py, else "-"."""
    return units.get(key) or UNITS.get(key) or "-"


def read_json(path: Path) -> dict:
    try:
        data = json.loads(Path(path).read_text())
    except (OSError, ValueError) as e:
        raise ValueError(f"{path}: not readable as JSON ({e})") from None
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a JSON object")
    return data


def summary_groups(s: dict) -> list[tuple[str, list[dict]]]:
    """The summary's numbers by group, each row with its units; empty groups left out."""
    units, seen, out = s.get("units") or {}, set(), []
    for name, keys in GROUPS.items():
        rows = [r for k in keys if k in s and (r := show(k, s[k], unit_of(k, units)))]
        seen.update(keys)
        if rows:
            out.append((name, rows))
        if name == "Pass":          # an asymmetric pass: each roll's figures after the pass's
            out += roll_groups(s.get("rolls") or [], units)
    skip = {"exit_code", "roll_centre", "contact_end", "K", "m", "roll_radius"}
    rest = [r for k, v in s.items() if k not in seen and k not in skip
            and (r := show(k, v, unit_of(k, units)))]
    if rest:
        out.append(("Other", rest))
    return out


def roll_groups(rolls: list[dict], units: dict) -> list[tuple[str, list[dict]]]:
    """An asymmetric pass's ``rolls`` entries as groups of rows, one per roll (units from
    summary.json's ``rolls.<key>``)."""
    out = []
    for entry in rolls:
        side, rows = entry.get("side", "?"), []
        for k, v in entry.items():
            r = show(k, v, unit_of(f"rolls.{k}", units))
            if r:
                rows.append({**r, "key": f"rolls.{side}.{k}",
                             "label": f"{side} roll: {k.replace('_', ' ')}"})
        if rows:
            out.append((f"{side.title()} roll", rows))
    return out


def contact_end_text(s: dict) -> str | None:
    """How the contact ends, in words (exact contact, steady solver), or None."""
    kind, p = s.get("contact_end_kind"), s.get("contact_end_pressure")
    if kind == "separation":
        a = s.get("separation_angle")
        return (f"the strip leaves the roll {math.degrees(a):.3g}° ({a:.4g} rad) before the gap, "
                f"where the contact pressure falls to zero; after it the top is free")
    if kind == "recovery":
        return ("the strip follows the rising roll past the gap while it recovers elastically; "
                "the contact ends where its pressure falls to zero")
    if kind == "wrap":
        return ("the strip curls onto the roll and presses on it past the gap; the contact "
                "ends where its pressure falls to zero")
    if kind == "bound":
        return ("the contact's end reached the end of its allowed range (half a contact length "
                "before the gap, or a quarter after it, half for a strip that curls onto it): where the "
                "strip leaves the roll is not "
                "resolved")
    if kind == "gap" and finite(p):
        return f"the contact reaches the roll gap; the pressure there is {p / 1e6:.4g} MPa"
    if kind == "held" and finite(p):
        return (f"bilateral contact: the strip is held to the roll up to the gap; the pressure "
                f"there is {p / 1e6:.4g} MPa")
    return None


def run_warnings(s: dict) -> list[dict]:
    """What a reader must not miss: failure, not steady or settled, contact loss, checks."""
    w = []

    def add(level: str, text: str) -> None:
        w.append({"level": level, "text": text})

    if s.get("failure"):
        add("error", s["failure"] if s.get("not_conserved") or s.get("contact_unresolved")
            else f"the run failed: {s['failure']}")
    if s.get("outlet_driven"):
        add("error", "skids: the outlet penalty drives the strip, no neutral point")
    if not finite(s.get("roll_force")):
        add("error", "the roll force is not a finite number")
    if s.get("steady_state") is False:
        add("error", f"not steady: the run ended with status '{s.get('status')}' before the "
                     f"steady state")
    if s.get("fixed_point_settled") is False:
        res = s.get("surface_residual_h")
        add("error", "free surface not settled: the steady solver's free-surface/a_f fixed "
                     "point did not settle" + (f" (last move {res:.3g} h)" if finite(res) else ""))
    if s.get("converged") is False and not w:
        add("error", f"not converged (status '{s.get('status')}', exit code {s.get('exit_code')})")
    for a, b in s.get("contact_loss") or []:
        add("warn", f"contact loss: the normal stress is tensile from x = {a:.4g} m to "
                    f"{b:.4g} m; the strip would leave the roll there"
            + (" (bilateral contact holds it: [contact] unilateral = true lets it go)"
               if s.get("contact_end_kind") == "held" else ""))
    end = contact_end_text(s)
    if end:
        add("warn" if s.get("contact_end_kind") == "bound" else "info", end)
    neutral = Neutral.from_summary(s)
    if neutral.kind == "sticking":     # a skidding strip: the error above says it
        add("info", neutral.label + (f" ({neutral.reason})" if neutral.reason else ""))
    if (s.get("unconverged_steps_in_window") or 0) > 0:
        add("warn", f"{s['unconverged_steps_in_window']} step(s) of the averaging window did "
                    f"not converge (left out of the means)")
    for key, limit in LIMITS.items():
        v = s.get(key)
        if finite(v) and v > limit:
            add("warn", f"{LABELS.get(key, key)} {100 * v:.3g} % is above {100 * limit:g} %")
    if s.get("warm_start_failed"):
        add("info", "the warm start failed; the case was solved from scratch")
    for text in s.get("warnings") or []:      # the case's plausibility (config/plausibility.py)
        add("warn", text)
    return w


CASE_LINE = re.compile(r"^\s*([A-Za-z_][\w-]*)\s*=.*#\s*(?:= [^;]*;\s*)?(.*?)\s*\[([^\]]*)\]"
                       r"(?:;|\s*$)")


def case_inputs(path: Path) -> tuple[str | None, list[tuple[str, list[dict]]]]:
    """The case file as run: (name, [(section, rows)]), each row key, value, unit, text; the
    units and descriptions from the comments ``# text [unit]; allowed: ...`` the run wrote."""
    text = path.read_text()
    data = tomllib.loads(text)
    notes, section = {}, ""
    for line in text.splitlines():
        if (m := re.match(r"^\s*\[([\w.-]+)\]", line)) and not line.lstrip().startswith("[["):
            section = m.group(1)
        elif m := CASE_LINE.match(line):
            notes[(section, m.group(1))] = (m.group(3), m.group(2))
    out = []
    for sec, table in data.items():
        if not isinstance(table, dict):
            continue
        rows = []
        for key, v in table.items():
            unit, desc = notes.get((sec, key), ("", ""))
            num = isinstance(v, (int, float)) and not isinstance(v, bool)
            rows.append({"key": key, "value": _input_text(v), "num": num,
                         "unit": unit if num or unit not in ("-", "") else "",
                         "text": re.sub(r"^\(omit:[^)]*\)\s*", "", desc)})
        out.append((sec, rows))
    name = data.get("name") if isinstance(data.get("name"), str) else None
    return name, out


def _input_text(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, list):
        if v and all(isinstance(p, list) for p in v) and max(len(p) for p in v) > 8:
            n = {len(p) for p in v}
            width = n.pop() if len(n) == 1 else f"{min(n)} to {max(n)}"
            return f"{len(v)} rows of {width}, the first: {_input_text(v[0])}"
        if v and all(isinstance(p, list) for p in v):
            return f"{len(v)} points: " + ", ".join(
                "(" + ", ".join(_input_text(x) for x in p) + ")" for p in v[:3]) + (
                ", ..." if len(v) > 3 else "")
        if len(v) > 8:                   # a long grid (a cross-section's eta): its ends
            return (f"{len(v)} values: " + ", ".join(_input_text(x) for x in v[:3])
                    + ", ..., " + _input_text(v[-1]))
        return "[" + ", ".join(_input_text(x) for x in v) + "]"
    if isinstance(v, dict):
        return ", ".join(f"{k} = {_input_text(x)}" for k, x in v.items())
    return str(v)


FIGURE_CAPTIONS = {
    "fig_mesh.png": "The mesh on the deformed strip and the roll",
    "fig_sigma_ef.png": "Flow stress over the strip",
    "fig_velocity.png": "Velocity over the strip",
    "fig_contact.png": "Normal and shear stress and slip along the contact",
    "fig_contact_angle.png": "Contact pressure and shear against the roll angle",
    "fig_top.png": "The strip's top surface",
    "fig_history.png": "Convergence history",
    "fig_temperature.png": "Temperature over the strip and at the roll bite",
    "fig_rolls.png": "Both rolls' contact pressure and shear against their angles "
                     "(an asymmetric pass)",
    "fig_exit_profile.png": "The outlet through the thickness: temperature, strain, shear",
    "fig_spread.png": "The 3D pass across the width: the exit section, the width along the "
                      "bite, the contact pressure over the arc and the width",
    "compare.png": "FE and slab theory: contact pressure and shear",
    "schedule.png": "The schedule pass by pass",
}


def run_figures(d: Path) -> list[tuple[str, Path]]:
    """The run's figures in the order ``plot_all`` draws them: (caption, path)."""
    order = list(FIGURE_CAPTIONS)
    pngs = sorted((p for p in d.glob("fig_*.png") if ".tmp" not in p.name), key=lambda p: (
        order.index(p.name) if p.name in order else len(order), p.name))
    return [(FIGURE_CAPTIONS.get(p.name, p.stem.removeprefix("fig_").replace("_", " ")), p)
            for p in pngs]


def compare_context(d: Path) -> dict | None:
    """compare.json's table (FE beside Orowan, Sims, Ford-Alexander) and notes, if written."""
    path = d / "compare.json"
    if not path.is_file():
        return None
    c = read_json(path)
    cols = [k for k in c.get("columns", []) if k not in ("quantity", "unit", "note")]
    rows = [{"quantity": str(r.get("quantity", "")).rsplit(" [", 1)[0], "unit": r.get("unit", ""),
             "cells": [("-" if not finite(r.get(k)) else
                        (f"{r[k]:.3f}" if k == "FE/slab" else number(r[k]))) for k in cols],
             "note": r.get("note") or ""} for r in c.get("rows", [])]
    errors = [f"{k.replace('_error', '').replace('_', '-')}: {c[k]}"
              for k in ("slab_error", "sims_error", "ford_alexander_error") if c.get(k)]
    ratio = next((r.get("FE/slab") for r in c.get("rows", []) if r.get("unit") == "N/m"
                  and str(r.get("quantity", "")).startswith("roll force")), None)
    return {"columns": cols, "rows": rows, "errors": errors,
            "force_ratio": f"{ratio:.3f}" if finite(ratio) else None, "regimes": c.get("regimes"),
            "friction": c.get("slab_friction"), "figure": d / "compare.png"}


def run_context(d: Path) -> dict:
    """Everything the run page shows (``templates/report.html.j2``, kind "run")."""
    d = Path(d)
    compare_dir = d if (d / "compare.json").is_file() else (
        d.parent if d.name == "fe" and (d.parent / "compare.json").is_file() else None)
    run_dir = d / "fe" if compare_dir == d else d
    s = RunDir(run_dir).summary()
    name, inputs = (case_inputs(run_dir / "case.toml") if (run_dir / "case.toml").is_file()
                    else (None, []))
    compare = compare_context(compare_dir) if compare_dir is not None else None
    figures = run_figures(run_dir)
    if compare and compare["figure"].is_file():
        figures.append((FIGURE_CAPTIONS["compare.png"], compare["figure"]))
    code = s.get("exit_code")
    ok = code == 0 or (code is None and s.get("converged"))
    headline = [r for k in HEADLINE
                if k in s and (r := show(k, s[k], unit_of(k, s.get("units") or {})))]
    headline.append(neutral_card(s))
    return {"kind": "run", "title": s.get("case_name") or name or d.name,
            "status": s.get("status"), "exit_code": code, "ok": bool(ok),
            "facts": _facts(s), "headline": headline, "groups": summary_groups(s),
            "inputs": inputs, "compare": compare, "figures": figures,
            "warnings": run_warnings(s), "run_dir": run_dir}


#: The page's key figures (those the summary has), then the neutral point's card.
HEADLINE = ("roll_force", "roll_force_total", "roll_torque", "roll_power", "forward_slip",
            "contact_length", "spread", "exit_width", "exit_temperature_mean")


def neutral_card(s: dict) -> dict:
    """The neutral point's key figure, as the summary tells it (``results/neutral.py``): its
    angle in degrees and the story below (degrees and radians, a sticking stretch around it),
    or "none" and the sticking zone (or why)."""
    n = Neutral.from_summary(s)
    card = {"key": "neutral", "label": LABEL, "value": ""}
    if n.kind == "point":
        return card | {"text": number(n.angle_deg), "unit": "°", "si": n.text, "si_unit": "",
                       "value": repr(n.angle)}
    return card | {"text": "none", "unit": "", "si": n.text.removeprefix("none: "),
                   "si_unit": ""}


def _facts(s: dict) -> list[tuple[str, str]]:
    """The run's words: method, status, laws (text and yes/no fields)."""
    keys = ("method", "status", "converged", "steady_state", "fixed_point_settled",
            "free_surface", "friction_law", "nonlinear", "thermal", "warm_start_from")
    out = []
    for k in keys:
        v = s.get(k)
        if v is None:
            continue
        out.append((k.replace("_", " "), ("yes" if v else "no") if isinstance(v, bool) else str(v)))
    return out
