"""Thermal data of the strip and of its boundary (issue 16; beyond the report: Touloupoulos 2020
has no temperature). SI units: K, kg/m^3, J/(kg K), W/(m K), W/(m^2 K).

- :class:`ThermalProperties`: density rho, specific heat c and conductivity k, each a constant or
  a table of (T, value) pairs, piecewise linear in T and constant beyond the ends; the volumetric
  heat capacity rho c(T), k(T) and the enthalpy per volume H(T) = int_ref^T rho c dT (exact: on
  each interval between the merged breakpoints rho and c are linear, rho c quadratic, H cubic)
  as NGSolve CoefficientFunctions of a temperature CF, and in numpy for tests.
- :class:`ThermalBoundary`: entry, roll and ambient temperatures, the heat-transfer laws of the
  roll contact and of the free surfaces (``model/heat_transfer``; by default a constant
  coefficient and convection with radiation), the share of the friction heat that goes into
  the strip and the Taylor-Quinney factor.

Bad input raises :class:`ThermalInputError` naming the field and the allowed range.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Union

import numpy as np

from hotroll.model.heat_transfer import ConstantConductance, ConvectionRadiation, HeatTransferLaw

Table = tuple  # ((T0, v0), (T1, v1), ...), T in K strictly increasing
Value = Union[float, Table]


class ThermalInputError(ValueError):
    """Bad thermal input: the message names the field and the allowed range."""


def finite_number(name: str, value, low: float, low_open: bool, high: float | None, unit: str) -> float:
    """``value`` as a finite float in the range, or ThermalInputError naming ``name``."""
    if high is not None:
        rule = f"must be in [{low:g}, {high:g}]"
    else:
        rule = f"must be a finite number {'>' if low_open else '>='} {low:g}"
    rule += f" ({unit})" if unit else ""
    try:
        if isinstance(value, bool):
            raise TypeError
        v = float(value)
    except (TypeError, ValueError):
        raise ThermalInputError(f"thermal.{name} = {value!r}: {rule}") from None
    bad = (not math.isfinite(v) or v < low or (low_open and v <= low)
           or (high is not None and v > high))
    if bad:
        raise ThermalInputError(f"thermal.{name} = {value!r}: {rule}")
    return v


def check_property(name: str, value, unit: str) -> float | Table:
    """A positive finite constant, or a table of at least 2 (T, value) pairs with T > 0 strictly
    increasing and positive finite values; returned as a float or a tuple of float pairs."""
    rule = (f"must be a positive finite number ({unit}) or a table of at least 2 (T in K, "
            f"value) pairs with 0 < T strictly increasing and positive finite values")
    if not isinstance(value, (list, tuple, np.ndarray)):
        try:
            return finite_number(name, value, 0.0, True, None, unit)
        except ThermalInputError:
            raise ThermalInputError(f"thermal.{name} = {value!r}: {rule}") from None
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ThermalInputError(f"thermal.{name} = {value!r}: {rule}") from None
    ok = (arr.ndim == 2 and arr.shape[0] >= 2 and arr.shape[1] == 2
          and bool(np.all(np.isfinite(arr))) and bool(np.all(arr > 0.0))
          and bool(np.all(np.diff(arr[:, 0]) > 0.0))) if arr.size else False
    if not ok:
        raise ThermalInputError(f"thermal.{name} = {value!r}: {rule}")
    return tuple((float(t), float(v)) for t, v in arr)


def _knots(p) -> tuple[np.ndarray, np.ndarray]:
    """Breakpoints and values of a property (a constant has none)."""
    if isinstance(p, tuple):
        a = np.array(p, dtype=float)
        return a[:, 0], a[:, 1]
    return np.zeros(0), np.array([float(p)])


def _clamp(T, lo: float, width: float, cf: bool):
    """min(max(T - lo, 0), width), for a CoefficientFunction (``cf``) or a numpy array."""
    if cf:
        from ngsolve import IfPos

        return IfPos(T - lo, IfPos(T - lo - width, width, T - lo), 0.0)
    return np.clip(T - lo, 0.0, width)


def _linear(p, T, cf: bool):
    """Piecewise-linear interpolation of property ``p`` at T, constant beyond the ends."""
    t, v = (a.tolist() for a in _knots(p))     # python floats: numpy scalars and CFs mix badly
    if cf and len(t) == 0:
        from ngsolve import CoefficientFunction

        return CoefficientFunction(v[0])
    out = v[0] + 0.0 * T
    for i in range(len(t) - 1):
        slope = (v[i + 1] - v[i]) / (t[i + 1] - t[i])
        if slope != 0.0:
            out = out + slope * _clamp(T, t[i], t[i + 1] - t[i], cf)
    return out


@dataclass(frozen=True)
class ThermalProperties:
    """rho (kg/m^3), c (J/(kg K)), k (W/(m K)): constants or (T, value) tables."""

    density: Value
    specific_heat: Value
    conductivity: Value

    def __post_init__(self):
        for name, unit in (("density", "kg/m^3"), ("specific_heat", "J/(kg K)"),
                           ("conductivity", "W/(m K)")):
            object.__setattr__(self, name, check_property(name, getattr(self, name), unit))

    # --- values ------------------------------------------------------------------------------
    def rho_c(self, T):
        """Volumetric heat capacity rho(T) c(T), J/(m^3 K), CF of the temperature CF ``T``."""
        return _linear(self.density, T, True) * _linear(self.specific_heat, T, True)

    def k(self, T):
        """Conductivity k(T), W/(m K), CF of the temperature CF ``T``."""
        return _linear(self.conductivity, T, True)

    def rho_c_values(self, T) -> np.ndarray:
        T = np.asarray(T, dtype=float)
        return _linear(self.density, T, False) * _linear(self.specific_heat, T, False)

    def k_values(self, T) -> np.ndarray:
        return _linear(self.conductivity, np.asarray(T, dtype=float), False)

    # --- enthalpy ----------------------------------------------------------------------------
    def enthalpy(self, T, reference: float = 0.0):
        """Enthalpy per volume H(T) - H(reference) = int_reference^T rho c dT, J/m^3, CF of the
        temperature CF ``T`` (below a table rho c keeps its first value, so the default
        reference 0 K gives rho c T for constants)."""
        return self._enthalpy(T, True) - float(self._enthalpy(np.array(reference), False))

    def enthalpy_values(self, T, reference: float = 0.0) -> np.ndarray:
        """numpy version of :meth:`enthalpy`."""
        T = np.asarray(T, dtype=float)
        return self._enthalpy(T, False) - self._enthalpy(np.array(float(reference)), False)

    def is_constant(self) -> bool:
        return not any(isinstance(p, tuple)
                       for p in (self.density, self.specific_heat, self.conductivity))

    def _enthalpy(self, T, cf: bool):
        """int_{T_0}^T rho c dT with T_0 the first merged breakpoint (0 K without tables).

        On [t_j, t_j + d_j] with s = T - t_j: rho = r + r' s, c = c + c' s, so the integral is
        r c s + (r c' + r' c) s^2 / 2 + r' c' s^3 / 3; below the first and above the last
        breakpoint rho c is constant and H linear."""
        t = np.union1d(_knots(self.density)[0], _knots(self.specific_heat)[0])
        if t.size == 0:
            return float(self.rho_c_values(0.0)) * T
        rho = _linear(self.density, t, False).tolist()
        cap = _linear(self.specific_heat, t, False).tolist()
        t = t.tolist()
        out = rho[0] * cap[0] * _outside(T, t[0], -1.0, cf)      # linear below t_0
        for j in range(len(t) - 1):
            d = t[j + 1] - t[j]
            dr, dc = (rho[j + 1] - rho[j]) / d, (cap[j + 1] - cap[j]) / d
            s = _clamp(T, t[j], d, cf)
            out = out + s * (rho[j] * cap[j] + s * (0.5 * (rho[j] * dc + dr * cap[j])
                                                    + s * dr * dc / 3.0))
        return out + rho[-1] * cap[-1] * _outside(T, t[-1], 1.0, cf)   # and above t_N


def _outside(T, t: float, side: float, cf: bool):
    """max(T - t, 0) (side = 1) or min(T - t, 0) (side = -1), CF or numpy."""
    if cf:
        from ngsolve import IfPos

        return IfPos(side * (T - t), T - t, 0.0)
    return np.where(side * (T - t) > 0.0, T - t, 0.0)


@dataclass(frozen=True)
class ThermalBoundary:
    """Boundary and source data of the thermal problem (K, W/(m^2 K), fractions)."""

    entry_temperature: float      # strip temperature on the inlet face, K
    roll_temperature: float       # roll surface temperature, K
    ambient_temperature: float    # air and surroundings, K
    htc_contact: float            # strip-roll heat-transfer coefficient, W/(m^2 K)
    htc_air: float                # free-surface convection coefficient, W/(m^2 K)
    emissivity: float             # of the free surface, radiating to the ambient
    friction_heat_to_strip: float = 0.5   # share of the friction power entering the strip
    taylor_quinney: float = 0.9           # share of the plastic power turned into heat
    entry_profile: object = None          # a ThicknessProfile of the inlet's T(eta), K, or
                                          # None: entry_temperature everywhere on the inlet
    contact: HeatTransferLaw | None = None  # the contact's law (model/heat_transfer; None:
                                            # constant, htc_contact)
    surface: HeatTransferLaw | None = None  # the free tops' law (None: convection_radiation,
                                            # htc_air and emissivity)

    def __post_init__(self):
        rules = {"entry_temperature": (0.0, True, None, "K"),
                 "roll_temperature": (0.0, True, None, "K"),
                 "ambient_temperature": (0.0, True, None, "K"),
                 "htc_contact": (0.0, False, None, "W/(m^2 K)"),
                 "htc_air": (0.0, False, None, "W/(m^2 K)"),
                 "emissivity": (0.0, False, 1.0, ""),
                 "friction_heat_to_strip": (0.0, False, 1.0, ""),
                 "taylor_quinney": (0.0, False, 1.0, "")}
        for name, (low, low_open, high, unit) in rules.items():
            object.__setattr__(self, name,
                               finite_number(name, getattr(self, name), low, low_open, high, unit))
        if self.contact is None:
            object.__setattr__(self, "contact", ConstantConductance(self.htc_contact))
        if self.surface is None:
            object.__setattr__(self, "surface", ConvectionRadiation(self.htc_air, self.emissivity))
        for name, kind in (("contact", "contact"), ("surface", "surface")):
            law = getattr(self, name)
            if not isinstance(law, HeatTransferLaw) or law.kind != kind:
                raise ThermalInputError(f"thermal.{name}_law: a {kind} law of "
                                        f"model/heat_transfer, got {law!r}")
