"""FE against slab theory on thin strip: roll force, torque, neutral angle, forward slip.

A grid of passes, each run through ``hotroll.workflows.compare.run_compare`` (steady FE, automatic
mesh, Coulomb friction) beside the slab (Orowan) solution and Sims' closed form. Grid: L/h_mean
in {2, 4, 6} (L = sqrt(R dh), h_mean = (h0 + h1)/2), reduction r = dh/h0 in {0.1, 0.3, 0.5},
Coulomb mu in {0.1, 0.2, 0.3}; one roll radius R (default 0.4 m) and roll surface speed U
(default 3 m/s), so that h0 = R r / ((L/h_mean)^2 (1 - r/2)^2). Material: Norton-Hoff
K = 4e7 Pa s^m, m = 0.15 (106-167 MPa at 10-200 1/s: S355J2's Hensel-Spittel flow stress at
1100 C and strain 0.3 within 3.3 % over that range), or ``--material s355j2`` (the grade).

Passes the friction cannot draw through (FE ``outlet_driven``, slab ``NoNeutralPointError``) are
recorded as "skids". Each case runs into DIR/cases/<name> (compare.csv/.md/.json/.png, FE in
fe/); a case whose compare.json exists for the same physics is reused. Tables, rewritten
(atomically) after every case: DIR/slab_study.csv (SI, full precision, every column) and .md,
and DIR/slab_study_diagnostics.md: the slab's assumptions checked on the FE solution (contact
length, yield condition p - q = 2k, through-thickness shear, surface k, no-slip zone, velocity
over the neutral section; ``fe_diagnostics``) and slab variants (small-angle geometry,
constant flow stress, yield offset).

    python scripts/slab_study.py                     # the 27 cases -> results/slab_study
    python scripts/slab_study.py --quick             # 3 cases, a smoke test
    python scripts/slab_study.py --mesh-check        # auto mesh vs h = auto/2 on 5 cases
    python scripts/slab_study.py --tensions          # back/front tension 0..30 % of 2k
    python scripts/slab_study.py --lh 2,4 --reductions 0.1,0.3 --mu 0.3 --v-reg 1e-4 \
        --out results/slab_study_vreg1e-4            # Coulomb regularisation 10 x smaller
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
import traceback
from pathlib import Path
from typing import Any, Sequence

import numpy as np
from _common import list_arg, print_table

from hotroll.config.case import Case, CaseError, case_from_dict, load_case
from hotroll.results.output import write_csv
from hotroll.results.run_dir import RunDir

SQRT3 = math.sqrt(3.0)
LH = [2.0, 4.0, 6.0]
REDUCTIONS = [0.1, 0.3, 0.5]
MUS = [0.1, 0.2, 0.3]
QUICK = [(4.0, 0.3, 0.2), (2.0, 0.5, 0.1), (6.0, 0.1, 0.3)]
MESH_CHECK = [(4.0, 0.3, 0.2), (2.0, 0.5, 0.3), (6.0, 0.1, 0.3), (2.0, 0.3, 0.1),
              (2.0, 0.5, 0.2)]
TENSION_CASE = (4.0, 0.3, 0.2)
TENSION_FRACTIONS = [0.0, 0.1, 0.2, 0.3]
MATERIALS = {
    "nh": {"law": "norton-hoff", "K": 4e7, "m": 0.15},
    "s355j2": {"law": "hensel-spittel", "grade": "S355J2"},
}
TEMPERATURE = 1373.15        # K (1100 C)
CODE = "unknown"             # hotroll's commit, set in main()

COLUMNS = ["name", "L_over_h", "reduction", "mu", "R", "h0", "h1", "bite_angle", "status",
           "fe_status", "slab_status", "fe_force", "slab_force", "force_ratio", "torque_ratio",
           "fe_torque", "slab_torque", "small_angle_ratio", "const_sigma_ratio",
           "fe_neutral_angle", "slab_neutral_angle",
           "fe_forward_slip", "slab_forward_slip", "slip_diff_points", "sims_force",
           "fe_sims_ratio", "slab_small_angle_force", "slab_const_sigma_force",
           "fe_stick_share", "slab_stick_share", "fe_peak_interior", "slab_peak",
           "contact_length_ratio", "mean_pressure_ratio", "neutral_flux_excess",
           "neutral_axis_lead", "pq_over_2k", "shear_over_k", "slab_w", "slab_w_force",
           "fe_slab_w_ratio", "k_surface_ratio", "noslip_share", "h_contact",
           "dofs", "nonlinear_iterations", "fe_wall_s", "wall_s", "reused", "code"]
MD_COLUMNS = [  # (header, key, format)
    ("L/h", "L_over_h", "{:g}"), ("r", "reduction", "{:g}"), ("mu", "mu", "{:g}"),
    ("h0 mm", "h0", "mm"), ("status", "status", "{}"),
    ("F FE MN/m", "fe_force", "MN"), ("F slab MN/m", "slab_force", "MN"),
    ("F FE/slab", "force_ratio", "{:.3f}"), ("T FE/slab", "torque_ratio", "{:.3f}"),
    ("phi_n FE mrad", "fe_neutral_angle", "mrad"), ("phi_n slab mrad", "slab_neutral_angle",
                                                   "mrad"),
    ("slip FE %", "fe_forward_slip", "pct"), ("slip slab %", "slab_forward_slip", "pct"),
    ("slip diff pts", "slip_diff_points", "{:+.2f}"), ("F FE/Sims", "fe_sims_ratio", "{:.3f}"),
    ("stick FE/slab %", "stick", "stick"), ("dofs", "dofs", "{}"),
    ("FE s", "fe_wall_s", "{:.1f}"), ("wall s", "wall_s", "{:.1f}"),
]


# ------------------------------------------------------------------------------- cases

def geometry(lh: float, r: float, R: float) -> tuple[float, float]:
    """(h0, h1) full thicknesses with sqrt(R dh)/h_mean = lh and dh/h0 = r."""
    h0 = R * r / (lh ** 2 * (1.0 - r / 2.0) ** 2)
    return h0, h0 * (1.0 - r)


def case_name(lh: float, r: float, mu: float) -> str:
    return f"lh{lh:g}_r{r:g}_mu{mu:g}"


def build_case(lh: float, r: float, mu: float, args: argparse.Namespace, *,
               h_contact: str | float = "auto", back: float = 0.0, front: float = 0.0,
               name: str | None = None) -> Case:
    R, U = args.roll_radius, args.roll_speed
    h0, h1 = geometry(lh, r, R)
    L = math.sqrt(R * (h0 - h1))
    friction = {"law": "coulomb", "mu": mu}
    if args.v_reg is not None:
        friction["v_reg"] = args.v_reg * U
    d = {
        "name": name or case_name(lh, r, mu),
        "pass": {"roll_radius": R, "entry_thickness": h0, "exit_thickness": h1,
                 "roll_angular_velocity": U / R, "back_tension": back, "front_tension": front},
        "plate": {"length": 4.0 * L, "temperature": TEMPERATURE},
        "material": dict(MATERIALS[args.material]),
        "friction": friction,
        "mesh": {"h_contact": h_contact},
        "solver": {"method": "steady", "threads": args.threads},
        "output": {"figures": False, "vtk": False},
    }
    return case_from_dict(d)


DIAG_MD = [  # the slab's assumptions checked on the FE solution (fe_diagnostics)
    ("L/h", "L_over_h", "{:g}"), ("r", "reduction", "{:g}"), ("mu", "mu", "{:g}"),
    ("F FE/slab", "force_ratio", "{:.3f}"), ("L FE/slab", "contact_length_ratio", "{:.4f}"),
    ("p_mean FE/slab", "mean_pressure_ratio", "{:.3f}"),
    ("slab small-angle/arc F", "small_angle_ratio", "{:.3f}"),
    ("slab const-sigma/law F", "const_sigma_ratio", "{:.3f}"),
    ("FE (p-q)/2k", "pq_over_2k", "{:.3f}"), ("FE mean abs(tau_xy)/k", "shear_over_k", "{:.2f}"),
    ("F FE/slab(w)", "fe_slab_w_ratio", "{:.3f}"),
    ("k FE surface/slab", "k_surface_ratio", "{:.3f}"),
    ("no-slip zone %", "noslip_share", "pct0"), ("stick FE/slab %", "stick", "stick"),
    ("flux excess at phi_n %", "neutral_flux_excess", "pct2"),
    ("axis lead at phi_n %", "neutral_axis_lead", "pct2"),
    ("slip diff pts", "slip_diff_points", "{:+.2f}"),
]


# ------------------------------------------------------------------------------ running

def code_version() -> str:
    """Short commit of the hotroll checkout, "+dirty" when hotroll/ has uncommitted changes."""
    import subprocess

    root = Path(__file__).resolve().parent.parent
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=root, text=True,
                              capture_output=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--", "hotroll"], cwd=root,
                               text=True, capture_output=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return head + ("+dirty" if dirty else "")


def _same_physics(case: Case, out: Path) -> bool:
    from hotroll.workflows.runner import fingerprint

    try:
        return fingerprint(load_case(out / "fe" / "case.toml")) == fingerprint(case)
    except (OSError, ValueError, CaseError):
        return False


def run_one(case: Case, out: Path, *, resume: bool) -> dict:
    """run_compare (or reuse its compare.json); returns {"compare", "summary", "wall_s",
    "reused"} or {"error": ...}."""
    from hotroll.workflows.compare import run_compare

    out = Path(out)
    record = out / "study_run.json"
    if resume and (out / "compare.json").is_file() and _same_physics(case, out):
        done = json.loads(record.read_text()) if record.is_file() else {}
        code = done.get("code", "unknown")
        note = "" if code == CODE else f" (WARNING: run with hotroll {code}, now {CODE})"
        print(f"[{case.name}] reusing {out}/compare.json{note}", flush=True)
        return {"compare": json.loads((out / "compare.json").read_text()),
                "summary": json.loads((out / "fe" / "summary.json").read_text()),
                "wall_s": done.get("wall_s"), "code": code, "reused": True}
    print(f"[{case.name}] running -> {out}  (h = {case.mesh.h:.4g} m)", flush=True)
    t0 = time.perf_counter()
    try:
        run_compare(case, out)
    except Exception as e:  # noqa: BLE001 - one failing case must not end the study
        traceback.print_exc()
        return {"error": f"{type(e).__name__}: {e}", "wall_s": time.perf_counter() - t0}
    wall = time.perf_counter() - t0
    _atomic(record, json.dumps({"wall_s": wall, "code": CODE}) + "\n")
    res = {"compare": json.loads((out / "compare.json").read_text()),
           "summary": json.loads((out / "fe" / "summary.json").read_text()),
           "wall_s": wall, "code": CODE, "reused": False}
    print(f"[{case.name}] {res['summary']['status']} (converged "
          f"{res['summary']['converged']}, outlet_driven {res['summary']['outlet_driven']}), "
          f"{wall:.1f} s", flush=True)
    return res


def _rows(compare: dict) -> dict:
    return {r["quantity"]: r for r in compare["rows"]}


def fe_stick_share(contact: dict | None, mu: float) -> float:
    """Share of the FE contact arc where mu p > k (Coulomb capped at k): nodal pressure and k,
    each node weighted by half its two adjacent edges."""
    if contact is None or len(contact["x"]) < 2:
        return math.nan
    xy = np.stack([contact["x"], contact["y"]], -1)
    seg = np.linalg.norm(np.diff(xy, axis=0), axis=1)
    w = np.zeros(len(xy))
    w[:-1] += seg / 2
    w[1:] += seg / 2
    capped = mu * np.maximum(-contact["normal_stress"], 0.0) > contact["shear_flow_stress"]
    return float(np.sum(w[capped]) / np.sum(w))


def fe_diagnostics(case: Case, fe_dir: Path, summary: dict, slab) -> dict:
    """Checks of the slab's assumptions on the FE solution (fields.npz, contact.csv).

    * ``neutral_flux_excess``: section-mean horizontal velocity at the FE neutral point over
      the roll's horizontal speed there, minus 1 (the slab takes the section to move as one,
      i.e. 0); ``neutral_axis_lead``: the same for the velocity on the axis.
    * ``pq_over_2k``: (p - q)/2k, the slab's yield condition (1), with p the FE contact
      pressure (smoothed) and q = -mean sigma_xx over the section, 2k its section mean; the
      mean over 38 sections along the arc weighted by p. sigma = -P I + (2/3) sigma_f/edot
      edot_ij from the written vertex fields (P1 gradients per triangle).
      ``shear_over_k``: the section mean of |sigma_xy|/k, weighted alike (the slab's
      homogeneous compression has 0 inside the section).
    * ``k_surface_ratio``: the FE's k along the contact (contact.csv shear_flow_stress) over
      the slab's k, arc means.
    * ``noslip_share``: share of the contact arc where |tau| < 0.9 min(mu p, k) (the FE's
      neutral zone, where the surface moves with the roll).
    """
    import matplotlib.tri as mtri

    out: dict[str, Any] = {}
    try:
        f = np.load(fe_dir / "fields.npz")
        c = RunDir(fe_dir).table("contact.csv")
    except OSError:
        return out
    if c is None:
        return out
    law, T = case.material.flow_stress(), case.plate.temperature
    P, tris, V = f["points"], f["triangles"], f["v"]
    x, y = P[tris, 0], P[tris, 1]
    det = (x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0]) - (x[:, 2] - x[:, 0]) * (y[:, 1] - y[:, 0])
    bx = np.stack([y[:, 1] - y[:, 2], y[:, 2] - y[:, 0], y[:, 0] - y[:, 1]], 1) / det[:, None]
    by = np.stack([x[:, 2] - x[:, 1], x[:, 0] - x[:, 2], x[:, 1] - x[:, 0]], 1) / det[:, None]
    vx, vy = V[tris, 0], V[tris, 1]
    exx, eyy = (bx * vx).sum(1), (by * vy).sum(1)
    exy = 0.5 * ((by * vx).sum(1) + (bx * vy).sum(1))
    eeq = np.sqrt(2.0 / 3.0 * (exx ** 2 + eyy ** 2 + 2.0 * exy ** 2)) + 1e-12
    strain = f["strain"][tris].mean(1) if "strain" in f else np.zeros(len(tris))
    sf = np.asarray(law.sigma(strain, eeq, T), float)
    sxx = -f["pressure"][tris].mean(1) + (2.0 / 3.0) * sf / eeq * exx
    sxy = (2.0 / 3.0) * sf / eeq * exy
    two_k = 2.0 * sf / SQRT3
    tri = mtri.Triangulation(P[:, 0], P[:, 1], tris)
    finder = tri.get_trifinder()
    cx, cy = summary["roll_centre"]
    R, U = summary["roll_radius"], summary["roll_surface_speed"]

    def section(xi: float):
        top = cy - math.sqrt(R * R - (xi - cx) ** 2)
        ys = np.linspace(0.0, top * 0.9999, 400)
        ti = finder(np.full_like(ys, xi), ys)
        ok = ti >= 0
        return ys[ok], ti[ok]

    a = summary.get("neutral_angle")
    if a is not None and math.isfinite(a) and a > 0:
        xn = cx - R * math.sin(a)
        ys, _ = section(xn)
        v = mtri.LinearTriInterpolator(tri, V[:, 0])(np.full_like(ys, xn), ys)
        ref = U * math.cos(a)
        out["neutral_flux_excess"] = float(np.trapezoid(v, ys) / (ys[-1] - ys[0]) / ref - 1.0)
        out["neutral_axis_lead"] = float(v[0] / ref - 1.0)
    xs, p = c["x"], -c["normal_stress_smooth"]
    order = np.argsort(xs)
    ratios, shears, weights = [], [], []
    for xi in np.linspace(xs.min(), xs.max(), 40)[1:-1]:
        ys, ti = section(xi)
        H = ys[-1] - ys[0]
        q = -np.trapezoid(sxx[ti], ys) / H
        tk = np.trapezoid(two_k[ti], ys) / H
        pi = float(np.interp(xi, xs[order], p[order]))
        ratios.append((pi - q) / tk)
        shears.append(np.trapezoid(np.abs(sxy[ti]) / (0.5 * two_k[ti]), ys) / H)
        weights.append(max(pi, 0.0))
    out["pq_over_2k"] = float(np.sum(np.multiply(ratios, weights)) / np.sum(weights))
    out["shear_over_k"] = float(np.sum(np.multiply(shears, weights)) / np.sum(weights))
    span = c["angle"].max() - c["angle"].min()
    k_fe = abs(np.trapezoid(c["shear_flow_stress"], c["angle"])) / span
    if slab is not None:
        k_slab = np.trapezoid(slab.plane_strain_flow_stress / 2.0, slab.angle) / slab.contact_angle
        out["k_surface_ratio"] = float(k_fe / k_slab)
    mu = case.friction.mu
    lim = np.minimum(mu * np.maximum(-c["normal_stress"], 0.0), c["shear_flow_stress"])
    xy = np.stack([c["x"], c["y"]], -1)
    seg = np.linalg.norm(np.diff(xy, axis=0), axis=1)
    w = np.zeros(len(xy))
    w[:-1] += seg / 2
    w[1:] += seg / 2
    out["noslip_share"] = float(np.sum(w[np.abs(c["shear_stress"]) < 0.9 * lim]) / np.sum(w))
    return out


def slab_variants(case: Case, exit_speed: float | None) -> dict:
    """The case's slab with small-angle geometry, with a constant (arc-mean) flow stress, and
    its sticking share (the share of the contact angle where mu p > k)."""
    from hotroll.theory import constant_flow_stress, solve_pass
    from hotroll.workflows.compare import arc_mean_flow_stress, map_case

    s = map_case(case)
    args = (s.roll_radius, s.h0, s.h1, s.roll_speed, s.friction)
    kw = dict(entry_strain=s.entry_strain, back_tension=s.back_tension,
              front_tension=s.front_tension)
    out: dict[str, Any] = {"slab": None}
    try:
        base = out["slab"] = solve_pass(*args, s.flow_stress, s.temperature, **kw)
        k = base.plane_strain_flow_stress / 2.0
        stick = case.friction.mu * base.pressure >= k * (1 - 1e-12)
        seg = np.diff(base.angle)
        mid = 0.5 * (stick[1:].astype(float) + stick[:-1])
        out["slab_stick_share"] = float(np.sum(mid * seg) / base.contact_angle)
    except Exception:  # noqa: BLE001 - the case's own slab error is reported elsewhere
        out["slab_stick_share"] = math.nan
    try:
        out["slab_small_angle_force"] = solve_pass(*args, s.flow_stress, s.temperature,
                                                   geometry="small_angle", **kw).force
    except Exception:  # noqa: BLE001
        out["slab_small_angle_force"] = math.nan
    sigma = arc_mean_flow_stress(s, exit_speed)
    out["mean_flow_stress"] = sigma
    try:
        out["slab_const_sigma_force"] = solve_pass(*args, constant_flow_stress(sigma),
                                                   s.temperature, **kw).force
    except Exception:  # noqa: BLE001
        out["slab_const_sigma_force"] = math.nan
    return out


def slab_force(case: Case, **options) -> float:
    """The case's slab force with extra ``solve_pass`` options (nan if it fails)."""
    from hotroll.theory import solve_pass
    from hotroll.workflows.compare import map_case

    s = map_case(case)
    try:
        return solve_pass(s.roll_radius, s.h0, s.h1, s.roll_speed, s.friction, s.flow_stress,
                          s.temperature, entry_strain=s.entry_strain,
                          back_tension=s.back_tension, front_tension=s.front_tension,
                          **options).force
    except Exception:  # noqa: BLE001
        return math.nan


