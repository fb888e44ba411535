"""A Hensel-Spittel law fitted to any flow-stress function sigma(strain, rate, T) (issue 17).

PyRolL gives a profile's flow stress as a Python function (``Profile.flow_stress_function``,
e.g. pyroll-freiberg-flow-stress, which evaluates Spittel's coefficients at strain + 0.1 and
rate + 0.1). The FE form needs the law in closed form (NGSolve coefficient functions of the
strain and temperature fields), so the function is fitted by linear least squares in
ln sigma over the pass's range:

    ln sigma = ln A + m1 T_C + m2 ln eps + m3 ln edot + m5 T_C ln(1 + eps) + m7 eps
               + m8 T_C ln edot           (T_C in deg C; m4 = m6 = m9 = 0)

on a grid of strains, rates and temperatures (``fit_hensel_spittel``). The fit's largest
relative error on that grid is returned beside the law and must be reported with the results.
A function that is itself of this form is recovered exactly.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hotroll.model.flow_stress import CELSIUS_OFFSET, HenselSpittel

#: The Hensel-Spittel terms the fit uses (m4 = e^(m4/eps), m6, m9 are left at 0).
FIT_TERMS = ("A", "m1", "m2", "m3", "m5", "m7", "m8")


@dataclass(frozen=True)
class FlowStressFit:
    law: HenselSpittel
    max_rel_error: float          # on the fitting grid
    strain: tuple[float, float]
    strain_rate: tuple[float, float]   # 1/s
    temperature: tuple[float, float]   # K


def fit_hensel_spittel(func, strain: tuple[float, float], strain_rate: tuple[float, float],
                       temperature: tuple[float, float], points: int = 7,
                       strain_min: float = 0.03) -> FlowStressFit:
    """Fit ``func(strain, strain_rate, temperature_K) -> Pa`` over the box (strain floored at
    ``strain_min``, rates > 0, T in K), ``points`` per axis (rates and strains spaced
    logarithmically). Raises ValueError on a box or function values that cannot be fitted."""
    e0, e1 = max(strain[0], strain_min), max(strain[1], strain_min)
    r0, r1 = strain_rate
    t0, t1 = temperature
    if not (e1 >= e0 > 0 and r1 >= r0 > 0 and t1 >= t0 > CELSIUS_OFFSET):
        raise ValueError(f"flow-stress fit: need 0 < strain range, 0 < rate range, T > 0 degC; "
                         f"got strain {strain}, rate {strain_rate} 1/s, T {temperature} K")
    eps = np.unique(np.geomspace(e0, e1 if e1 > e0 else e0 * 1.5, points))
    rate = np.unique(np.geomspace(r0, r1 if r1 > r0 else r0 * 2.0, points))
    T = np.unique(np.linspace(t0, t1 if t1 > t0 else t0 + 50.0, points))
    E, R, TK = (a.ravel() for a in np.meshgrid(eps, rate, T, indexing="ij"))
    sigma = np.array([float(func(e, r, t)) for e, r, t in zip(E, R, TK)])
    if not np.all(np.isfinite(sigma)) or np.any(sigma <= 0.0):
        raise ValueError("flow-stress fit: the function gives non-positive or non-finite "
                         "stresses on the pass's range")
    tc = TK - CELSIUS_OFFSET
    basis = np.stack([np.ones_like(E), tc, np.log(E), np.log(R), tc * np.log1p(E), E,
                      tc * np.log(R)], axis=1)
    scale = np.max(np.abs(basis), axis=0)
    coef, *_ = np.linalg.lstsq(basis / scale, np.log(sigma), rcond=None)
    coef = coef / scale
    params = dict(zip(FIT_TERMS, coef))
    params["A"] = float(np.exp(params["A"]))
    law = HenselSpittel(**{k: float(v) for k, v in params.items()}, strain_min=strain_min,
                        name="fitted to a flow-stress function")
    err = float(np.max(np.abs(law.sigma(E, R, TK) / sigma - 1.0)))
    return FlowStressFit(law, err, (float(eps[0]), float(eps[-1])),
                         (float(rate[0]), float(rate[-1])), (float(T[0]), float(T[-1])))
