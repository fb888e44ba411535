"""The flow stress a PyRolL flat pass is rolled with in hotroll (``hotroll.pyroll``; issues 17, 51).

From what the in profile gives, first found wins:

1. a constant ``flow_stress`` set on the profile (Pa; PyRolL's tests' and examples' usual
   ``flow_stress=100e6``). As in PyRolL, a value set on a profile wins over every hook function,
   so over a ``flow_stress_function`` and a grade. hotroll's FE needs a rate-sensitive law
   (Norton-Hoff needs 0 < m <= 1; a rate-independent law has m = 0), so the constant becomes
   the Norton-Hoff law sigma = K 3^((m+1)/2) edot^m with m = ``rate_exponent``
   (``hotroll.pyroll.Config.FLOW_STRESS_RATE_EXPONENT``, 0.1) and K such that sigma equals the
   given value at the pass's mean equivalent strain rate U / l_c x 2/sqrt(3) ln(h0/h1) (1/s):
   the constant exactly there, within (rate ratio)^m elsewhere. Logged once per pass at
   WARNING with K, m and that rate;
2. a ``flow_stress_function`` (e.g. pyroll-freiberg-flow-stress): a Hensel-Spittel law fitted
   over the pass's range (``model/flow_stress_fit.py``), the fit's error in the pass's
   ``hotroll_result["flow_stress_fit"]``;
3. the hotroll grade ``material`` names (S355J2, C45, C20, Al99.5).

A ``flow_stress`` set but not a finite positive number is no flow stress hotroll can use: the
pass is left to PyRolL with that reason (``missing``). Only model-layer imports here (no
pyroll-core, no ``hotroll.pyroll``): the profile is read through ``has_value``/``has_set``
(``hotroll/pyroll_inputs.py`` reads the rest of a pass's data).
"""
from __future__ import annotations

import logging
import math

from hotroll.model.flow_stress_fit import fit_hensel_spittel
from hotroll.model.grades import list_grades
from hotroll.pyroll_inputs import value

_LOG = logging.getLogger("hotroll.pyroll")


def grade(profile) -> str | None:
    """The hotroll grade the profile's ``material`` (a name or a list of names) names."""
    names = value(profile, "material", None)
    names = [names] if isinstance(names, str) else list(names or [])
    known = {g.lower(): g for g in list_grades()}
    for n in names:
        if str(n).lower() in known:
            return known[str(n).lower()]
    return None


def given_constant(profile):
    """The ``flow_stress`` set on the profile (not computed by a hook function), or None."""
    has_set = getattr(profile, "has_set", None)
    if has_set is None or not has_set("flow_stress"):
        return None
    return profile.__dict__.get("flow_stress")


def _usable(sigma) -> bool:
    try:
        return math.isfinite(float(sigma)) and float(sigma) > 0.0
    except (TypeError, ValueError):
        return False


def missing(profile) -> str | None:
    """Why hotroll has no flow stress for the profile (None: it has one)."""
    sigma = given_constant(profile)
    if sigma is not None:
        return None if _usable(sigma) else (
            f"the profile's flow_stress {sigma!r} (Pa) is no finite positive number")
    if value(profile, "flow_stress_function", None) is None and grade(profile) is None:
        return (f"no flow stress: neither a flow_stress (Pa) nor a flow_stress_function on the "
                f"profile, and its material {value(profile, 'material', None)!r} is no hotroll "
                f"grade ({', '.join(list_grades())})")
    return None


def mean_rate(h0: float, h1: float, U: float, lc: float) -> float:
    """The pass's mean equivalent strain rate (1/s): U / l_c x 2/sqrt(3) ln(h0/h1)."""
    return U / lc * 2.0 / math.sqrt(3.0) * math.log(h0 / h1)