def status_of(summary: dict | None, slab_error: str | None) -> tuple[str, str, str]:
    """(combined, FE, slab) status words."""
    if summary is None:
        fe = "error"
    elif summary.get("converged"):
        fe = "ok"
    elif summary.get("outlet_driven"):
        fe = "skids"
    else:
        fe = str(summary.get("status"))
    if slab_error is None:
        slab = "ok"
    elif slab_error.startswith("NoNeutralPointError"):
        slab = "skids"
    else:
        slab = "error"
    combined = fe if fe == slab else f"FE {fe}, slab {slab}"
    return combined, fe, slab


def _ratio(a, b):
    return a / b if a is not None and b not in (None, 0.0) and math.isfinite(b) else None


def case_row(lh: float, r: float, mu: float, case: Case, res: dict, out: Path) -> dict:
    R = case.pass_.roll_radius
    h0, h1 = case.pass_.entry_thickness, case.pass_.exit_thickness
    row: dict[str, Any] = {"name": case.name, "L_over_h": lh, "reduction": r, "mu": mu, "R": R,
                           "h0": h0, "h1": h1, "bite_angle": math.acos(1 - (h0 - h1) / (2 * R)),
                           "wall_s": res.get("wall_s"), "reused": res.get("reused", False),
                           "code": res.get("code")}
    if "error" in res:
        row.update(status=f"error: {res['error']}", fe_status="error", slab_status="-")
        return row
    cmp_, summ = res["compare"], res["summary"]
    rows = _rows(cmp_)
    g = lambda q, col: rows[q][col]  # noqa: E731
    F, T = "roll force per unit width [N/m]", "roll torque per roll [N m/m]"
    A, S = "neutral angle [rad]", "forward slip [%]"
    P = "peak pressure beyond 2h from the contact start [MPa]"
    combined, fe, slab = status_of(summ, cmp_["slab_error"])
    row.update(status=combined, fe_status=fe, slab_status=slab,
               fe_force=g(F, "FE"), slab_force=g(F, "slab (Orowan)"),
               fe_torque=g(T, "FE"), slab_torque=g(T, "slab (Orowan)"),
               fe_neutral_angle=g(A, "FE"), slab_neutral_angle=g(A, "slab (Orowan)"),
               fe_forward_slip=None if g(S, "FE") is None else g(S, "FE") / 100,
               slab_forward_slip=None if g(S, "slab (Orowan)") is None
               else g(S, "slab (Orowan)") / 100,
               sims_force=g(F, "Sims"), fe_peak_interior=g(P, "FE"),
               slab_peak=g(P, "slab (Orowan)"),
               h_contact=summ.get("h_contact"), dofs=summ.get("dofs"),
               nonlinear_iterations=summ.get("nonlinear_iterations"),
               fe_wall_s=summ.get("wall_time_s"))
    row["force_ratio"] = _ratio(row["fe_force"], row["slab_force"])
    row["torque_ratio"] = _ratio(row["fe_torque"], row["slab_torque"])
    row["fe_sims_ratio"] = _ratio(row["fe_force"], row["sims_force"])
    if row["fe_forward_slip"] is not None and row["slab_forward_slip"] is not None:
        row["slip_diff_points"] = 100 * (row["fe_forward_slip"] - row["slab_forward_slip"])
    slab_v1 = None if row["slab_forward_slip"] is None else (
        case.pass_.roll_surface_speed * (1 + row["slab_forward_slip"]))
    variants = slab_variants(case, slab_v1)
    slab_obj = variants.pop("slab")
    row.update(variants)
    row["fe_stick_share"] = fe_stick_share(RunDir(out / "fe").table("contact.csv"), mu)
    if fe == "ok":
        row.update(fe_diagnostics(case, out / "fe", summ, slab_obj))
    w = row.get("pq_over_2k")
    if slab == "ok" and w is not None and math.isfinite(w):
        row["slab_w"] = min(1.0, w)
        row["slab_w_force"] = slab_force(case, yield_offset=row["slab_w"])
        row["fe_slab_w_ratio"] = _ratio(row["fe_force"], row["slab_w_force"])
    L = rows["projected contact length L [m]"]
    row["contact_length_ratio"] = L["FE/slab"]
    mp = rows["mean pressure over the projected contact length [MPa]"]
    row["mean_pressure_ratio"] = mp["FE/slab"]
    if fe != "ok" or slab != "ok":   # ratios only where both roll
        for k in ("force_ratio", "torque_ratio", "fe_sims_ratio", "slip_diff_points"):
            row[k] = None
    return row


