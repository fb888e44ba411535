"""hotroll as PyRolL's model of flat roll passes (issues 17, 32): ``import hotroll.pyroll``.

Importing this module registers hook functions with pyroll-core (3.1), as any PyRolL plugin.
hotroll solves a ``RollPass`` whose groove is a ``FlatGroove`` and for which it has its inputs
(a roll speed and a flow stress, ``handles``): the roll force, the roll torque, the forward
slip, the neutral angle, the contact length, the flattened radius (``flattened_radius``,
``flattening_ratio``: the names of pyroll-hitchcock-roll-flattening), the exit velocity, strain
and temperature come from one steady thermo-mechanical hotroll solve of the pass, and the exit
width is the entry width (plane strain: no spread). Every other
unit, and a flat pass without those inputs (logged once), is left to PyRolL's own models and
other plugins: every hook returns None there, and nothing else changes. A flat strip entering a
flat pass hotroll solves is not turned by 90 degrees (PyRolL's rotation rule for flat after
flat is an edging pass's). With ``Config.TRANSPORT_COOLING`` a plain ``Transport`` after a
hotroll pass cools the strip's mean temperature with hotroll's interpass model
(``model/interpass.py``).

PyRolL's conventions (docs/notes/pyroll-api.md): SI, heights are full thicknesses, the roll
force is the force on one roll over the whole width (N), the torque that of one roll (N m),
temperatures in K, tensions are stresses (Pa).

What the FE pass takes from PyRolL:
- geometry and speed: ``in_profile.height``, ``gap``, ``in_profile.width``, the roll's
  ``nominal_radius`` (or the ``working_radius`` set on it), its ``rotational_frequency``,
  ``surface_velocity`` or ``working_velocity``, or the pass's ``velocity`` (PyRolL's strip
  speed at the neutral point, U cos(phi_n)); tensions ``back_tension``, ``front_tension``;
- the roll's ``elastic_modulus`` and ``poissons_ratio`` (an elastic roll; ``Config.ROLL``
  the case's [roll] otherwise); the in profile's ``elastic_modulus`` and ``poissons_ratio``
  (the strip's, in the contact; else its grade's E(T), or rigid-plastic without a grade);
- the strip: ``in_profile.temperature``, ``in_profile.strain``; the flow stress
  ``in_profile.flow_stress_function`` (e.g. pyroll-freiberg-flow-stress) as a Hensel-Spittel
  law fitted over the pass's range (``model/flow_stress_fit.py``; the fit's error is in
  ``RollPass.hotroll_result``), or else the hotroll grade ``in_profile.material`` names;
  ``density``, ``specific_heat_capacity``, ``thermal_conductivity`` (else ``Config``);
- friction ``RollPass.coulomb_friction_coefficient`` (else ``Config.FRICTION``), roll
  temperature ``Roll.temperature`` and ``Roll.contact_heat_transfer_coefficient`` (the names
  pyroll-integral-thermal uses; else ``Config.THERMAL``).

PyRolL evaluates the force once and the torque about four times per iteration of
``Unit.solve``, and re-solves every unit on every iteration of a ``PassSequence``: the FE
solve is cached on the pass, keyed on its case (inputs rounded: temperatures to 0.01 K,
strains to 1e-6, lengths to 1 um); a pass whose inputs changed starts from its previous
solution, a new pass from the last pass solved, mapped onto its mesh (``workflows/sweep.py``,
``solvers/transfer.py``). ``STATS`` counts the FE solves and cache hits.
"""
from __future__ import annotations

import logging
import math
import sys
import tempfile
from pathlib import Path

try:
    from pyroll.core import BaseRollPass, FlatGroove, Hook, RollPass, Rotator, Transport
except ImportError as e:      # pragma: no cover - the extra is not installed
    raise ImportError("hotroll.pyroll needs pyroll-core: pip install 'hotroll[pyroll]'") from e

