"""The thermal part of the case (issue 16): the ``[thermal]`` section and the strip's thermal
properties in ``[material]`` (``density``, ``specific_heat``, ``conductivity``).

A case with a ``[thermal]`` section solves the coupled thermo-mechanical problem
(``hotroll/thermal``); without one the run is isothermal at ``plate.temperature``, as before.
A property is a constant or a table of ``[T (K), value]`` pairs, piecewise linear in T and
constant beyond its ends.
"""

from __future__ import annotations

from typing import Any, Union

from hotroll.config.base import Section, field, has_text
from hotroll.model.thermal_properties import ThermalBoundary, ThermalInputError
from hotroll.model.thermal_properties import check_property as thermal_property

#: A thermal property: a constant, or [[T (K), value], ...] with strictly increasing T.
Property = Union[float, list[tuple[float, float]]]

PROPERTY_UNITS = {"density": "kg/m^3", "specific_heat": "J/(kg K)", "conductivity": "W/(m K)"}


def check_property(key: str, value: Any) -> Any:
    """A constant > 0 or a table of >= 2 [T, value] pairs, T > 0 strictly increasing, values
    > 0 (``hotroll.model.thermal_properties.check_property``); a table comes back as a list of pairs.
    The case error names ``material.<key>`` and the allowed form."""
    if value is None:
        return None
    if has_text(value):         # numpy would read "7800" and true as numbers
        raise ValueError(f"numbers, got {value!r}")
    try:
        checked = thermal_property(key, value, PROPERTY_UNITS[key])
    except ThermalInputError as e:
        raise ValueError(str(e)) from None
    return list(checked) if isinstance(checked, tuple) else checked


class ThermalConfig(Section):
    """Heat sources and losses of the strip (W, K, m); the properties are in ``[material]``."""

    taylor_quinney: float = field(0.9, "share of the plastic work that becomes heat (beta)", "",
                                   "in [0, 1]", ge=0, le=1)
    friction_heat_to_strip: float = field(
        0.5, "share of the friction heat that goes into the strip (the rest into the roll)", "",
        "in [0, 1]", ge=0, le=1)
    htc_contact: float = field(..., "heat transfer coefficient strip -> roll in the contact",
                                "W/(m^2 K)", ">= 0", ge=0)
    roll_temperature: float = field(..., "roll surface temperature", "K", "> 0", gt=0)
    htc_air: float = field(..., "convective heat transfer coefficient on the free surfaces",
                            "W/(m^2 K)", ">= 0", ge=0)
    emissivity: float = field(..., "emissivity of the free surfaces (radiation)", "",
                               "in [0, 1]", ge=0, le=1)
    ambient_temperature: float = field(293.15, "ambient temperature (air and radiation)", "K",
                                        "> 0", gt=0)
    mesh_refinement: float = field(
        1.0, "the temperature's strip mesh finer by this factor (rows and columns; for "
        "convergence studies)", "", "in [0.25, 16]", ge=0.25, le=16)

    def boundary(self, entry_temperature: float, entry_profile=None):
        """The solver's boundary data (``hotroll.model.thermal_properties.ThermalBoundary``);
        ``entry_profile``: the inlet's T(eta) (``process.profile.ThicknessProfile``)."""
        return ThermalBoundary(
            entry_temperature=entry_temperature, roll_temperature=self.roll_temperature,
            ambient_temperature=self.ambient_temperature, htc_contact=self.htc_contact,
            htc_air=self.htc_air, emissivity=self.emissivity,
            friction_heat_to_strip=self.friction_heat_to_strip,
            taylor_quinney=self.taylor_quinney, entry_profile=entry_profile)
