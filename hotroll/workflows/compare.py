"""FE versus classical rolling theory for one pass: ``hotroll compare CASE.toml --out DIR``.

:func:`run_compare` runs the FE model (``runner.run_case`` into ``DIR/fe``), solves the same pass
with the slab theory of :mod:`hotroll.theory` (Orowan's equation, plus Sims' and Ford &
Alexander's closed forms) and writes ``DIR/compare.csv``, ``compare.md``, ``compare.json`` and
the figure ``compare.png``.

Same quantities, checked definitions (per unit width, SI):

* roll force: FE ``roll_force`` = -int T_y ds over the upper roll contact = the vertical force
  of the upper roll on the strip (``fem/quantities.py: integrals``, docs/theory.md 4.2). The FE
  is the upper half strip, but the upper roll touches only that half, so this is the whole
  force of one roll = the roll separating force. Slab ``force`` = R int (p cos phi -
  s tau sin phi) dphi = the vertical force on one roll (separating force). Same quantity,
  no factor 2.
* roll torque: FE ``roll_torque`` = int tau r ds of the upper roll (one roll); slab ``torque``
  = R^2 int (-s) tau dphi per roll. Same quantity. Roll power: FE ``roll_power`` is one roll;
  slab ``power`` is both rolls (2 T U / R), so the table shows slab ``power / 2``.
* neutral angle: both from the roll's vertical centre line (line of roll centres), positive
  towards the entry (``RollPass.angle``; slab phi with 0 at the exit).
* forward slip: both (v_exit - U) / U with U = omega R (FE: mean exit velocity through the exit
  face; slab: h_n cos(phi_n) / h1 - 1, uniform velocity over the section).
* thicknesses: the case's ``entry_thickness``, ``exit_thickness`` are FULL thicknesses, which is
  what the slab solver takes (the FE meshes their halves).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

from hotroll.config.case import Case
from hotroll.model.friction import FRICTION_LAWS
from hotroll.model.friction.coulomb import CoulombFriction
from hotroll.results.compare_table import (
    COLUMNS,
    DEFINITIONS,
    REGIME_NOTE,
    SIMS_MEAN_NOTE,
    csv_text,
    md_text,
)
from hotroll.results.figures.slab import plot_compare_profiles
from hotroll.results.output import write_json, write_text
from hotroll.results.run_dir import RunDir
from hotroll.theory import Coulomb, Sticking, Tresca, ford_alexander, sims, solve_pass
from hotroll.workflows.runner import run_case

SQRT3 = math.sqrt(3.0)

#: Ford & Alexander's simplified formula in ``theory/ford_alexander.py`` and Sims' closed form
#: keep Sims' assumptions (sticking, small angles, a constant mean 2k, homogeneous slabs).
@dataclass(frozen=True)
class SlabInputs:
    """The case mapped onto :func:`hotroll.theory.solve_pass` (SI, full thicknesses)."""

    roll_radius: float
    h0: float
    h1: float
    roll_speed: float
    friction: object
    friction_note: str
    flow_stress: Callable[[float, float, float], float]
    flow_law: object
    temperature: float
    entry_strain: float
    back_tension: float
    front_tension: float

    def describe(self) -> dict:
        law = self.flow_law
        return {"roll_radius_m": self.roll_radius, "h0_m (full)": self.h0,
                "h1_m (full)": self.h1, "roll_speed_m_per_s (omega R)": self.roll_speed,
                "slab_friction": self.friction_note, "friction_object": repr(self.friction),
                "flow_stress": law.describe() if hasattr(law, "describe") else repr(law),
                "temperature_K": self.temperature, "entry_strain": self.entry_strain,
                "back_tension_Pa": self.back_tension, "front_tension_Pa": self.front_tension}


def slab_friction(case: Case):
    """(theory friction object, note) for the case's friction law."""
    fr = case.friction
    form, key = FRICTION_LAWS[fr.law].slab or ("sticking", None)
    if form == "coulomb":
        r = CoulombFriction.rounding  # the FE's rounded kinks: the slab solves the same law
        return Coulomb(fr.mu, rounding=r), (f"coulomb mu = {fr.mu:g} (tau = min(mu p, k), "
                                            f"its kinks rounded over {r:g} k as the FE)")
    if form == "tresca":
        return Tresca(getattr(fr, key)), (f"tresca factor = {getattr(fr, key):g} (tau = factor k,"
                                          " as the FE)")
    if fr.law == "viscoplastic" and fr.a_f == "estimate":
        return Sticking(), ("sticking (no slab form of the viscoplastic law; the estimated a_f "
                            "(3.15) sticks the whole arc, so sticking is its slab counterpart)")
    return Sticking(), f"sticking (no slab form of the {fr.law} law)"