from hotroll.config.case import Case, case_from_dict
from hotroll.model.flow_stress_fit import fit_hensel_spittel
from hotroll.model.grades import list_grades
from hotroll.model.interpass import cool, enthalpy_mean
from hotroll.model.profile import ThicknessProfile
from hotroll.model.thermal_properties import ThermalProperties
from hotroll.workflows.runner import run_case
from hotroll.workflows.sweep import Sweep


class Config:
    """The plugin's defaults, used where PyRolL's objects do not give a value."""

    FRICTION: dict = {"law": "coulomb", "mu": 0.3}
    MESH: dict = {}                   # the pass cases' [mesh], e.g. {"h_contact": 0.001}
    SOLVER: dict = {"threads": 2}
    THERMAL: dict = {"htc_contact": 2.0e4, "roll_temperature": 353.15, "htc_air": 20.0,
                     "emissivity": 0.8, "ambient_temperature": 293.15}
    PROPERTIES: dict = {"density": 7600.0, "specific_heat": 650.0, "conductivity": 28.0}
    OUTPUT_DIR: Path | None = None    # each FE run into OUTPUT_DIR/<label>; None: a temp dir
    TRANSPORT_COOLING: bool = True
    PLATE_CONTACT_LENGTHS: float = 5.0
    #: the pass cases' [roll] (model, youngs_modulus, ...); {}: rigid, or elastic where the
    #: Roll gives its elastic_modulus
    ROLL: dict = {}
    #: a recrystallisation set's name (e.g. "hodgson_gibbs_cmn") runs hotroll's austenite
    #: kinetics through the sequence (``hotroll/pyroll_microstructure.py``); None: off
    MICROSTRUCTURE: str | None = None


_LOG = logging.getLogger("hotroll.pyroll")


#: FE solves, cache hits and warm starts since import (or ``reset_stats()``).
STATS = {"fe_solves": 0, "cache_hits": 0, "warm_starts": 0}


_SWEEP = None    # the solved passes (workflows/sweep.py), shared by all passes


def reset_stats() -> None:
    """Zero ``STATS`` and forget the solved passes (the next pass starts cold)."""
    global _SWEEP
    _SWEEP = None
    for k in STATS:
        STATS[k] = 0


def _declare(cls, name: str, doc: str) -> None:
    """A hook that another plugin may already have declared (same name, same meaning)."""
    if not isinstance(cls.__dict__.get(name), Hook) and not isinstance(getattr(cls, name, None),
                                                                        Hook):
        hook = Hook[float]()
        hook.__doc__ = doc
        setattr(cls, name, hook)


_declare(RollPass, "coulomb_friction_coefficient", "Coulomb's friction coefficient mu")
_declare(RollPass.Roll, "contact_heat_transfer_coefficient", "strip-roll HTC, W/(m^2 K)")
_declare(Transport, "convection_heat_transfer_coefficient", "convection to air, W/(m^2 K)")
_declare(Transport, "relative_radiation_coefficient", "emissivity")
RollPass.hotroll_result = Hook[dict]()
"""hotroll's summary of the pass (summary.json's figures, per unit width, SI) with the
flow-stress fit (``flow_stress_fit``) and the case (``case_toml``)."""


def is_flat(rp) -> bool:
    return isinstance(getattr(rp.roll, "groove", None), FlatGroove)


def _value(obj, name: str, default):
    """A hook's value if it can be computed, else ``default``."""
    try:
        return getattr(obj, name) if obj.has_value(name) else default
    except (AttributeError, ValueError, TypeError):
        return default


def _missing(rp, profile=None) -> str | None:
    """What hotroll lacks to solve the flat pass ``rp`` (None: it solves it): a roll speed and
    a flow stress (the profile's flow_stress_function or a hotroll grade as its material).
    ``profile``: the strip entering (default the pass's in profile)."""
    if _roll_speed(rp) is None:
        return ("no roll speed (the roll's rotational_frequency, surface_velocity or "
                "working_velocity, or the pass's velocity)")
    ip = rp.in_profile if profile is None else profile
    if _value(ip, "flow_stress_function", None) is None and _grade(ip) is None:
        return (f"no flow_stress_function on the profile and its material "
                f"{_value(ip, 'material', None)!r} is no hotroll grade "
                f"({', '.join(list_grades())})")
    return None


