"""The thermal part of the case (issue 16): the ``[thermal]`` section and the strip's thermal
properties in ``[material]`` (``density``, ``specific_heat``, ``conductivity``).

A case with a ``[thermal]`` section solves the coupled thermo-mechanical problem
(``hotroll/thermal``); without one the run is isothermal at ``plate.temperature``, as before.
A property is a constant or a table of ``[T (K), value]`` pairs, piecewise linear in T and
constant beyond its ends.
"""

from __future__ import annotations

from typing import Any, Literal, Union

from pydantic import create_model, model_validator

from hotroll.config.base import Problems, Section, field, has_text, with_units
from hotroll.config.law_section import parameter_fields
from hotroll.model.heat_transfer import HEAT_TRANSFER_LAWS, KINDS, laws_of
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
    unit = PROPERTY_UNITS[key]
    value = with_units(value, unit, columns=("K", unit))      # "7.85 t/m^3", [["1000 degC", ..]]
    if has_text(value):         # numpy would read "7800" and true as numbers
        raise ValueError(f"numbers, got {value!r}")
    try:
        checked = thermal_property(key, value, PROPERTY_UNITS[key])
    except ThermalInputError as e:
        raise ValueError(str(e)) from None
    return list(checked) if isinstance(checked, tuple) else checked


class _ThermalSection(Section):
    """Heat sources and losses of the strip (W, K, m); the properties are in ``[material]``.
    The heat-transfer laws of the contact and of the free surfaces come from the registry
    (``model/heat_transfer``), each with its own parameters."""

    taylor_quinney: float = field(0.9, "share of the plastic work that becomes heat (beta)", "",
                                   "in [0, 1]", ge=0, le=1)
    friction_heat_to_strip: float = field(
        0.5, "share of the friction heat that goes into the strip (the rest into the roll)", "",
        "in [0, 1]", ge=0, le=1)
    roll_temperature: float = field(..., "roll surface temperature", "K", "> 0", gt=0)
    ambient_temperature: float = field(293.15, "ambient temperature (air and radiation)", "K",
                                        "> 0", gt=0)
    mesh_refinement: float = field(
        1.0, "the temperature's strip mesh finer by this factor (rows and columns; for "
        "convergence studies)", "", "in [0.25, 16]", ge=0.25, le=16)

    @model_validator(mode="after")
    def _check_laws(self):
        problems = []
        chosen = {kind: HEAT_TRANSFER_LAWS[getattr(self, f"{kind}_law")] for kind in KINDS}
        own = {p.name for spec in chosen.values() for p in spec.parameters}
        for kind, spec in chosen.items():
            problems += [f"thermal.{p.name}: required for {kind}_law = \"{spec.name}\" (allowed: "
                         f"{p.allowed})" for p in spec.parameters if getattr(self, p.name) is None]
        for other in HEAT_TRANSFER_LAWS.values():
            problems += [f"thermal.{p.name}: only for {other.kind}_law = \"{other.name}\" (the "
                         f"{other.kind}_law is \"{chosen[other.kind].name}\")"
                         for p in other.parameters
                         if p.name not in own and getattr(self, p.name) is not None]
        if problems:
            raise Problems(problems)
        return self

    def law(self, kind: str, **override):
        """The ``kind`` ("contact" or "surface") law with its parameters (``override``: some
        replaced, as a schedule's transport does)."""
        spec = HEAT_TRANSFER_LAWS[getattr(self, f"{kind}_law")]
        values = {p.name: getattr(self, p.name) for p in spec.parameters}
        values.update({k: v for k, v in override.items() if k in values and v is not None})
        return spec.build(values)

    def boundary(self, entry_temperature: float, entry_profile=None):
        """The solver's boundary data (``hotroll.model.thermal_properties.ThermalBoundary``);
        ``entry_profile``: the inlet's T(eta) (``process.profile.ThicknessProfile``)."""
        return ThermalBoundary(
            entry_temperature=entry_temperature, roll_temperature=self.roll_temperature,
            ambient_temperature=self.ambient_temperature,
            htc_contact=self.htc_contact or 0.0, htc_air=self.htc_air or 0.0,
            emissivity=self.emissivity or 0.0,
            friction_heat_to_strip=self.friction_heat_to_strip,
            taylor_quinney=self.taylor_quinney, entry_profile=entry_profile,
            contact=self.law("contact"), surface=self.law("surface"))


def _law_choice(kind: str):
    laws = laws_of(kind)
    return (Literal[tuple(laws)], field(
        next(iter(laws)), f"heat-transfer law of the {kind}: " + "; ".join(
            f"{s.name} ({s.summary})" for s in laws.values()), "",
        ", ".join(f'"{n}"' for n in laws)))


ThermalConfig = create_model(
    "ThermalConfig", __base__=_ThermalSection, __module__=__name__,
    contact_law=_law_choice("contact"), surface_law=_law_choice("surface"),
    **parameter_fields(HEAT_TRANSFER_LAWS),
)
ThermalConfig.__doc__ = _ThermalSection.__doc__
