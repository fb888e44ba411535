"""JMAK recrystallisation and grain growth along a temperature history (issue 33; theory 1g).

Isothermal: X(t) = 1 - exp(ln 0.5 (t / t_0.5)^n). Non-isothermal, by the additivity rule
(Avrami's isokinetic condition: only t_0.5 depends on T, the deformation state is frozen):

    tau(t) = int_0^t dt' / t_0.5(T(t')),     X = 1 - exp(ln 0.5 tau^n),

integrated by the trapezoid rule on the history's own times (second order in the step).
Growth after recrystallisation has finished (X = 0.95, tau_f = (ln 0.05 / ln 0.5)^(1/n)) runs
on the temperature-compensated time W = int exp(-Q_gg / (R T)) dt from the finish on.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

LN_HALF = math.log(0.5)
#: The recrystallised fraction at which recrystallisation counts as finished (grain growth
#: starts): 0.95, as PyRolL's threshold and common practice.
FINISHED = 0.95


def fraction(tau, n: float):
    """X = 1 - exp(ln 0.5 tau^n), tau = t / t_0.5 (or its additive integral)."""
    return 1.0 - np.exp(LN_HALF * np.asarray(tau, dtype=float) ** n)


def tau_at(X: float, n):
    """The tau at which the fraction reaches X (n one exponent or an array of them)."""
    return (math.log(1.0 - X) / LN_HALF) ** (1.0 / np.asarray(n, dtype=float))


@dataclass(frozen=True)
class HoldResult:
    """Per point: tau at the end, the fraction X, the time X reached 0.5 and 0.95 (s; nan if it
    did not), the temperature at X = 0.5 (K; the end temperature if it did not) and the
    temperature-compensated growth time after the finish (s)."""

    tau: np.ndarray
    X: np.ndarray
    t_half: np.ndarray
    t_finished: np.ndarray
    T_half: np.ndarray
    W_after: np.ndarray


def _crossing(t0, t1, a0, a1, level):
    """Where the linear a(t) between (t0, a0) and (t1, a1) reaches level (a0 < level <= a1)."""
    return t0 + (t1 - t0) * (level - a0) / np.where(a1 > a0, a1 - a0, 1.0)


def hold(times, T, half_time: Callable[[np.ndarray, int], np.ndarray], n,
         growth_rate: Callable[[np.ndarray], np.ndarray] | None = None) -> HoldResult:
    """Integrate the fraction of ``m`` points over the history ``T[i, j]`` (K) at ``times[i]``
    (s, increasing from the deformation's end): ``half_time(T_i, i)`` gives t_0.5 (s) of every
    point at the i-th temperatures, ``n`` JMAK's exponent (one, or one per point),
    ``growth_rate(T)`` dW/dt of grain growth (None: no W)."""
    t = np.asarray(times, dtype=float)
    T = np.asarray(T, dtype=float)
    if t.ndim != 1 or T.ndim != 2 or T.shape[0] != t.size or t.size < 1:
        raise ValueError("hold: times (nt,) and T (nt, m) needed")
    if np.any(np.diff(t) <= 0.0):
        raise ValueError("hold: times must increase strictly")
    m = T.shape[1]
    n = np.broadcast_to(np.asarray(n, dtype=float), (m,))
    tau_half = np.ones(m)
    tau_fin = tau_at(FINISHED, n)
    tau = np.zeros(m)
    t_half = np.full(m, np.nan)
    t_fin = np.full(m, np.nan)
    T_half = T[-1].copy()
    W = np.zeros(m)
    r0 = 1.0 / half_time(T[0], 0)
    g0 = growth_rate(T[0]) if growth_rate is not None else None
    for i in range(1, t.size):
        dt = t[i] - t[i - 1]
        r1 = 1.0 / half_time(T[i], i)
        new = tau + 0.5 * dt * (r0 + r1)
        hit = (tau < tau_half) & (new >= tau_half)
        if np.any(hit):
            th = _crossing(t[i - 1], t[i], tau, new, tau_half)
            t_half[hit] = th[hit]
            w = (th - t[i - 1]) / dt
            T_half[hit] = ((1.0 - w) * T[i - 1] + w * T[i])[hit]
        done = (tau < tau_fin) & (new >= tau_fin)
        if np.any(done):
            tf = _crossing(t[i - 1], t[i], tau, new, tau_fin)
            t_fin[done] = tf[done]
        if g0 is not None:
            g1 = growth_rate(T[i])
            grown = np.isfinite(t_fin)
            # the share of the step after the finish (all of it once finished before it)
            after = np.where(grown, np.clip((t[i] - np.nan_to_num(t_fin, nan=t[i])) / dt,
                                            0.0, 1.0), 0.0)
            W += after * dt * 0.5 * (g0 + g1)
            g0 = g1
        tau, r0 = new, r1
    return HoldResult(tau, fraction(tau, n), t_half, t_fin, T_half, W)