def handles(rp) -> bool:
    """Whether hotroll solves this pass: a flat one with its inputs (``_missing``). Others are
    left to PyRolL's own models and plugins (every hook returns None); a flat pass left so is
    logged once, with the reason."""
    if not is_flat(rp):
        return False
    why = _missing(rp)
    if why is not None:
        if not rp.__dict__.get("_hotroll_told"):
            rp.__dict__["_hotroll_told"] = True
            _LOG.info("hotroll.pyroll: pass %r left to PyRolL: %s", rp.label, why)
        return False
    return True


def _properties(profile) -> ThermalProperties:
    """The profile's density, specific heat and conductivity (else ``Config.PROPERTIES``)."""
    props = Config.PROPERTIES
    return ThermalProperties(
        float(_value(profile, "density", props["density"])),
        float(_value(profile, "specific_heat_capacity", props["specific_heat"])),
        float(_value(profile, "thermal_conductivity", props["conductivity"])))


def _grade(profile) -> str | None:
    names = _value(profile, "material", None)
    names = [names] if isinstance(names, str) else list(names or [])
    known = {g.lower(): g for g in list_grades()}
    for n in names:
        if str(n).lower() in known:
            return known[str(n).lower()]
    return None


def _radius(rp) -> float:
    """The rigid roll's radius (m): the working radius the user set, else the nominal one
    (not PyRolL's working radius, which a flattening plugin raises to R')."""
    roll = rp.roll
    if roll.has_set("working_radius"):
        return float(roll.working_radius)
    return float(roll.nominal_radius)


def _roll_speed(rp) -> float | None:
    """The roll's surface speed (m/s) from what the user set: the roll's working_velocity,
    rotational_frequency or surface_velocity, or the pass's velocity v, PyRolL's strip speed
    at the neutral point, U cos(phi_n) (hotroll's phi_n of the last solve, rounded to 1e-9
    rad: the pass is solved again until U settles); None if nothing is set."""
    roll = rp.roll
    R = _radius(rp)
    if roll.has_set("working_velocity"):
        return float(roll.working_velocity)
    if roll.has_set("rotational_frequency"):
        return 2.0 * math.pi * float(roll.rotational_frequency) * R
    if roll.has_set("surface_velocity"):
        return float(roll.surface_velocity) * R / float(roll.nominal_radius)
    if rp.has_set("velocity"):
        phi = round(rp.__dict__.get("_hotroll_neutral", 0.0), 9)
        return float(rp.velocity) / math.cos(phi)
    return None


def _material(rp, T0: float, e0: float, h0: float, h1: float, U: float, lc: float):
    """([material] table, fit description): the in profile's flow-stress function fitted, or
    the hotroll grade its material names."""
    ip = rp.in_profile
    func = _value(ip, "flow_stress_function", None)
    if func is not None:
        # PyRolL asks a pass for its hooks dozens of times: the fit (343 calls of the
        # function, ~4 ms) once per pass and box
        fits = rp.__dict__.setdefault("_hotroll_fits", {})
        box = (T0, e0, h0, h1, U, lc)
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

    grade = _grade(ip)
    if grade is None:
        raise ValueError(f"hotroll.pyroll: pass {rp.label!r}: {_missing(rp)}")
    return {"law": "hensel-spittel", "grade": grade}, {"source": f"hotroll grade {grade}"}


