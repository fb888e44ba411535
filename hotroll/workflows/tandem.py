"""Interstand tensions from the stand speeds of a tandem mill (issue 32, ``mill.tensions =
"from_speeds"``).

With every stand's roll speed given (a cold tandem's set-up, a mill log), the strip between
stands k and k+1 carries the tension t_k (Pa) that makes the stands pass one mass flux: each
stand's exit flux Q_k = h_k v_k (its exit thickness and speed, v_k = U_k (1 + f_k) with its
forward slip f_k from its own FE solve) depends on its back and front tension. The residuals

    r_k = ln Q_{k+1} - ln Q_k,  k = 1 .. n-1,

are driven to |r_k| <= ``mill.flux_tolerance`` by Newton's method on t. Its Jacobian is
tridiagonal in the tensions (a stand feels only its own two; the temperature handed on is a
weaker link, left to the iteration): two extra schedule runs measure it by finite differences,
the even tensions moved in one and the odd ones in the other, so every stand sees one moved
tension per run, whatever the number of stands. Broyden's update keeps it current. Each run
of the schedule starts every stand's Newton from its last solve (``workflows/sweep``).

A tension is kept in [0, ``MAX_TENSION_SHARE`` x the smaller mean flow stress of its two
stands]: a mill whose speeds need a compressive or a tearing interstand force stops with the
stand pair named.
"""
from __future__ import annotations

from typing import Callable

import numpy as np

#: The finite-difference step of the Jacobian, a share of the stands' mean flow stress.
STEP_SHARE = 0.02
#: The largest interstand tension, a share of the smaller mean flow stress of its two stands.
MAX_TENSION_SHARE = 0.7
#: Newton steps (schedule runs after the Jacobian's) before the search gives up.
MAX_STEPS = 12


class TensionError(RuntimeError):
    """The stand speeds need a tension outside [0, MAX_TENSION_SHARE sigma_f], or the
    search did not settle."""


def _log_flux(rows: list[dict]) -> np.ndarray:
    """ln Q_k of the stands' exit fluxes (half strip)."""
    return np.log([r["mass_flux_out"] for r in rows])


def residuals(rows: list[dict]) -> np.ndarray:
    """r_k = ln Q_{k+1} - ln Q_k."""
    return np.diff(_log_flux(rows))


def solve_tensions(sch, roll: Callable, start: list[float] | None,
                   say: Callable[[str], None]) -> tuple[list[dict], list[dict], dict]:
    """The interstand tensions of ``sch`` (module docstring). ``roll(tensions, quiet)`` rolls
    the whole schedule with them and returns (rows, profiles); ``start``: a first guess (a
    finished run's tensions), else each pass's front tension. Returns the rows and profiles
    at the solution and the figures schedule.json keeps."""
    n = len(sch.passes)
    tol = sch.mill.flux_tolerance
    if start is not None and len(start) == n - 1:
        t = np.asarray(start, dtype=float)
    else:
        t = np.array([max(sch.passes[k].front_tension, sch.passes[k + 1].back_tension)
                      for k in range(n - 1)])
    runs = 0
    fe = 0

    def run(tt: np.ndarray, quiet: bool = True):
        nonlocal runs, fe
        rows, profiles = roll(list(map(float, tt)), quiet)
        runs += 1
        fe += sum(r["fe_solves"] for r in rows)
        return rows, profiles

    rows, profiles = run(t, quiet=False)
    r = residuals(rows)
    say(f"tensions {_kpa(t)}: largest flux difference {np.max(np.abs(r)):.2e}")
    J = None
    for _ in range(MAX_STEPS):
        if np.max(np.abs(r)) <= tol:
            break
        upper = MAX_TENSION_SHARE * np.minimum(
            [row["mean_flow_stress"] for row in rows[:-1]],
            [row["mean_flow_stress"] for row in rows[1:]])
        if J is None:
            J = _jacobian(rows, t, run, upper)
        step = np.linalg.solve(J, -r)
        t_new = np.clip(t + step, 0.0, upper)
        new_rows, new_profiles = run(t_new, quiet=False)
        r_new = residuals(new_rows)
        dt, dr = t_new - t, r_new - r
        if np.dot(dt, dt) > 0.0:                   # Broyden's update of the Jacobian
            J = J + np.outer(dr - J @ dt, dt) / np.dot(dt, dt)
        _check_bounds(sch, t_new, r_new, upper, tol)
        t, r, rows, profiles = t_new, r_new, new_rows, new_profiles
        say(f"tensions {_kpa(t)}: largest flux difference {np.max(np.abs(r)):.2e}")
    if np.max(np.abs(r)) > tol:
        raise TensionError(f"mill.tensions: the interstand tensions did not settle in "
                           f"{MAX_STEPS} steps (largest flux difference "
                           f"{np.max(np.abs(r)):.2e}, tolerance {tol:g})")
    info = {"interstand_tensions": list(map(float, t)), "flux_mismatch": float(np.max(np.abs(r))),
            "tension_runs": runs, "fe_solves": fe}
    return rows, profiles, info


def _jacobian(rows: list[dict], t: np.ndarray, run, upper: np.ndarray) -> np.ndarray:
    """dr/dt by finite differences: the even tensions raised in one run, the odd in another
    (downwards where a tension is at its upper bound)."""
    m = len(t)
    sigma = float(np.mean([row["mean_flow_stress"] for row in rows]))
    base = _log_flux(rows)
    J = np.zeros((m, m))
    for colour in (0, 1):
        moved = np.arange(m) % 2 == colour
        if not moved.any():
            continue
        h = np.where(t + STEP_SHARE * sigma <= upper, 1.0, -1.0) * STEP_SHARE * sigma
        tt = np.where(moved, t + h, t)
        q = _log_flux(run(tt)[0]) - base
        for i in np.flatnonzero(moved):            # tension i: stand i's front, i+1's back
            dq = np.zeros(m + 1)
            dq[i], dq[i + 1] = q[i] / h[i], q[i + 1] / h[i]
            J[:, i] = np.diff(dq)
    return J


def _check_bounds(sch, t, r, upper, tol) -> None:
    """A tension pinned at a bound while its residual still asks to go beyond it."""
    for k in range(len(t)):
        pair = f"{sch.pass_name(k)} and {sch.pass_name(k + 1)}"
        if t[k] <= 0.0 and r[k] < -tol:
            raise TensionError(
                f"mill.tensions: the roll speeds need a compressive force between stands "
                f"{pair} (stand {k + 2} too slow for stand {k + 1}'s exit flux: the strip "
                f"would loop); raise stand {k + 2}'s speed or lower stand {k + 1}'s")
        if t[k] >= upper[k] and r[k] > tol:
            raise TensionError(
                f"mill.tensions: the roll speeds need more than {MAX_TENSION_SHARE:g} of the "
                f"flow stress ({upper[k] / MAX_TENSION_SHARE:.4g} Pa) as tension between "
                f"stands {pair} (stand {k + 2} too fast); lower its speed")


def _kpa(t) -> str:
    return "[" + ", ".join(f"{1e-6 * x:.3f}" for x in t) + "] MPa"
