"""The interface of the flow-stress laws sigma_f(strain, strain rate, temperature) and their
secant viscosity; the laws themselves are one module each (``norton_hoff.py``,
``hensel_spittel.py``, ``misaka.py``), registered by name in ``registry.py``.

Every law here has one interface, and every method works on Python floats, numpy arrays and
NGSolve CoefficientFunctions alike (any argument may be a CoefficientFunction; the result is then
one too):

========================================  ==========================================================
``sigma(strain, strain_rate, T)``         uniaxial (von Mises effective) flow stress, Pa
``rate_exponent(T)``                      local m = d ln sigma / d ln edot
``consistency(strain, T)``                K of the Norton-Hoff law that coincides with this law at
                                          (strain, T) for *every* edot:
                                          sigma = K 3^((m+1)/2) edot^m, i.e.
                                          K = sigma(strain, 1, T) / 3^((m+1)/2)   (Pa s^m)
``viscosity(edot2, strain, T, m=None)``   secant viscosity mu with s = mu eps_dot,
                                          mu = 2 sigma(e) / (3 e), e = sqrt(edot2 + eps0^2)  (Pa s)
``power_density(edot, strain, T)``        plastic dissipation s:eps_dot = sigma(edot) edot  (W/m^3)
``range_report`` / ``in_range``           is (strain, edot, T) inside the fit's validity ranges?
``describe()``                            parameters, ranges and units as a plain dict (for output)
========================================  ==========================================================

Units at the interface: strain and strain rate are the equivalent (von Mises) values,
edot = sqrt(2/3 eps_dot:eps_dot) in 1/s, ``edot2`` its square (what
:func:`hotroll.model.material.edot_squared` returns); temperature in **kelvin**; stresses in Pa.

Why ``mu = 2 sigma / (3 edot)``: for the isotropic law s = mu eps_dot the effective stress is
sqrt(3/2 s:s) = mu sqrt(3/2 eps_dot:eps_dot) = mu (3/2) edot; asking it to equal sigma_f(edot)
gives mu.  At edot -> 0, edot is replaced by sqrt(edot^2 + eps0^2) as in (2.21), so that for the
Norton-Hoff law ``viscosity`` is exactly :meth:`hotroll.model.material.NortonHoff.viscosity`.

Evaluation outside the fit (policy, stated once here):

* strain below ``strain_min`` is raised to ``strain_min`` (> 0) in the laws with a power of the
  strain (Hensel-Spittel's eps^m2 and e^(m4/eps), Misaka's eps^0.21 go to 0 or inf at eps = 0):
  the entry of the roll gap has zero strain and the material there has a finite, non-zero yield
  stress.  Default ``strain_min`` = the lower strain
  bound of the fit's validity range when it is known, else :data:`DEFAULT_STRAIN_MIN` = 0.03 (the
  lower strain bound of the Landolt-Boernstein Al99.5 fit in :mod:`hotroll.model.grades`, the
  only LB range we could read).  Below the floor the law is therefore strain independent: the
  flow stress at eps = 0 is sigma(strain_min).
* everything else (strain above the range, strain rate and temperature outside their ranges) is
  evaluated by the formula as it stands: a power law in edot extrapolates benignly, and clamping
  the rate would make the law rigid-plastic (rate-independent) below the clamp, which the secant
  viscosity cannot represent.  This extrapolation is *not* silent: :meth:`range_report` and
  :meth:`in_range` tell, point by point, whether a state lies inside the published ranges, and
  :meth:`in_range` refuses (ValueError) to answer for a law whose ranges are unknown.
* the rate exponent must lie in (0, 1] (Norton-Hoff requirement: monotone, at most linear).  It
  is checked at every numeric call of :meth:`viscosity`, and by each law where it depends on T.
"""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from typing import Any, Optional, Tuple

import numpy as np

from hotroll.model.material import NortonHoff

SQRT3 = 3.0**0.5
LN3 = math.log(3.0)
CELSIUS_OFFSET = 273.15  # T_C = T_K - CELSIUS_OFFSET
DEFAULT_STRAIN_MIN = 0.03
DEFAULT_EPS0 = 1e-4  # 1/s, as NortonHoff.eps0

Range = Tuple[float, float]


# --- backends: numpy or NGSolve ------------------------------------------------------------------
def is_cf(x) -> bool:
    """True if ``x`` is an NGSolve CoefficientFunction (GridFunction, Parameter, ... included)."""
    ng = sys.modules.get("ngsolve")  # nothing can be a CF if ngsolve was never imported
    return ng is not None and isinstance(x, ng.CoefficientFunction)