def pass_case(rp) -> tuple[Case, dict]:
    """The hotroll case of a flat PyRolL roll pass and its flow-stress description."""
    ip = rp.in_profile
    R = _radius(rp)
    h0, h1 = round(float(ip.height), 6), round(float(rp.height), 6)
    width = float(ip.width)
    if "vertical" in _value(ip, "classifiers", set()) and h0 > width:
        raise ValueError(f"hotroll.pyroll: pass {rp.label!r}: the strip enters on edge "
                         f"({h0:g} m high, {width:g} m wide): PyRolL turned it by 90 degrees "
                         f"before this flat pass; give the pass rotation=False (or put a "
                         f"Rotator(rotation=0) before it)")
    U = round(_roll_speed(rp), 9)
    T0 = round(float(ip.temperature), 2)
    e0 = round(float(_value(ip, "strain", 0.0)), 6)
    lc = math.sqrt(R * 0.5 * (h0 - h1))
    material, fit = _material(rp, T0, e0, h0, h1, U, lc)
    props = _properties(ip)
    material.update(density=props.density, specific_heat=props.specific_heat,
                    conductivity=props.conductivity)
    mu = _value(rp, "coulomb_friction_coefficient", None)
    thermal = dict(Config.THERMAL)
    thermal["roll_temperature"] = float(_value(rp.roll, "temperature",
                                               thermal["roll_temperature"]))
    thermal["htc_contact"] = float(_value(rp.roll, "contact_heat_transfer_coefficient",
                                          thermal["htc_contact"]))
    d = {
        "name": str(rp.label or "pass"),
        "pass": {"roll_radius": R, "entry_thickness": h0, "exit_thickness": h1,
                 "roll_angular_velocity": U / R, "width": round(float(ip.width), 6),
                 "back_tension": float(_value(rp, "back_tension", 0.0)),
                 "front_tension": float(_value(rp, "front_tension", 0.0))},
        "plate": {"length": Config.PLATE_CONTACT_LENGTHS * lc, "temperature": T0,
                  "entry_strain": e0, **_micro.entry_plate(rp)},
        "material": material,
        "friction": {"law": "coulomb", "mu": float(mu)} if mu is not None
        else dict(Config.FRICTION),
        "mesh": dict(Config.MESH),
        "solver": {"method": "steady", **Config.SOLVER},
        "output": {"figures": False, "vtk": False},
        "thermal": thermal,
        "roll": _roll_table(rp.roll),
        "contact": _contact_table(ip),
    }
    return case_from_dict(d), fit


def _contact_table(ip) -> dict:
    """The case's [contact]: the strip's elastic_modulus and poissons_ratio where the in
    profile gives them (its elastic exit zone, docs/theory.md 1e); else the grade's E(T), or
    rigid-plastic for a flow_stress_function without a grade (``strip_youngs_modulus =
    "auto"``)."""
    E, nu = _value(ip, "elastic_modulus", None), _value(ip, "poissons_ratio", None)
    table = {}
    if E is not None:
        table["strip_youngs_modulus"] = float(E)
    if nu is not None:
        table["strip_poissons_ratio"] = float(nu)
    return table


def _roll_table(roll) -> dict:
    """The case's [roll]: ``Config.ROLL`` with the Roll's elastic_modulus and poissons_ratio
    where PyRolL gives them (the model then elastic unless ``Config.ROLL`` names one)."""
    table = dict(Config.ROLL)
    E, nu = _value(roll, "elastic_modulus", None), _value(roll, "poissons_ratio", None)
    if E is not None:
        table["youngs_modulus"] = float(E)
        table.setdefault("model", "elastic")
    if nu is not None:
        table["poissons_ratio"] = float(nu)
    return table