def map_case(case: Case) -> SlabInputs:
    """Map a case onto the slab solver's inputs."""
    p, law = case.pass_, case.material.flow_stress()
    friction, note = slab_friction(case)

    def flow_stress(strain: float, strain_rate: float, temperature: float) -> float:
        return float(law.sigma(strain, strain_rate, temperature))

    return SlabInputs(roll_radius=p.roll_radius, h0=p.entry_thickness, h1=p.exit_thickness,
                      roll_speed=p.roll_surface_speed, friction=friction, friction_note=note,
                      flow_stress=flow_stress, flow_law=law,
                      temperature=getattr(case.plate, "temperature", 1373.15),
                      entry_strain=getattr(case.plate, "entry_strain", 0.0),
                      back_tension=p.back_tension, front_tension=p.front_tension)


def arc_mean_flow_stress(s: SlabInputs, exit_speed: float | None = None, n: int = 2001) -> float:
    """Mean uniaxial flow stress over the roll angle along the slab's path (Pa), see
    ``SIMS_MEAN_NOTE``; ``exit_speed`` v1 (default: the roll speed, no slip)."""
    R, h0, h1 = s.roll_radius, s.h0, s.h1
    v1 = s.roll_speed if exit_speed is None else exit_speed
    alpha = math.acos(1.0 - (h0 - h1) / (2.0 * R))
    phi = np.linspace(0.0, alpha, n)
    h = h1 + 2.0 * R * (1.0 - np.cos(phi))
    strain = s.entry_strain + 2.0 / SQRT3 * np.log(h0 / h)
    rate = 2.0 / SQRT3 * (v1 * h1 / h) * 2.0 * np.tan(phi) / h
    sig = np.array([s.flow_stress(e, r, s.temperature) for e, r in zip(strain, rate)])
    return float(np.trapezoid(sig, phi) / alpha)


def run_theory(case: Case) -> dict:
    """Slab (Orowan), Sims and Ford-Alexander for the case; a slab failure is recorded."""
    s = map_case(case)
    out: dict = {"inputs": s, "slab": None, "slab_error": None, "sims": None,
                 "sims_error": None, "ford_alexander": None, "ford_alexander_error": None}
    try:
        out["slab"] = solve_pass(s.roll_radius, s.h0, s.h1, s.roll_speed, s.friction,
                                 s.flow_stress, s.temperature, entry_strain=s.entry_strain,
                                 back_tension=s.back_tension, front_tension=s.front_tension)
    except Exception as e:  # NoNeutralPointError (skids), ValueError (tension), RuntimeError
        out["slab_error"] = f"{type(e).__name__}: {e}"
    v1 = out["slab"].exit_speed if out["slab"] is not None else None
    sf = arc_mean_flow_stress(s, v1)
    out["mean_flow_stress"] = sf
    for key, fn in (("sims", sims), ("ford_alexander", ford_alexander)):
        try:
            out[key] = fn(s.roll_radius, s.h0, s.h1, sf)
        except Exception as e:
            out[f"{key}_error"] = f"{type(e).__name__}: {e}"
    return out