# ------------------------------------------------------------------------------- tables

def _atomic(path: Path, text: str) -> None:
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


def _cell(v: Any) -> Any:
    if isinstance(v, (float, np.floating)):
        v = float(v)
        return v if math.isfinite(v) else None
    return v


def _show(v: Any, how: str, row: dict) -> str:
    if how in ("pct0", "pct2") and isinstance(v, float) and math.isfinite(v):
        return f"{100 * v:.{how[-1]}f}"
    if how == "stick":
        a, b = row.get("fe_stick_share"), row.get("slab_stick_share")
        return "/".join("-" if x is None or not math.isfinite(x) else f"{100 * x:.0f}"
                        for x in (a, b))
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    if isinstance(v, bool):
        return str(v).lower()
    scale = {"MN": 1e-6, "kN": 1e-3, "mrad": 1e3, "pct": 100.0, "mm": 1e3,
             "MPa": 1e-6}.get(how)
    if scale is not None:
        return f"{v * scale:.4g}" if how != "mrad" else f"{v * scale:.2f}"
    return how.format(v)


def write_tables(rows: Sequence[dict], columns: Sequence[str],
                 md_columns: Sequence[tuple[str, str, str]], stem: Path, title: str,
                 notes: Sequence[str] = (), *, with_csv: bool = True) -> None:
    """stem.csv (all ``columns``, SI, full precision; unless ``with_csv`` is false) and stem.md
    (``md_columns`` formatted), both written atomically."""
    stem = Path(stem)
    stem.parent.mkdir(parents=True, exist_ok=True)
    if not with_csv:
        pass
    elif rows:
        write_csv(stem.with_suffix(".csv"), [{c: _cell(r.get(c)) for c in columns}
                                             for r in rows])
    else:
        _atomic(stem.with_suffix(".csv"), ",".join(columns) + "\n")
    lines = [f"# {title}", "", "| " + " | ".join(h for h, _, _ in md_columns) + " |",
             "|" + "---|" * len(md_columns)]
    lines += ["| " + " | ".join(_show(r.get(k), f, r).replace("|", "/")
                                for _, k, f in md_columns) + " |" for r in rows]
    if notes:
        lines += [""] + [f"- {n}" for n in notes]
    _atomic(stem.with_suffix(".md"), "\n".join(lines) + "\n")