def solve(rp) -> dict:
    """hotroll's summary of a flat pass: cached on the pass, keyed on its case; a changed
    case starts from the previous solution where the mesh is the same."""
    case, fit = pass_case(rp)
    key = case.to_toml()
    cache = rp.__dict__.setdefault("_hotroll_cache", {})
    if key in cache:
        STATS["cache_hits"] += 1
        return cache[key]
    global _SWEEP
    if _SWEEP is None:     # a pass starts from its own last solve, else from the last pass
        _SWEEP = Sweep(similar=True, history=False)
    sweep = _SWEEP
    if Config.OUTPUT_DIR is not None:
        out = Path(Config.OUTPUT_DIR) / case.name
    else:
        tmp = rp.__dict__.setdefault("_hotroll_tmp", tempfile.TemporaryDirectory())
        out = Path(tmp.name) / case.name
    summary = run_case(case, out, resume=False, sweep=sweep)
    STATS["fe_solves"] += 1
    STATS["warm_starts"] += summary.get("warm_start_from") is not None
    if summary.get("exit_code") != 0:
        raise RuntimeError(f"hotroll.pyroll: pass {rp.label!r} ended with exit code "
                           f"{summary.get('exit_code')} (status {summary.get('status')}); "
                           f"its output is in {out}")
    # PyRolL's pass velocity is U cos(phi_n): the next call's roll speed uses this phi_n
    rp.__dict__["_hotroll_neutral"] = float(summary.get("neutral_angle") or 0.0)
    T_out, e_out = _outlet_means(case, summary)
    summary = dict(summary, flow_stress_fit=fit, case_toml=key, output_dir=str(out),
                   outlet_temperature_mean=T_out, outlet_strain_mean=e_out)
    cache[key] = summary
    return summary


def _outlet_means(case: Case, s: dict) -> tuple[float, float]:
    """(temperature K, strain) means of the profile at the FE strip's outlet (the temperature
    by its heat content)."""
    import numpy as np

    prof = s["exit_profile"]
    T = ThicknessProfile(tuple(prof["eta"]), tuple(prof["temperature"]))
    T_mean = enthalpy_mean(case.material.thermal_properties(), np.asarray(T.values),
                           T.weights())
    e = (ThicknessProfile(tuple(prof["eta"]), tuple(prof["strain"])).mean()
         if prof.get("strain") is not None else s["homogeneous_exit_strain"])
    return T_mean, e


@RollPass.hotroll_result
def hotroll_result(self: RollPass):
    return solve(self) if handles(self) else None


@RollPass.roll_force(tryfirst=True)
def roll_force(self: RollPass):
    if not handles(self):
        return None
    s = solve(self)
    return s["roll_force"] * self.in_profile.width


@RollPass.Roll.roll_torque(tryfirst=True)
def roll_torque(self: RollPass.Roll):
    rp = self.roll_pass
    if not handles(rp):
        return None
    return solve(rp)["roll_torque"] * rp.in_profile.width


@RollPass.forward_slip_ratio(tryfirst=True)
def forward_slip_ratio(self: RollPass):
    return solve(self)["forward_slip"] if handles(self) else None


@RollPass.Roll.neutral_angle(tryfirst=True)
def neutral_angle(self: RollPass.Roll):
    """PyRolL's sign: negative towards the entry (hotroll's is positive there)."""
    rp = self.roll_pass
    if not handles(rp):
        return None
    ang = solve(rp)["neutral_angle"]  # null in a sticking zone: PyRolL's own hooks decide
    return None if ang is None else -ang


@BaseRollPass.Roll.contact_length(tryfirst=True)
def contact_length(self):
    """hotroll's contact length (m): where the strip touches the (flattened) roll."""
    rp = self.roll_pass
    return solve(rp)["contact_length"] if handles(rp) else None


_declare(BaseRollPass.Roll, "flattened_radius", "the flattened roll's radius R' (m)")
_declare(BaseRollPass.Roll, "flattening_ratio", "R'/R, the flattened over the rigid radius")


@BaseRollPass.Roll.flattened_radius(tryfirst=True)
def flattened_radius(self):
    """R' (m): the radius of the circle fitted to hotroll's flattened roll over the contact
    (``roll_equivalent_radius``); the rigid radius for a rigid roll. The names are those of
    pyroll-hitchcock-roll-flattening: with hotroll's pass PyRolL reads hotroll's R'."""
    rp = self.roll_pass
    if not handles(rp):
        return None
    return solve(rp).get("roll_equivalent_radius", _radius(rp))


@BaseRollPass.Roll.flattening_ratio(tryfirst=True)
def flattening_ratio(self):
    rp = self.roll_pass
    if not handles(rp):
        return None
    return solve(rp).get("roll_equivalent_radius", _radius(rp)) / _radius(rp)