# ----------------------------------------------------------------------------- FE side
def fe_quantities(summary: dict, contact: dict | None, h_contact: float) -> dict:
    """Scalar FE figures for the table (SI), from summary.json and contact.csv."""
    q = {"roll_force": summary.get("roll_force"), "roll_torque": summary.get("roll_torque"),
         "roll_power": summary.get("roll_power"), "neutral_angle": summary.get("neutral_angle"),
         "forward_slip": summary.get("forward_slip"),
         "contact_arc_length": summary.get("contact_length")}
    nan = math.nan
    q.update(peak_smooth=nan, peak_raw=nan, peak_interior=nan, projected_length=nan,
             contact_start_angle=nan, peak_source="none")
    if contact is not None and len(contact.get("x", [])):
        raw = -contact["normal_stress"]                     # compressive pressure > 0
        smooth = -contact["normal_stress_smooth"] if "normal_stress_smooth" in contact else None
        q["peak_raw"] = float(np.max(raw))
        prof = smooth if smooth is not None else raw
        q["peak_source"] = "normal_stress_smooth" if smooth is not None else "normal_stress (raw)"
        q["peak_smooth"] = float(np.max(prof))
        xy = np.stack([contact["x"], contact["y"]], -1)
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))])
        away = s >= 2.0 * h_contact                         # beyond 2h from the first contact
        q["peak_interior"] = float(np.max(prof[away])) if away.any() else nan
        q["projected_length"] = float(np.max(contact["x"]) - np.min(contact["x"]))
        q["contact_start_angle"] = float(np.max(contact["angle"]))
    return q


# ----------------------------------------------------------------------------- table
def _f(v):
    if v is None:
        return None
    try:
        v = float(v)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def build_table(case: Case, fe: dict, th: dict) -> list[dict]:
    """Rows = quantities; columns ``COLUMNS``. Missing values are None."""
    s, slab, si, fa = th["inputs"], th["slab"], th["sims"], th["ford_alexander"]
    h_mean = 0.5 * (s.h0 + s.h1)
    U, R = s.roll_speed, s.roll_radius
    g = lambda obj, attr, scale=1.0: None if obj is None else _f(getattr(obj, attr)) * scale  # noqa
    rows = []

    def row(name, unit, fe_v, slab_v, sims_v=None, fa_v=None, note=""):
        fe_v, slab_v, sims_v, fa_v = _f(fe_v), _f(slab_v), _f(sims_v), _f(fa_v)
        ratio = fe_v / slab_v if fe_v is not None and slab_v not in (None, 0.0) else None
        rows.append(dict(zip(COLUMNS, [f"{name} [{unit}]", unit, fe_v, slab_v, sims_v, fa_v,
                                       ratio, note])))

    F = fe["roll_force"]
    row("roll force per unit width", "N/m", F, g(slab, "force"), g(si, "force"), g(fa, "force"),
        "separating force of one roll (FE: upper roll on the strip)")
    row("roll force per unit width", "MN/m", None if F is None else F / 1e6,
        g(slab, "force", 1e-6), g(si, "force", 1e-6), g(fa, "force", 1e-6))
    row("roll torque per roll", "N m/m", fe["roll_torque"], g(slab, "torque"),
        g(si, "torque"), None, "shear moment about the roll axis, one roll")
    row("roll power per roll", "W/m", fe["roll_power"], g(slab, "power", 0.5),
        None if si is None else si.torque * U / R, None, "slab power / 2 (it is both rolls)")
    row("neutral angle", "rad", fe["neutral_angle"], g(slab, "neutral_angle"),
        g(si, "neutral_angle"), None, "from the roll's vertical centre line, + towards entry")
    row("forward slip", "%", None if fe["forward_slip"] is None else 100 * fe["forward_slip"],
        g(slab, "forward_slip", 100.0), g(si, "forward_slip", 100.0), None,
        "(v_exit - omega R)/(omega R)")
    row("peak pressure", "Pa", fe["peak_smooth"], g(slab, "peak_pressure"), None, None,
        f"FE: max of {fe['peak_source']} (P1 projection along the arc)")
    row("peak pressure", "MPa", fe["peak_smooth"] * 1e-6, g(slab, "peak_pressure", 1e-6),
        None, None, f"FE: max of {fe['peak_source']}")
    row("peak pressure, raw nodal FE", "MPa", fe["peak_raw"] * 1e-6,
        g(slab, "peak_pressure", 1e-6), None, None,
        "FE: max of the raw nodal penalty reaction (spikes at the first contact node)")
    row("peak pressure beyond 2h from the contact start", "MPa", fe["peak_interior"] * 1e-6,
        g(slab, "peak_pressure", 1e-6), None, None,
        "FE smoothed, the entry corner (first 2 h of arc) left out; mesh-dependent there")
    Lfe = fe["projected_length"]
    row("mean pressure over the projected contact length", "MPa",
        None if F is None or not Lfe else F / Lfe * 1e-6, g(slab, "mean_pressure", 1e-6),
        g(si, "mean_pressure", 1e-6), g(fa, "mean_pressure", 1e-6), "roll force / L")
    L_slab = s.roll_radius * math.sin(math.acos(1.0 - (s.h0 - s.h1) / (2.0 * s.roll_radius)))
    L_small = math.sqrt(s.roll_radius * (s.h0 - s.h1))
    row("projected contact length L", "m", Lfe, L_slab, L_small, L_small,
        "FE: x extent of the contact (free entry top); slab R sin(alpha); Sims/FA sqrt(R dh)")
    row("contact arc length", "m", fe["contact_arc_length"],
        s.roll_radius * math.acos(1.0 - (s.h0 - s.h1) / (2.0 * s.roll_radius)), None, None,
        "FE: length of the contact boundary; slab R alpha")
    row("L/h_mean", "-", None if not Lfe else Lfe / h_mean, L_slab / h_mean,
        L_small / h_mean, L_small / h_mean, f"h_mean = (h0 + h1)/2 = {h_mean:g} m")
    sf = th["mean_flow_stress"]
    row("mean uniaxial flow stress along the arc", "MPa", None,
        None if slab is None else _slab_mean_flow_stress(slab) * 1e-6, sf * 1e-6, sf * 1e-6,
        "slab: its own local sigma_f (column = its angle mean); Sims/FA: the constant used")
    return rows


