"""The Hensel-Spittel law.

Hensel-Spittel, Spittel's form (Spittel & Spittel, Landolt-Boernstein VIII/2C, 2009):

    sigma = A e^(m1 T) T^m9 eps^m2 e^(m4/eps) (1+eps)^(m5 T + m6) e^(m7 eps) edot^(m3 + m8 T)

with T in deg C *inside the formula* (as the fits are published; ``temperature`` is converted,
T_C = T_K - 273.15) and A in Pa (published tables give MPa: multiply by 1e6).  m6 is not in
Spittel's form; it is kept (default 0) because the Freiberg/pyroll variant has it.

The pyroll-freiberg-flow-stress package evaluates the same formula at (eps + 0.1, edot + 0.1)
("baseStrain/baseStrainRate").  We keep Spittel's original form; pyroll's value at (eps, edot, T)
equals ``HenselSpittel.sigma(eps + 0.1, edot + 0.1, T)`` here (tested).
"""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

from hotroll.model.flow_stress.base import (
    CELSIUS_OFFSET,
    DEFAULT_EPS0,
    DEFAULT_STRAIN_MIN,
    FlowStressLaw,
    Range,
    ValidityRange,
    backend,
    backend_of,
    finite,
)
from hotroll.model.flow_stress.registry import LawSpec, Parameter, register


class HenselSpittel(FlowStressLaw):
    """Hensel-Spittel law in Spittel's form (see the module docstring for formula and policy).

    Parameters
    ----------
    A : float
        Pa (> 0).  Published tables give MPa: pass ``A_MPa * 1e6``.
    m1, m2, m3, m4, m5, m7, m8, m9 : float
        As published, for T in deg C inside the formula.  m6 (keyword only, default 0) is the
        Freiberg/pyroll extra exponent of (1 + eps).
    validity : ValidityRange, optional
        The fit's published ranges (temperature in K).
    strain_min : float, optional
        Strain floor (> 0); default: lower strain bound of ``validity``, else 0.03.
    eps0 : float
        Regularisation strain rate of :meth:`viscosity` (1/s).
    """

    PARAMS = ("A", "m1", "m2", "m3", "m4", "m5", "m6", "m7", "m8", "m9")

    @property
    def depends_on_strain(self) -> bool:
        """The strain terms eps^m2, e^(m4/eps), (1+eps)^(m5 T + m6), e^(m7 eps)."""
        return any(getattr(self, k) != 0.0 for k in ("m2", "m4", "m5", "m6", "m7"))

    def __init__(self, A: float, m1: float = 0.0, m2: float = 0.0, m3: float = 0.0,
                 m4: float = 0.0, m5: float = 0.0, m7: float = 0.0, m8: float = 0.0,
                 m9: float = 0.0, *, m6: float = 0.0, validity: Optional[ValidityRange] = None,
                 strain_min: Optional[float] = None, eps0: float = DEFAULT_EPS0, name: str = ""):
        self.A = finite("A", A)
        if not self.A > 0.0:
            raise ValueError(f"A must be > 0 (Pa), got {A!r}")
        for key, val in (("m1", m1), ("m2", m2), ("m3", m3), ("m4", m4), ("m5", m5), ("m6", m6),
                         ("m7", m7), ("m8", m8), ("m9", m9)):
            setattr(self, key, finite(key, val))
        self.eps0 = finite("eps0", eps0)
        if not self.eps0 > 0.0:
            raise ValueError(f"eps0 must be > 0 (1/s), got {eps0!r}")
        self.validity = validity if validity is not None else ValidityRange()
        if strain_min is None:
            s = self.validity.strain
            strain_min = s[0] if s is not None and s[0] > 0 else DEFAULT_STRAIN_MIN
        self.strain_min = finite("strain_min", strain_min)
        if not self.strain_min > 0.0:
            raise ValueError(f"strain_min must be > 0, got {strain_min!r}")
        self.name = name
        # rate exponent m3 + m8 T_C in (0, 1]: over the validity temperatures when known
        lo, hi = self.admissible_temperature_range()  # raises if empty
        t = self.validity.temperature
        if t is not None and not (lo <= t[0] and t[1] <= hi
                                  and self._m_ok(t[0]) and self._m_ok(t[1])):
            raise ValueError(
                f"rate exponent m3 + m8*T_C must lie in (0, 1] over the validity temperature range "
                f"{t} K; it is {self.rate_exponent(t[0]):.4g} .. {self.rate_exponent(t[1]):.4g}"
                f" (admissible T: {lo:.6g} .. {hi:.6g} K)")
        if self.m9 != 0.0 and t is not None and t[0] <= CELSIUS_OFFSET:
            raise ValueError(f"m9 != 0 needs T_C > 0 (T > {CELSIUS_OFFSET} K) over the validity "
                             f"temperature range, got {t} K")

    # -- helpers
    def _m_ok(self, T_K: float) -> bool:
        m = self.rate_exponent(T_K)
        return 0.0 < m <= 1.0

    def admissible_temperature_range(self) -> Range:
        """Open/closed interval of T (K) where the rate exponent m3 + m8 T_C lies in (0, 1].

        Raises ValueError (naming m3/m8) if there is none with T > 0 K.
        """
        m3, m8 = self.m3, self.m8
        if m8 == 0.0:
            if not 0.0 < m3 <= 1.0:
                raise ValueError(f"rate exponent m3 (with m8 = 0) must lie in (0, 1], got {m3!r}")
            return (0.0, math.inf)
        t0 = -m3 / m8 + CELSIUS_OFFSET          # m = 0
        t1 = (1.0 - m3) / m8 + CELSIUS_OFFSET   # m = 1
        lo, hi = (t0, t1) if m8 > 0 else (t1, t0)
        lo = max(lo, 0.0)
        if not lo < hi:
            raise ValueError(f"rate exponent m3 + m8*T_C (m3={m3}, m8={m8}) is nowhere in (0, 1] "
                             f"for T > 0 K")
        return (lo, hi)

    # -- the law
    def rate_exponent(self, temperature):
        ops = backend_of(temperature)
        T_C = ops.prep(temperature) - CELSIUS_OFFSET
        return self.m3 + self.m8 * T_C

    def sigma(self, strain, strain_rate, temperature):
        ops = backend(strain, strain_rate, temperature)
        T_C = backend_of(temperature).prep(temperature) - CELSIUS_OFFSET
        eps = backend_of(strain).floor(backend_of(strain).prep(strain), self.strain_min)
        rate = backend_of(strain_rate).prep(strain_rate)
        ln_eps = backend_of(strain).log(eps)
        ln_1eps = backend_of(strain).log(1.0 + eps)
        with np.errstate(divide="ignore"):  # edot = 0 gives sigma = 0 (log -> -inf, exp -> 0)
            ln_rate = backend_of(strain_rate).log(rate)
        expo = (self.m1 * T_C                                # e^(m1 T)
                + self.m2 * ln_eps                           # eps^m2
                + self.m4 / eps                              # e^(m4/eps)
                + (self.m5 * T_C + self.m6) * ln_1eps        # (1+eps)^(m5 T + m6)
                + self.m7 * eps                              # e^(m7 eps)
                + (self.m3 + self.m8 * T_C) * ln_rate)       # edot^(m3 + m8 T)
        if self.m9 != 0.0:
            expo = expo + self.m9 * backend_of(temperature).log(T_C)  # T^m9
        return self.A * ops.exp(expo)

    def params(self) -> dict:
        return {k: getattr(self, k) for k in self.PARAMS}

    def describe(self) -> dict:
        return {
            "law": "HenselSpittel",
            "name": self.name,
            "formula": ("sigma = A e^(m1 T) T^m9 eps^m2 e^(m4/eps) (1+eps)^(m5 T + m6) e^(m7 eps) "
                        "edot^(m3 + m8 T), T in degC"),
            "parameters": self.params(),
            "parameter_units": {"A": "Pa", "m1": "1/degC", "m5": "1/degC", "m8": "1/degC",
                                "others": "1"},
            "validity": self.validity.as_dict(),
            "strain_min": self.strain_min,
            "eps0_1_per_s": self.eps0,
            "admissible_temperature_K": self.admissible_temperature_range(),
            "out_of_range_policy": ("strain floored at strain_min; strain, rate and temperature "
                                    "otherwise extrapolated by the formula; see in_range()"),
            "units": {"sigma": "Pa", "strain_rate": "1/s", "temperature": "K"},
        }

    def __repr__(self) -> str:
        p = ", ".join(f"{k}={v!r}" for k, v in self.params().items() if v != 0.0 or k == "A")
        return f"HenselSpittel({p}, strain_min={self.strain_min!r}, name={self.name!r})"


