"""Interstand tensions from the stand speeds of a tandem mill (issue 32, ``mill.tensions =
"from_speeds"``).

With every stand's roll speed given (a cold tandem's set-up, a mill log), the strip between
stands k and k+1 carries the tension t_k (Pa) under which what leaves stand k enters stand
k+1: stand k's exit flux Q_k^out = h_k v_k (its solved exit thickness and speed, v_k = U_k (1
+ f_k) with its forward slip f_k from its own FE solve) is stand k+1's inlet flux Q_{k+1}^in =
h_k v_{k+1}^in (it enters with the thickness stand k left it, ``workflows/schedule``), both
depending on the stands' back and front tensions. The residuals

    r_k = ln Q_{k+1}^in - ln Q_k^out = ln (v_{k+1}^in / v_k),  k = 1 .. n-1,

the strip's speed leaving one stand against its speed entering the next, are driven to |r_k|
<= ``mill.flux_tolerance`` by Newton's method on t. (Before issue 51 they were ln Q_{k+1}^out -
ln Q_k^out: the exit fluxes matched to 4e-5 while each coarse FE stand passes 1.7-2e-3 less
flux out than in, its flux crossing the traced free tops, first order in the mesh size; that
loss went into the strip between the stands, and the next stand entered at the nominal gap.)
Each stand's own loss is reported (``stand_flux_error``, the largest |Q^out / Q^in - 1|) and
named in the progress where it is above the tolerance. The Jacobian is tridiagonal in the
tensions (a stand feels only its own two; the thickness and temperature handed on are weaker
links, left to the iteration): two extra schedule runs measure it by finite differences, the
even tensions moved in one and the odd ones in the other, so every stand sees one moved
tension per run, whatever the number of stands. Broyden's update keeps it current. Each run of
the schedule starts every stand's Newton from its last solve (``workflows/sweep``).

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


def _log_fluxes(rows: list[dict]) -> tuple[np.ndarray, np.ndarray]:
    """(ln Q_k^in, ln Q_k^out): the stands' inlet and exit fluxes (half strip)."""
    return (np.log([r["mass_flux"] for r in rows]),
            np.log([r["mass_flux_out"] for r in rows]))


def residuals(rows: list[dict]) -> np.ndarray:
    """r_k = ln Q_{k+1}^in - ln Q_k^out: stand k+1's inlet flux against stand k's exit."""
    q_in, q_out = _log_fluxes(rows)
    return q_in[1:] - q_out[:-1]


def stand_flux_error(rows: list[dict]) -> float:
    """The largest |Q^out / Q^in - 1| of a stand: the flux its own FE solve loses."""
    return float(max(abs(r["mass_flux_out"] / r["mass_flux"] - 1.0) for r in rows))


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
    leak = stand_flux_error(rows)
    if leak > tol:
        say(f"the strip between the stands carries one flux to {np.max(np.abs(r)):.2e}; within "
            f"a stand its FE solve loses up to {leak:.2e} of the flux (mass_flux_error: it "
            f"crosses the traced free tops, first order in mesh.h_contact), above the flux "
            f"tolerance {tol:g}")
    info = {"interstand_tensions": list(map(float, t)), "flux_mismatch": float(np.max(np.abs(r))),
            "stand_flux_error": leak, "tension_runs": runs, "fe_solves": fe}
    return rows, profiles, info


def _jacobian(rows: list[dict], t: np.ndarray, run, upper: np.ndarray) -> np.ndarray:
    """dr/dt by finite differences: the even tensions raised in one run, the odd in another
    (downwards where a tension is at its upper bound)."""
    m = len(t)
    sigma = float(np.mean([row["mean_flow_stress"] for row in rows]))
    base_in, base_out = _log_fluxes(rows)
    J = np.zeros((m, m))
    for colour in (0, 1):
        moved = np.arange(m) % 2 == colour
        if not moved.any():
            continue
        h = np.where(t + STEP_SHARE * sigma <= upper, 1.0, -1.0) * STEP_SHARE * sigma
        tt = np.where(moved, t + h, t)
        q_in, q_out = _log_fluxes(run(tt)[0])
        q_in, q_out = q_in - base_in, q_out - base_out
        for i in np.flatnonzero(moved):            # tension i: stand i's front, i+1's back
            d_in, d_out = np.zeros(m + 1), np.zeros(m + 1)
            d_in[i:i + 2] = q_in[i:i + 2] / h[i]
            d_out[i:i + 2] = q_out[i:i + 2] / h[i]
            J[:, i] = d_in[1:] - d_out[:-1]        # r_k = ln Q_{k+1}^in - ln Q_k^out
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