def _notes(args: argparse.Namespace) -> list[str]:
    mat = MATERIALS[args.material]
    mat_text = (f"Norton-Hoff K = {mat['K']:g} Pa s^m, m = {mat['m']:g}"
                if mat["law"] == "norton-hoff" else f"Hensel-Spittel {mat['grade']}")
    return [
        f"R = {args.roll_radius:g} m, roll surface speed {args.roll_speed:g} m/s, {mat_text}, "
        f"T = {TEMPERATURE:g} K; h0 = R r/((L/h)^2 (1 - r/2)^2); plate length 4 L; steady FE, "
        "automatic mesh unless stated, Coulomb friction (regularised, v_reg = "
        f"{1e-3 if args.v_reg is None else args.v_reg:g} U).",
        "F = roll separating force of one roll per unit width, T = torque per roll; FE/slab "
        "ratios only where both roll. phi_n = neutral angle from the line of roll centres; "
        "slip = forward slip (v_exit - U)/U; slip diff = FE - slab in points of %.",
        "F FE/Sims: Sims' closed form (sticking, small angles, arc-mean flow stress).",
        "stick FE/slab: share (%) of the contact where mu p > k (Coulomb capped at k); FE "
        "from nodal pressure and k, slab along its profile.",
        "status: ok (both roll), skids (FE outlet-driven, slab NoNeutralPointError), or "
        "the two statuses when they differ.",
        "wall s: run_compare (FE + slab + table + figure); FE s: the FE run (summary "
        "wall_time_s). Both on this machine's 2 cores, threads = "
        f"{args.threads}; '-' for a reused case run before the record was kept.",
    ]