COEFFICIENTS = ("A", "m1", "m2", "m3", "m4", "m5", "m7", "m8", "m9")


def _build(p: dict, eps0: float) -> HenselSpittel:
    return HenselSpittel(**{k: p.get(k, 0.0) for k in COEFFICIENTS}, eps0=eps0)


def _check(p: dict) -> list[tuple[str, str]]:
    """The law's own checks: its rate exponent m3 + m8 T in (0, 1] somewhere above 0 K."""
    try:
        _build(p, DEFAULT_EPS0)
    except ValueError as e:
        return [("m3", f"{e}; allowed: m3 + m8 T_C (T in degC) in (0, 1] at some T > 0 K "
                       "(m3 omitted: 0)")]
    return []


def _coefficient(name: str, text: str, unit: str = "") -> Parameter:
    return Parameter(name, f"Hensel-Spittel {name} ({text})", unit, "a finite number (omit: 0)",
                     required=False)


SPEC = register(LawSpec(
    name="hensel-spittel",
    summary="sigma = A e^(m1 T) T^m9 eps^m2 e^(m4/eps) (1+eps)^(m5 T) e^(m7 eps) edot^(m3 + m8 T), "
            "T in degC (or a grade: model/grades.py)",
    source="M. Spittel, T. Spittel, Landolt-Boernstein VIII/2C (Springer 2009)",
    parameters=(Parameter("A", "Hensel-Spittel A", "Pa", "> 0", gt=0),
                _coefficient("m1", "temperature, e^(m1 T)", "1/degC"),
                _coefficient("m2", "strain, eps^m2"),
                _coefficient("m3", "rate, edot^m3"),
                _coefficient("m4", "e^(m4/eps)"),
                _coefficient("m5", "(1+eps)^(m5 T)", "1/degC"),
                _coefficient("m7", "e^(m7 eps)"),
                _coefficient("m8", "edot^(m8 T)", "1/degC"),
                _coefficient("m9", "T^m9")),
    build=_build,
    check=_check,
))
