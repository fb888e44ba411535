"""Softening between two passes, point by point through the thickness (issue 33; theory 1g).

Beynon and Sellars' multipass bookkeeping on each streamline (eta = y / half thickness, which a
flat strip keeps from entry to exit):

- in the pass: the strain eps (retained + this pass's) and the streamline's Zener-Hollomon
  parameter ln Z = <ln edot> + Q_def/R <1/T>, both strain-weighted means along the streamline
  (``fem/strain.py`` integrates them on the FE flow); dynamic recrystallisation has started
  where eps >= eps_c(d0, Z);
- in the transport (the strip's cooling history ``T(t, eta)``): metadynamic recrystallisation
  where DRX started (t_0.5(Z, T), d_mdrx(Z)), static elsewhere (t_0.5(eps, d0, edot, T),
  d_srx(eps, d0, T) at the temperature where X = 0.5), JMAK by additivity (``jmak.py``), grain
  growth once X = 0.95;
- handed on: the retained strain lambda (1 - X) eps and the grain size, d_grown once finished,
  else Beynon and Sellars' mix X^(4/3) d_rex + (1 - X)^2 d0.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hotroll.model.microstructure.base import R, RecrystallisationSet
from hotroll.model.microstructure.jmak import hold


class KineticsRangeError(ValueError):
    """A cooling history that is not one (named with where it occurred)."""


@dataclass(frozen=True)
class PassState:
    """The deformed strip at a pass's exit, per point (arrays over eta)."""

    eta: np.ndarray
    strain: np.ndarray          # total equivalent strain at the exit (retained + pass)
    grain: np.ndarray           # grain size entering the pass (m)
    rate: np.ndarray            # strain-weighted geometric mean strain rate (1/s)
    zener: np.ndarray           # Z (1/s)
    critical: np.ndarray        # eps_c
    temperature: np.ndarray     # the exit temperature (K)

    @property
    def dynamic(self) -> np.ndarray:
        """Where dynamic recrystallisation started in the pass."""
        return self.strain >= self.critical


def pass_state(s: RecrystallisationSet, eta, strain, grain, log_rate, inverse_T,
               temperature) -> PassState:
    """The pass's exit state from the FE streamline means (``log_rate`` = <ln edot>, edot in
    1/s; ``inverse_T`` = <1/T>, 1/K; both strain-weighted along each streamline)."""
    eta, strain, grain = (np.asarray(a, dtype=float) for a in (eta, strain, grain))
    log_rate, inverse_T = np.asarray(log_rate, float), np.asarray(inverse_T, float)
    Z = np.exp(log_rate + s.q_def / R * inverse_T)
    return PassState(eta, strain, grain, np.exp(log_rate), Z, s.critical_strain(grain, Z),
                     np.asarray(temperature, dtype=float))


@dataclass(frozen=True)
class Softened:
    """After the transport, per point: mechanism (1 metadynamic, 0 static), X, t_0.5 at the
    start (s), the recrystallised and the handed-on grain size (m), the retained strain,
    whether X reached 0.95, and the lowest temperature of the history (K): below the set's
    range (a chilled surface just after the bite) the laws are extrapolated, and reported so
    (``extrapolated``), not refused."""

    eta: np.ndarray
    metadynamic: np.ndarray
    fraction: np.ndarray
    half_time: np.ndarray
    rex_grain: np.ndarray
    grain: np.ndarray
    retained_strain: np.ndarray
    finished: np.ndarray
    coldest: np.ndarray
    extrapolated: np.ndarray


def soften(s: RecrystallisationSet, ps: PassState, times, T, retained_share: float = 1.0,
           where: str = "transport") -> Softened:
    """Recrystallise the pass state ``ps`` over the cooling history T[i, j] (K, point j of
    ``ps.eta`` at ``times[i]``, s from the pass's exit)."""
    T = np.asarray(T, dtype=float)
    if T.ndim != 2 or T.shape[1] != ps.eta.size or not np.all(np.isfinite(T)) \
            or np.any(T <= 0.0):
        raise KineticsRangeError(f"{where}: the cooling history must be finite temperatures "
                                 f"> 0 K at the {ps.eta.size} points of the pass state")
    lo, hi = s.temperature_range
    coldest, hottest = T.min(axis=0), T.max(axis=0)
    md = ps.dynamic
    strain = np.maximum(ps.strain, 1e-12)
    n = np.where(md, s.mdrx_exponent, s.srx_exponent)

    def half_time(Ti, i):
        return np.where(md, s.mdrx_half_time(ps.zener, Ti),
                        s.srx_half_time(strain, ps.grain, ps.rate, Ti))

    res = hold(times, T, half_time, n, s.growth.rate)
    d_rex = np.where(md, s.mdrx_grain_size(ps.zener), s.srx_grain_size(strain, ps.grain,
                                                                        res.T_half))
    done = np.isfinite(res.t_finished)
    X = res.X
    mixed = X ** (4.0 / 3.0) * d_rex + (1.0 - X) ** 2 * ps.grain
    d_out = np.where(done, s.grown(d_rex, res.W_after), mixed)
    return Softened(ps.eta, md, X, half_time(T[0], 0), d_rex, d_out,
                    retained_share * (1.0 - X) * ps.strain, done, coldest,
                    (coldest < lo) | (hottest > hi))
