"""Microstructure through a schedule (issue 33; docs/theory.md 1g): after each pass, the
recrystallisation kinetics of ``[microstructure] model`` on every streamline of the pass's
exit profile (its strain, ln Z and exit temperature: ``solvers/streamlines.py``), integrated
over the transport's cooling history (``model/interpass.cool``, record=True), and the
retained-strain and grain-size profiles handed to the next pass. Without a model, each
transport's ``strain_retained`` share of the strain is kept, as before.
"""
from __future__ import annotations

import numpy as np

from hotroll.model.microstructure.softening import PassState, Softened, pass_state, soften
from hotroll.model.profile import ThicknessProfile, folded
from hotroll.results.output import write_csv


class MicrostructureError(RuntimeError):
    """A pass whose exit profile lacks the streamline histories the kinetics need."""


def deformed(sch, entry_strain: ThicknessProfile, grain: ThicknessProfile,
             summary: dict, k: int) -> PassState:
    """The k-th pass's exit state on its exit profile's eta (``softening.pass_state``): the
    strain = the entry's at that eta + the streamline's pass strain; an asymmetric pass's
    whole-thickness profile folded about the middle (``profile.folded``)."""
    prof = folded(summary.get("exit_profile")) or {}
    if prof.get("pass_strain") is None:
        raise MicrostructureError(f"pass {k + 1}: its exit profile has no streamline "
                                  f"histories (a thermal steady run writes them)")
    eta = np.asarray(prof["eta"], dtype=float)
    total = entry_strain(eta) + np.asarray(prof["pass_strain"], dtype=float)
    return pass_state(sch.microstructure.kinetics, eta, total, grain(eta),
                      prof["log_rate_mean"], prof["inverse_temperature_mean"],
                      prof["temperature"])


def on_rows(history: np.ndarray, y: np.ndarray, eta: np.ndarray) -> np.ndarray:
    """A cooling history (steps, nodes at y from the centre) at the pass state's eta."""
    e = y / y[-1]
    return np.array([np.interp(eta, e, row) for row in history])


def after_transport(sch, ps: PassState, cooled, where: str) -> Softened:
    """Soften ``ps`` over the transport's recorded cooling (``cool(..., record=True)``)."""
    return soften(sch.microstructure.kinetics, ps, cooled.times,
                  on_rows(cooled.history, cooled.y, ps.eta),
                  sch.microstructure.retained_share, where)


def _profile(eta, values) -> ThicknessProfile:
    return ThicknessProfile(tuple(eta), tuple(np.asarray(values, dtype=float)))


def handed_on(soft: Softened) -> tuple[ThicknessProfile, ThicknessProfile]:
    """(retained strain, grain size) profiles for the next pass."""
    return (_profile(soft.eta, np.maximum(soft.retained_strain, 0.0)),
            _profile(soft.eta, soft.grain))


def pass_columns(ps: PassState) -> dict:
    """The pass's row: where DRX started (its share of the section), ln Z mean (eta-mean of
    ln Z), the critical strain and strain at the surface and the centre."""
    onset = _profile(ps.eta, ps.dynamic.astype(float)).mean()
    return {"drx_onset_share": onset,
            "zener_log_mean": _profile(ps.eta, np.log(ps.zener)).mean(),
            "critical_strain_centre": float(ps.critical[0]),
            "critical_strain_surface": float(ps.critical[-1]),
            "kinetics_strain_centre": float(ps.strain[0]),
            "kinetics_strain_surface": float(ps.strain[-1])}


def transport_columns(soft: Softened) -> dict:
    """The transport's row: fraction recrystallised, grain size and retained strain as
    section means (over eta) and at the surface and the centre; the mechanism there."""
    out = {}
    for key, vals in (("recrystallised_fraction", soft.fraction), ("grain_size", soft.grain),
                      ("retained_strain", soft.retained_strain)):
        out[f"{key}_mean"] = _profile(soft.eta, vals).mean()
        out[f"{key}_surface"] = float(vals[-1])
        out[f"{key}_centre"] = float(vals[0])
    out["kinetics_temperature_min"] = float(np.min(soft.coldest))
    out["kinetics_extrapolated_share"] = _profile(soft.eta,
                                                  soft.extrapolated.astype(float)).mean()
    out["mechanism_surface"] = "metadynamic" if soft.metadynamic[-1] else "static"
    out["mechanism_centre"] = "metadynamic" if soft.metadynamic[0] else "static"
    return out


def profile_dict(ps: PassState, soft: Softened | None) -> dict:
    """The per-eta record of schedule.json (and microstructure.csv)."""
    d = {"eta": ps.eta.tolist(), "strain": ps.strain.tolist(),
         "grain_size_entry": ps.grain.tolist(), "zener": ps.zener.tolist(),
         "strain_rate": ps.rate.tolist(), "critical_strain": ps.critical.tolist(),
         "dynamic_onset": ps.dynamic.astype(int).tolist()}
    if soft is not None:
        d.update({"metadynamic": soft.metadynamic.astype(int).tolist(),
                  "half_time": soft.half_time.tolist(),
                  "recrystallised_fraction": soft.fraction.tolist(),
                  "recrystallised_grain_size": soft.rex_grain.tolist(),
                  "grain_size": soft.grain.tolist(),
                  "retained_strain": soft.retained_strain.tolist(),
                  "finished": soft.finished.astype(int).tolist(),
                  "coldest": soft.coldest.tolist(),
                  "extrapolated": soft.extrapolated.astype(int).tolist()})
    return d


def write_table(path, record: dict) -> None:
    """microstructure.csv of a pass (one row per eta)."""
    write_csv(path, {k: np.asarray(v) for k, v in record.items()})