def _code_note(rows: Sequence[dict]) -> str:
    codes = sorted({str(r.get("code")) for r in rows})
    return f"hotroll commit of the runs: {', '.join(codes)} (column code of the csv)."


DIAG_NOTES = [
    "L, p_mean: projected contact length and force/L, FE over slab (compare.json).",
    "slab small-angle/arc F, const-sigma/law F: the slab's force with von Karman's small-angle "
    "geometry, and with a constant flow stress (the arc mean of the case law), over the case's "
    "slab (arc geometry, local flow stress).",
    "FE (p-q)/2k: the slab's yield condition p - q = 2k evaluated on the FE solution (p the "
    "contact pressure, q = -section mean of sigma_xx, 2k its section mean), mean over the arc "
    "weighted by p; the slab has 1. FE mean abs(tau_xy)/k: the section mean of the shear "
    "stress over k, weighted alike (0 in the slab's homogeneous compression). F FE/slab(w): "
    "FE force over the slab's with yield_offset w = min(1, FE (p-q)/2k), i.e. p - q = w 2k. "
    "k FE surface/slab: arc means of k along the contact.",
    "no-slip zone: share of the FE contact with |tau| < 0.9 min(mu p, k); stick: share with "
    "mu p > k (FE/slab).",
    "flux excess at phi_n: FE section-mean velocity at its neutral point over U cos(phi_n), "
    "minus 1 (the slab's uniform-velocity assumption makes it 0); axis lead: the same for the "
    "velocity on the axis. The FE-slab slip difference follows from it.",
    "Sections: the written vertex fields, P1 gradients per triangle (checked on lh4_r0.3_mu0.2 "
    "and its 30 % tension runs: q 2-4 mm outside the bite equals the applied tension to "
    "1.5 MPa, 1 % of 2k).",
]


