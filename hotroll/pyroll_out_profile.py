"""The values hotroll sets on PyRolL's out profiles (``hotroll.pyroll``; issues 17, 32, 51).

PyRolL (pyroll-core 3.1) starts a unit's out profile as a copy of its in profile, and a value
in a profile's ``__dict__`` wins over every hook function; temperature is no root hook in
pyroll-core (pyroll-integral-thermal makes it one). So hotroll sets its values as
post-processors (``Unit.post_processors``): ``SetValues`` puts them on the unit's out profile
and on the profile handed to the next unit. The producers (``register``), each
``unit -> dict | None`` (None: not hotroll's):

- a flat pass hotroll solves: ``temperature``, the FE outlet's mean (K, by heat content);
  also the pass's ``OutProfile.temperature`` hook (tryfirst), which PyRolL asks when a thermal
  plugin made temperature a root hook;
- a plain ``Transport`` after such a pass, with ``Config.TRANSPORT_COOLING`` and no other loaded
  plugin giving a transport's out temperature: ``temperature`` cooled by hotroll's interpass
  model (``model/interpass.cool``). With a thermal plugin (pyroll-integral-thermal) PyRolL's own
  cooling between passes is left untouched, from hotroll's exit temperature;
- ``hotroll.pyroll_microstructure`` registers its grain size, recrystallised fraction, ...;
- a ``PassSequence``: its out profile gets what its last unit's got (recursively), so
  ``sequence.out_profile.temperature`` is the last pass's FE exit mean, not the entry
  temperature PyRolL copied (PyRolL hands a sequence's root hooks, such as the strain, on from
  its last unit, but not the temperature). A sequence hotroll did not touch sees nothing.

No root hook is added: one for temperature breaks pyroll-core's own tests (a profile without a
temperature, docs/notes/issue51-research.md 3).
"""
from __future__ import annotations

try:
    from pyroll.core import PassSequence, RollPass, Transport
except ImportError as e:      # pragma: no cover - the extra is not installed
    raise ImportError("hotroll.pyroll_out_profile needs pyroll-core: pip install "
                      "'hotroll[pyroll]'") from e

from hotroll.model.interpass import cool

_P = None      # the hotroll.pyroll module (``install``)

#: (unit class, producer) in registration order: a producer gives the values hotroll sets on
#: the unit's out profile, or None
PRODUCERS: list = []


class SetValues:
    """A PyRolL post-processor (``Unit.post_processors``): sets ``values`` on the unit's out
    profile as it leaves and on the profile handed on (PyRolL hands on only the values set on
    a profile)."""

    label = "hotroll"

    def __init__(self, unit, values: dict):
        self.values = values
        for key, val in values.items():
            setattr(unit.out_profile, key, val)

    def solve(self, profile):
        for key, val in self.values.items():
            setattr(profile, key, val)
        return profile


def register(cls, producer) -> None:
    """Set ``producer(unit)``'s values on the out profile of every ``cls`` unit (a post-processor)
    and, through ``out_values``, on the out profile of a sequence ending with that unit."""
    PRODUCERS.append((cls, producer))

    def post_processor(unit):
        values = producer(unit)
        return SetValues(unit, values) if values else None

    post_processor.__name__ = f"hotroll_{getattr(producer, '__name__', 'values')}"
    cls.post_processors.append(post_processor)


def out_values(unit) -> dict:
    """Everything hotroll sets on ``unit``'s out profile: a sequence's are its last unit's."""
    if isinstance(unit, PassSequence):
        units = list(unit.units)
        return out_values(units[-1]) if units else {}
    values = {}
    for cls, producer in PRODUCERS:
        if isinstance(unit, cls):
            values.update(producer(unit) or {})
    return values


def _sequence_values(seq):
    values = out_values(seq)
    return SetValues(seq, values) if values else None


def pass_temperature(rp) -> float | None:
    """The FE outlet's mean temperature (K) of a flat pass hotroll solves, else None."""
    if isinstance(rp, RollPass) and _P.handles(rp):
        return _P.solve(rp)["outlet_temperature_mean"]
    return None


def other_transport_model() -> list[str]:
    """The hook functions of other plugins that give a Transport's out temperature (e.g.
    pyroll-integral-thermal's ``out_temperature``)."""
    return [f"{f.module}.{f.qualname}" for f in Transport.OutProfile.temperature.functions
            if not f.module.startswith("hotroll")]


def cools(tr) -> bool:
    """Whether hotroll cools the transport: a plain Transport after a pass hotroll solved, with
    ``Config.TRANSPORT_COOLING`` and no other plugin's transport temperature model."""
    if type(tr) is not Transport or not _P.Config.TRANSPORT_COOLING or other_transport_model():
        return False
    try:
        before = tr.prev_of(RollPass)
    except (ValueError, IndexError, AttributeError):
        return False
    return _P.handles(before)


def transport_temperature(tr) -> float | None:
    """hotroll's interpass cooling of a uniform strip at the in profile's mean temperature
    over the transport's duration: 1D conduction, convection and radiation
    (``model/interpass.cool``); None without a temperature or a duration."""
    ip, value = tr.in_profile, _P._value
    T0, duration = value(ip, "temperature", None), value(tr, "duration", None)
    if T0 is None or duration is None:
        return None
    th = _P.Config.THERMAL
    htc = float(value(tr, "convection_heat_transfer_coefficient", th["htc_air"]))
    eps = float(value(tr, "relative_radiation_coefficient", th["emissivity"]))
    ambient = float(value(tr, "environment_temperature", th["ambient_temperature"]))
    res = cool([0.0], [float(T0)], 0.5 * float(ip.height), float(duration),
               _P._properties(ip), htc, eps, ambient)
    return res.mean


def _transport_cooling(tr) -> float | None:
    return transport_temperature(tr) if cools(tr) else None


def _pass_values(unit) -> dict | None:
    T = pass_temperature(unit)
    return None if T is None else {"temperature": T}


def _transport_values(unit) -> dict | None:
    T = _transport_cooling(unit)
    return None if T is None else {"temperature": T}


def _pass_temperature_hook(self):
    return pass_temperature(self.roll_pass)


def _transport_temperature_hook(self):
    return _transport_cooling(self.transport)


def install(plugin) -> None:
    """Register with ``plugin`` (the ``hotroll.pyroll`` module, which calls this once when it is
    imported): its Config, handles, solve, _value and _properties."""
    global _P
    if _P is not None:
        return
    _P = plugin
    register(RollPass, _pass_values)
    register(Transport, _transport_values)
    RollPass.OutProfile.temperature.add_function(_pass_temperature_hook, tryfirst=True)
    Transport.OutProfile.temperature.add_function(_transport_temperature_hook, tryfirst=True)
    PassSequence.post_processors.append(_sequence_values)