@RollPass.OutProfile.velocity(tryfirst=True)
def out_velocity(self: RollPass.OutProfile):
    rp = self.roll_pass
    return solve(rp)["exit_velocity"] if handles(rp) else None


@RollPass.OutProfile.width(tryfirst=True)
def out_width(self: RollPass.OutProfile):
    """hotroll's pass is plane strain: the strip leaves as wide as it enters (no spread;
    PyRolL's default fills the groove's usable width)."""
    rp = self.roll_pass
    return float(rp.in_profile.width) if handles(rp) else None


@RollPass.OutProfile.strain(tryfirst=True)
def out_strain(self: RollPass.OutProfile):
    rp = self.roll_pass
    return solve(rp)["outlet_strain_mean"] if handles(rp) else None


@Rotator.rotation(tryfirst=True)
def flat_strip_stays_flat(self: Rotator):
    """0 (no turn) between a flat strip and a flat pass hotroll solves. PyRolL (3.1.15,
    rule ``flat_flat_0``) turns a flat profile by 90 degrees before a flat pass, as for an
    edging pass of a bar; a strip rolled flat after flat would enter on edge. Other passes
    keep PyRolL's rules."""
    nxt = self.next_roll_pass
    if ("flat" in _value(self.in_profile, "classifiers", set()) and is_flat(nxt)
            and "3fold" not in nxt.classifiers and _missing(nxt, self.in_profile) is None):
        return 0
    return None


class _SetValues:
    """A PyRolL post-processor (``Unit.post_processors``): sets values on the unit's out
    profile as it leaves (the temperature hotroll computed; PyRolL hands on only the values
    set on a profile)."""

    label = "hotroll"

    def __init__(self, unit, values: dict):
        self.values = values
        for key, value in values.items():
            setattr(unit.out_profile, key, value)

    def solve(self, profile):
        for key, value in self.values.items():
            setattr(profile, key, value)
        return profile


def _after_pass(unit):
    """A flat pass hotroll solves leaves at the FE outlet's mean temperature."""
    if isinstance(unit, RollPass) and handles(unit):
        return _SetValues(unit, {"temperature": solve(unit)["outlet_temperature_mean"]})
    return None


def _after_transport(unit):
    """A plain Transport after a pass hotroll solved cools by hotroll's interpass model
    (``Config.TRANSPORT_COOLING``); other transports (cooling pipes, furnaces, ...) and
    those after other passes keep PyRolL's models."""
    if type(unit) is not Transport or not Config.TRANSPORT_COOLING:
        return None
    try:
        before = unit.prev_of(RollPass)
    except (ValueError, IndexError, AttributeError):
        return None
    if not handles(before):
        return None
    T = transport_temperature(unit)
    return None if T is None else _SetValues(unit, {"temperature": T})


def transport_temperature(tr) -> float | None:
    """hotroll's interpass cooling of a uniform strip at the in profile's mean temperature
    over the transport's duration: 1D conduction, convection and radiation
    (``model/interpass.cool``); None without a temperature or a duration."""
    ip = tr.in_profile
    T0, duration = _value(ip, "temperature", None), _value(tr, "duration", None)
    if T0 is None or duration is None:
        return None
    p = _properties(ip)
    htc = float(_value(tr, "convection_heat_transfer_coefficient", Config.THERMAL["htc_air"]))
    eps = float(_value(tr, "relative_radiation_coefficient", Config.THERMAL["emissivity"]))
    ambient = float(_value(tr, "environment_temperature", Config.THERMAL["ambient_temperature"]))
    res = cool([0.0], [float(T0)], 0.5 * float(ip.height), float(duration), p, htc, eps,
               ambient)
    return res.mean


RollPass.post_processors.append(_after_pass)
Transport.post_processors.append(_after_transport)

from hotroll import pyroll_microstructure as _micro  # noqa: E402  (it needs the above)

_micro.install(sys.modules[__name__])