# ------------------------------------------------------------------------------- modes

def grid_mode(args: argparse.Namespace) -> int:
    points = QUICK if args.quick else [(lh, r, mu) for lh in args.lh for r in args.reductions
                                       for mu in args.mu]
    rows, failed = [], 0
    stem = args.out / ("slab_study_quick" if args.quick else "slab_study")
    title = "FE (steady, auto mesh) against slab theory, Coulomb friction"
    t0 = time.perf_counter()
    for lh, r, mu in points:
        case = build_case(lh, r, mu, args)
        out = args.out / "cases" / case.name
        res = run_one(case, out, resume=args.resume)
        failed += "error" in res
        row = case_row(lh, r, mu, case, res, out)
        for key, var in (("small_angle_ratio", "slab_small_angle_force"),
                         ("const_sigma_ratio", "slab_const_sigma_force")):
            row[key] = _ratio(row.get(var), row.get("slab_force"))
        rows.append(row)
        write_tables(rows, COLUMNS, MD_COLUMNS, stem, title, _notes(args) + [_code_note(rows)])
        write_tables(rows, COLUMNS, DIAG_MD, stem.with_name(stem.name + "_diagnostics"),
                     "Slab assumptions checked on the FE solution", DIAG_NOTES, with_csv=False)
    print(f"total {time.perf_counter() - t0:.1f} s; tables: {stem}.csv, {stem}.md")
    print_table(rows, ["name", "status", "force_ratio", "torque_ratio", "fe_neutral_angle",
                       "slab_neutral_angle", "slip_diff_points", "fe_sims_ratio", "wall_s"])
    return 1 if failed else 0


MESH_COLUMNS = ["name", "mesh", "h_contact", "dofs", "status", "fe_force", "fe_torque",
                "fe_neutral_angle", "fe_forward_slip", "force_change_pct", "torque_change_pct",
                "angle_change_mrad", "slip_change_points", "contact_length_ratio", "fe_wall_s",
                "wall_s", "code"]
MESH_MD = [("case", "name", "{}"), ("mesh", "mesh", "{}"), ("h mm", "h_contact", "mm"),
           ("dofs", "dofs", "{}"), ("status", "status", "{}"), ("F MN/m", "fe_force", "MN"),
           ("T kN m/m", "fe_torque", "kN"), ("phi_n mrad", "fe_neutral_angle", "mrad"),
           ("slip %", "fe_forward_slip", "pct"), ("dF %", "force_change_pct", "{:+.2f}"),
           ("dT %", "torque_change_pct", "{:+.2f}"),
           ("dphi_n mrad", "angle_change_mrad", "{:+.3f}"),
           ("dslip pts", "slip_change_points", "{:+.3f}"),
           ("L FE/slab", "contact_length_ratio", "{:.4f}"), ("FE s", "fe_wall_s", "{:.1f}")]