class NumpyOps:
    exp = staticmethod(np.exp)
    log = staticmethod(np.log)

    @staticmethod
    def floor(x, lo):
        return np.maximum(x, lo)

    @staticmethod
    def prep(x):
        """Python numbers as they are, numpy scalars as Python floats (a float32 scalar would
        keep the law in single precision), anything else as a float64 array."""
        if isinstance(x, (float, int)):
            return x
        if isinstance(x, (np.floating, np.integer)):
            return float(x)
        return np.asarray(x, float)


class NgOps:
    @staticmethod
    def exp(x):
        import ngsolve

        return ngsolve.exp(x)

    @staticmethod
    def log(x):
        import ngsolve

        return ngsolve.log(x)

    @staticmethod
    def floor(x, lo):
        import ngsolve

        return ngsolve.IfPos(x - lo, x, lo)

    @staticmethod
    def prep(x):
        return x


def backend(*xs):
    return NgOps if any(is_cf(x) for x in xs) else NumpyOps


def backend_of(x):
    """Backend for one argument (so that a float strain is floored with numpy even if T is a CF)."""
    return NgOps if is_cf(x) else NumpyOps


def is_numeric(x) -> bool:
    return not is_cf(x)


def finite(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


# --- validity ranges -----------------------------------------------------------------------------
@dataclass(frozen=True)
class ValidityRange:
    """Published validity box of a fit; each entry (low, high) or None when not known.

    ``temperature`` is in kelvin (use :meth:`from_celsius` for ranges published in deg C).
    """

    strain: Optional[Range] = None
    strain_rate: Optional[Range] = None  # 1/s
    temperature: Optional[Range] = None  # K

    def __post_init__(self):
        for name, lower in (("strain", 0.0), ("strain_rate", 0.0), ("temperature", 0.0)):
            r = getattr(self, name)
            if r is None:
                continue
            if len(r) != 2:
                raise ValueError(f"validity range {name} must be a pair (low, high), got {r!r}")
            lo, hi = finite(f"{name} range low", r[0]), finite(f"{name} range high", r[1])
            if not lower <= lo < hi:
                raise ValueError(
                    f"validity range {name} must satisfy {lower} <= low < high, got ({lo}, {hi})")
            object.__setattr__(self, name, (lo, hi))

    @classmethod
    def from_celsius(cls, strain=None, strain_rate=None, temperature_c=None) -> "ValidityRange":
        t = None if temperature_c is None else tuple(v + CELSIUS_OFFSET for v in temperature_c)
        return cls(strain=strain, strain_rate=strain_rate, temperature=t)

    @property
    def complete(self) -> bool:
        return None not in (self.strain, self.strain_rate, self.temperature)

    def as_dict(self) -> dict:
        t = self.temperature
        return {
            "strain": self.strain,
            "strain_rate_1_per_s": self.strain_rate,
            "temperature_K": t,
            "temperature_C": None if t is None else tuple(round(v - CELSIUS_OFFSET, 10) for v in t),
        }


# --- the interface -------------------------------------------------------------------------------
class FlowStressLaw:
    """Base class: subclasses implement :meth:`sigma` and :meth:`rate_exponent`.

    Attributes every law has: ``eps0`` (regularisation strain rate, 1/s), ``validity``
    (:class:`ValidityRange`), ``name``.
    """

    eps0: float = DEFAULT_EPS0
    validity: ValidityRange = ValidityRange()
    name: str = ""
    #: the law depends on the strain: the solvers then carry the strain with the material
    depends_on_strain: bool = False

    # -- to implement
    def sigma(self, strain, strain_rate, temperature):  # pragma: no cover - abstract
        """Uniaxial flow stress in Pa at equivalent strain, equivalent strain rate (1/s), T (K)."""
        raise NotImplementedError

    def rate_exponent(self, temperature):  # pragma: no cover - abstract
        """Local strain-rate sensitivity m = d ln sigma / d ln edot (may depend on T only)."""
        raise NotImplementedError

    def admissible_temperature_range(self) -> Range:
        """Temperatures (K) where the rate exponent lies in (0, 1]: all of them for a constant
        exponent (the laws whose exponent depends on T override it)."""
        return (0.0, math.inf)

    # -- derived, common to all laws
    def consistency(self, strain, temperature):
        """K (Pa s^m) of the Norton-Hoff law equal to this one at (strain, T) for every edot.

        sigma(strain, edot, T) = K 3^((m+1)/2) edot^m with m = rate_exponent(T), exactly, because
        all laws here are pure power laws in edot at fixed (strain, T).
        """
        m = self.rate_exponent(temperature)
        ops = backend(m, strain, temperature)
        return self.sigma(strain, 1.0, temperature) / ops.exp(0.5 * LN3 * (m + 1.0))

    def viscosity(self, edot2, strain=None, temperature=None, m=None):
        """Secant viscosity mu (Pa s) with s = mu eps_dot, regularised as in (2.21).

        mu = 2 sigma(e) / (3 e), e = sqrt(edot2 + eps0^2)
           = 2 K sqrt3^(m-1) (edot2 + eps0^2)^((m-1)/2),  K = consistency(strain, T).

        ``m`` overrides the exponent with K kept (as NortonHoff.viscosity does), e.g. m = 1 for the
        Newtonian first Picard iterate.  Raises ValueError for numeric temperatures at which the
        law's rate exponent leaves (0, 1].
        """
        m_law = self.rate_exponent(temperature)
        if is_numeric(m_law):
            check_exponent(m_law, temperature)
        K = self.consistency(strain, temperature)
        mm = m_law if m is None else m
        ops = backend(edot2, mm, K)
        return 2.0 * K * ops.exp(0.5 * (mm - 1.0) * (LN3 + ops.log(edot2 + self.eps0**2)))

    def power_density(self, edot, strain=None, temperature=None):
        """Plastic dissipation s:eps_dot = sigma(strain, edot, T) * edot, W/m^3 (unregularised)."""
        return self.sigma(strain, edot, temperature) * edot

    def norton_hoff_at(self, strain: float, temperature: float):
        """The :class:`hotroll.model.material.NortonHoff` law frozen at a numeric (strain, T)."""
        K = float(self.consistency(float(strain), float(temperature)))
        m = float(self.rate_exponent(float(temperature)))
        return NortonHoff(K=K, m=m, eps0=self.eps0)

    # -- validity
    def range_report(self, strain, strain_rate, temperature) -> dict:
        """Per variable: boolean (array) 'inside the published range', or None if not known.

        Numeric inputs only (numpy broadcasting).  Key ``inside``: all three inside, or None if
        any of the three ranges is unknown.
        """
        vals = {"strain": strain, "strain_rate": strain_rate, "temperature": temperature}
        if any(is_cf(v) for v in vals.values()):
            raise TypeError("range_report needs numeric values, not CoefficientFunctions")
        out: dict[str, Any] = {}
        for key, v in vals.items():
            r = getattr(self.validity, key)
            a = np.asarray(v, float)
            out[key] = None if r is None else scalar_or_array((a >= r[0]) & (a <= r[1]))
        known = [out[k] for k in vals]
        out["inside"] = None if any(k is None for k in known) else scalar_or_array(
            np.logical_and.reduce(np.broadcast_arrays(*[np.asarray(k) for k in known])))
        return out

    def in_range(self, strain, strain_rate, temperature):
        """True where (strain, edot, T) lie inside all three validity ranges.

        Raises ValueError naming the missing range(s) if the law does not carry them: outside a
        known box, or without a box, the law is an extrapolation and the caller must decide.
        """
        missing = [k for k in ("strain", "strain_rate", "temperature")
                   if getattr(self.validity, k) is None]
        if missing:
            raise ValueError(
                f"validity range(s) {', '.join(missing)} unknown for "
                f"{self.name or type(self).__name__};"
                " cannot tell whether the state is inside the fit")
        return self.range_report(strain, strain_rate, temperature)["inside"]

    def describe(self) -> dict:  # pragma: no cover - overridden
        return {"law": type(self).__name__}


def scalar_or_array(a):
    a = np.asarray(a)
    return bool(a) if a.ndim == 0 else a


def check_exponent(m, temperature):
    a = np.asarray(m, float)
    bad = ~((a > 0.0) & (a <= 1.0))
    if np.any(bad):
        t = np.broadcast_to(np.asarray(temperature if temperature is not None else np.nan, float),
                            a.shape)
        raise ValueError(
            f"rate exponent m must lie in (0, 1]; got m = {a[bad].ravel()[:3]} at temperature "
            f"{t[bad].ravel()[:3]} K")