def constant_law(sigma: float, rate: float, m: float) -> dict:
    """The [material] table of the Norton-Hoff law with exponent ``m`` equal to ``sigma`` (Pa)
    at the equivalent strain rate ``rate`` (1/s)."""
    K = float(sigma) / (3.0 ** ((m + 1.0) / 2.0) * rate**m)
    return {"law": "norton-hoff", "K": K, "m": m}


def material(rp, T0: float, e0: float, h0: float, h1: float, U: float, lc: float,
             rate_exponent: float) -> tuple[dict, dict]:
    """([material] table, description) of the flat pass ``rp`` entering at T0 (K), strain e0,
    from h0 to h1 (m) under a roll of surface speed U (m/s) and contact length lc (m)."""
    ip = rp.in_profile
    fits = rp.__dict__.setdefault("_hotroll_fits", {})
    box = (T0, e0, h0, h1, U, lc, rate_exponent)
    sigma = given_constant(ip)
    if sigma is not None:
        if not _usable(sigma):
            raise ValueError(f"hotroll.pyroll: pass {rp.label!r}: {missing(ip)}")
        if box not in fits:
            rate = mean_rate(h0, h1, U, lc)
            table = constant_law(sigma, rate, rate_exponent)
            fits[box] = (table, {"source": "in_profile.flow_stress", "flow_stress": float(sigma),
                                 "strain_rate": rate, "m": rate_exponent, "K": table["K"]})
            if not rp.__dict__.get("_hotroll_told_constant"):
                rp.__dict__["_hotroll_told_constant"] = True
                _LOG.warning(
                    "hotroll.pyroll: pass %r: the profile's constant flow_stress %.6g MPa is "
                    "rolled as Norton-Hoff's sigma = K 3^((m+1)/2) edot^m with m = %g "
                    "(Config.FLOW_STRESS_RATE_EXPONENT; hotroll needs 0 < m <= 1) and K = "
                    "%.6g MPa s^m: %.6g MPa at the pass's mean strain rate %.4g 1/s, "
                    "x (rate ratio)^m elsewhere%s", rp.label, float(sigma) / 1e6, rate_exponent,
                    table["K"] / 1e6, float(sigma) / 1e6, rate, _unused(ip))
        table, info = fits[box]
        return dict(table), dict(info)

    func = value(ip, "flow_stress_function", None)
    if func is not None:
        # PyRolL asks a pass for its hooks dozens of times: the fit (343 calls of the
        # function, ~4 ms) once per pass and box
        if box not in fits:
            inc = 2.0 / math.sqrt(3.0) * math.log(h0 / h1)
            rate = U / lc * inc
            fit = fit_hensel_spittel(func, (e0, e0 + 1.5 * inc), (0.05 * rate, 4.0 * rate),
                                     (max(T0 - 250.0, 300.0), T0 + 60.0))
            table = {"law": "hensel-spittel", **{k: v for k, v in fit.law.params().items()
                                                  if k not in ("m4", "m6", "m9")}}
            fits[box] = (table, {"source": "in_profile.flow_stress_function",
                                 "max_rel_error": fit.max_rel_error, "strain": fit.strain,
                                 "strain_rate": fit.strain_rate,
                                 "temperature": fit.temperature})
        table, info = fits[box]
        return dict(table), dict(info)

    name = grade(ip)
    if name is None:
        raise ValueError(f"hotroll.pyroll: pass {rp.label!r}: {missing(ip)}")
    return {"law": "hensel-spittel", "grade": name}, {"source": f"hotroll grade {name}"}


def _unused(profile) -> str:
    """What the set flow_stress overrides, for the log: a flow_stress_function, a grade."""
    parts = []
    if value(profile, "flow_stress_function", None) is not None:
        parts.append("its flow_stress_function")
    name = grade(profile)
    if name is not None:
        parts.append(f"hotroll's grade {name}'s flow stress")
    return (f" ({' and '.join(parts)} not used: a value set on a profile wins, as in PyRolL)"
            if parts else "")