def mesh_mode(args: argparse.Namespace) -> int:
    rows, failed = [], 0
    for lh, r, mu in MESH_CHECK:
        auto = build_case(lh, r, mu, args)
        h = auto.mesh.h
        base = None
        for label, hc in (("auto", "auto"), ("auto/2", h / 2)):
            case = build_case(lh, r, mu, args, h_contact=hc)
            out = args.out / ("cases" if hc == "auto" else "mesh_check") / case.name
            res = run_one(case, out, resume=args.resume)
            failed += "error" in res
            row = case_row(lh, r, mu, case, res, out)
            row["mesh"] = label
            if base is None:
                base = row
            elif "error" not in res:
                f = lambda k: row[k] - base[k]  # noqa: E731
                row["force_change_pct"] = 100 * f("fe_force") / base["fe_force"]
                row["torque_change_pct"] = 100 * f("fe_torque") / base["fe_torque"]
                row["angle_change_mrad"] = 1e3 * f("fe_neutral_angle")
                row["slip_change_points"] = 100 * f("fe_forward_slip")
            row["status"] = row["fe_status"]
            rows.append(row)
            write_tables(rows, MESH_COLUMNS, MESH_MD, args.out / "mesh_check",
                         "FE mesh check: automatic mesh against h = auto/2",
                         ["Changes (d) are auto/2 minus auto, relative to auto for force and "
                          "torque. L FE/slab: projected contact length, FE over slab.",
                          _code_note(rows)])
    print(f"tables: {args.out / 'mesh_check.csv'}, .md")
    print_table(rows, ["name", "mesh", "dofs", "fe_force", "force_change_pct",
                       "torque_change_pct", "angle_change_mrad", "slip_change_points"])
    return 1 if failed else 0


TENSION_COLUMNS = ["side", "fraction", "tension", "fe_status", "slab_status",
                   "fe_force", "slab_const_force", "slab_law_force",
                   "fe_neutral_angle", "slab_const_neutral_angle", "slab_law_neutral_angle",
                   "fe_forward_slip", "slab_const_forward_slip", "slab_law_forward_slip",
                   "fe_dforce_pct", "slab_const_dforce_pct", "slab_law_dforce_pct",
                   "fe_dangle", "slab_const_dangle", "slab_law_dangle",
                   "fe_dslip_points", "slab_const_dslip_points", "slab_law_dslip_points",
                   "fe_force_balance_x", "fe_wall_s", "wall_s", "code"]
TENSION_MD = [
    ("side", "side", "{}"), ("t/2k", "fraction", "{:g}"), ("t MPa", "tension", "MPa"),
    ("F FE", "fe_force", "MN"), ("F slab", "slab_law_force", "MN"),
    ("dF FE %", "fe_dforce_pct", "{:+.1f}"), ("dF slab %", "slab_law_dforce_pct", "{:+.1f}"),
    ("phi_n FE", "fe_neutral_angle", "mrad"), ("phi_n slab", "slab_law_neutral_angle", "mrad"),
    ("dphi_n FE", "fe_dangle", "mrad"), ("dphi_n slab", "slab_law_dangle", "mrad"),
    ("slip FE %", "fe_forward_slip", "pct"), ("slip slab %", "slab_law_forward_slip", "pct"),
    ("dslip FE pts", "fe_dslip_points", "{:+.2f}"),
    ("dslip slab pts", "slab_law_dslip_points", "{:+.2f}"),
    ("dF slab-c %", "slab_const_dforce_pct", "{:+.1f}"),
    ("dphi_n slab-c", "slab_const_dangle", "mrad"),
    ("dslip slab-c pts", "slab_const_dslip_points", "{:+.2f}"),
    ("FE status", "fe_status", "{}"), ("slab status", "slab_status", "{}"),
    ("FE s", "fe_wall_s", "{:.1f}"),
]