def _slab_mean_flow_stress(slab) -> float:
    """Angle mean of the slab solution's uniaxial flow stress (Pa)."""
    sig = np.asarray(slab.plane_strain_flow_stress) * SQRT3 / 2.0
    return float(np.trapezoid(sig, slab.angle) / slab.contact_angle)


def run_compare(case: Case, out: Path, progress=None) -> dict:
    """Run the FE model and the slab theory on ``case``; write compare.csv/.md/.json/.png
    into ``out`` (the FE run in ``out/fe``). Returns the table and its context as a dict."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    summary = run_case(case, out / "fe", progress=progress)
    contact = RunDir(out / "fe").table("contact.csv")
    fe = fe_quantities(summary, contact, float(summary.get("h_contact") or case.mesh.h))
    th = run_theory(case)
    rows = build_table(case, fe, th)
    s = th["inputs"]
    result = {
        "case_name": case.name,
        "rows": rows,
        "columns": COLUMNS,
        "inputs": s.describe(),
        "slab_friction": s.friction_note,
        "slab_error": th["slab_error"],
        "sims_error": th["sims_error"],
        "ford_alexander_error": th["ford_alexander_error"],
        "sims_mean_flow_stress_Pa": th["mean_flow_stress"],
        "sims_mean_flow_stress": SIMS_MEAN_NOTE,
        "regimes": REGIME_NOTE,
        "definitions": DEFINITIONS,
        "fe": {k: summary.get(k) for k in ("method", "status", "converged", "outlet_driven",
                                            "h_contact", "contact_start", "contact_end",
                                            "contact_loss", "wall_time_s")},
        "fe_peak_pressure_source": fe["peak_source"],
        "files": {"fe": "fe/", "csv": "compare.csv", "md": "compare.md", "json": "compare.json",
                  "figure": "compare.png"},
    }

    try:
        plot_compare_profiles(contact, th["slab"], summary, out / "compare.png",
                              title=f"{case.name}: contact pressure and shear, FE vs slab")
    except Exception as e:  # a figure must not lose the table
        result["files"]["figure"] = None
        result["figure_error"] = f"{type(e).__name__}: {e}"
    write_text(out / "compare.csv", csv_text(rows))
    write_text(out / "compare.md", md_text(case, result))

    write_json(out / "compare.json", result)
    return result