def tension_mode(args: argparse.Namespace) -> int:
    from hotroll.theory import constant_flow_stress, solve_pass
    from hotroll.workflows.compare import map_case

    lh, r, mu = TENSION_CASE
    ref = build_case(lh, r, mu, args)
    s = map_case(ref)
    slab0 = solve_pass(s.roll_radius, s.h0, s.h1, s.roll_speed, s.friction, s.flow_stress,
                       s.temperature, entry_strain=s.entry_strain)
    two_k = float(np.trapezoid(slab0.plane_strain_flow_stress, slab0.angle)
                  / slab0.contact_angle)
    const = constant_flow_stress(two_k * SQRT3 / 2.0)
    print(f"tension case {ref.name}: mean 2k of the slab = {two_k / 1e6:.2f} MPa", flush=True)
    runs = [("none", 0.0)] + [(side, f) for side in ("back", "front")
                              for f in TENSION_FRACTIONS if f > 0]
    rows, failed = [], 0
    for side, frac in runs:
        t = frac * two_k
        back, front = (t, 0.0) if side == "back" else (0.0, t) if side == "front" else (0, 0)
        name = f"{ref.name}_{side}{frac:g}"
        case = build_case(lh, r, mu, args, back=back, front=front, name=name)
        out = args.out / "tensions" / name
        res = run_one(case, out, resume=args.resume)
        failed += "error" in res
        row: dict[str, Any] = {"side": side, "fraction": frac, "tension": t,
                               "wall_s": res.get("wall_s")}
        if "error" not in res:
            summ, cmp_ = res["summary"], res["compare"]
            rr = _rows(cmp_)
            _, row["fe_status"], row["slab_status"] = status_of(summ, cmp_["slab_error"])
            if row["slab_status"] == "error":
                row["slab_status"] = cmp_["slab_error"].split(":")[0]
            row["code"] = res.get("code")
            row.update(fe_force=summ["roll_force"], fe_neutral_angle=summ["neutral_angle"],
                       fe_forward_slip=summ["forward_slip"], fe_wall_s=summ["wall_time_s"],
                       fe_force_balance_x=summ["horizontal_force"],
                       slab_law_force=rr["roll force per unit width [N/m]"]["slab (Orowan)"],
                       slab_law_neutral_angle=rr["neutral angle [rad]"]["slab (Orowan)"])
            sl = rr["forward slip [%]"]["slab (Orowan)"]
            row["slab_law_forward_slip"] = None if sl is None else sl / 100
        try:
            sc = solve_pass(s.roll_radius, s.h0, s.h1, s.roll_speed, s.friction, const,
                            s.temperature, entry_strain=s.entry_strain, back_tension=back,
                            front_tension=front)
            row.update(slab_const_force=sc.force, slab_const_neutral_angle=sc.neutral_angle,
                       slab_const_forward_slip=sc.forward_slip)
        except Exception as e:  # noqa: BLE001
            row["slab_const_error"] = f"{type(e).__name__}: {e}"
        rows.append(row)
        base = rows[0]
        for r_ in rows:
            for src in ("fe", "slab_const", "slab_law"):
                F, F0 = r_.get(f"{src}_force"), base.get(f"{src}_force")
                if F is not None and F0:
                    r_[f"{src}_dforce_pct"] = 100 * (F - F0) / F0
                a, a0 = r_.get(f"{src}_neutral_angle"), base.get(f"{src}_neutral_angle")
                if a is not None and a0 is not None:
                    r_[f"{src}_dangle"] = a - a0
                v, v0 = r_.get(f"{src}_forward_slip"), base.get(f"{src}_forward_slip")
                if v is not None and v0 is not None:
                    r_[f"{src}_dslip_points"] = 100 * (v - v0)
        notes = [f"Case {ref.name}: R = {args.roll_radius:g} m, h0 = {s.h0 * 1e3:.3f} mm, "
                 f"h1 = {s.h1 * 1e3:.3f} mm, U = {args.roll_speed:g} m/s, Coulomb mu = {mu:g}; "
                 f"2k = {two_k / 1e6:.2f} MPa, the angle mean of the slab's plane-strain flow "
                 "stress (no tension).",
                 "F in MN/m (one roll), phi_n in mrad, slip = forward slip in %; d = change "
                 "from the no-tension row.",
                 "slab: Orowan with the case's flow-stress law, as hotroll compare runs it "
                 "(its slab_error, if any, in the slab status column); slab-c: Orowan with a "
                 "constant flow stress sigma = 2k sqrt3/2 (absolute values in the csv).",
                 _code_note(rows)]
        write_tables(rows, TENSION_COLUMNS, TENSION_MD, args.out / "tension_study",
                     "Tensions: FE against slab theory", notes)
    print(f"tables: {args.out / 'tension_study.csv'}, .md")
    print_table(rows, ["side", "fraction", "fe_force", "slab_const_force", "fe_dforce_pct",
                       "slab_const_dforce_pct", "fe_neutral_angle", "slab_const_neutral_angle",
                       "fe_forward_slip", "slab_const_forward_slip"])
    return 1 if failed else 0


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", type=Path, default=Path("results/slab_study"),
                   help="output directory (default results/slab_study)")
    p.add_argument("--quick", action="store_true",
                   help=f"only {len(QUICK)} cases (a smoke test): {QUICK}")
    p.add_argument("--mesh-check", action="store_true",
                   help=f"run auto mesh and h = auto/2 on {MESH_CHECK} (L/h, r, mu)")
    p.add_argument("--tensions", action="store_true",
                   help=f"back and front tension {TENSION_FRACTIONS} x 2k on {TENSION_CASE}")
    p.add_argument("--lh", type=list_arg(float), default=LH, help="L/h_mean values")
    p.add_argument("--reductions", type=list_arg(float), default=REDUCTIONS,
                   help="reductions dh/h0")
    p.add_argument("--mu", type=list_arg(float), default=MUS, help="Coulomb coefficients")
    p.add_argument("--roll-radius", type=float, default=0.4, help="R in m (default 0.4)")
    p.add_argument("--roll-speed", type=float, default=3.0,
                   help="roll surface speed omega R in m/s (default 3)")
    p.add_argument("--material", choices=sorted(MATERIALS), default="nh",
                   help="nh: Norton-Hoff K = 4e7 Pa s^m, m = 0.15 (default); s355j2: "
                        "Hensel-Spittel S355J2")
    p.add_argument("--v-reg", type=float, default=None,
                   help="Coulomb regularisation velocity as a fraction of the roll speed "
                        "(default: hotroll's, 1e-3); use another --out")
    p.add_argument("--threads", type=int, default=2, help="NGSolve threads per run (default 2)")
    p.add_argument("--resume", action=argparse.BooleanOptionalAction, default=True,
                   help="reuse cases whose compare.json exists for the same physics")
    args = p.parse_args(argv)
    global CODE
    CODE = code_version()
    try:
        build_case(*TENSION_CASE, args)
    except CaseError as e:
        p.error(str(e))
    if args.mesh_check:
        return mesh_mode(args)
    if args.tensions:
        return tension_mode(args)
    return grid_mode(args)


if __name__ == "__main__":
    sys.exit(main())
