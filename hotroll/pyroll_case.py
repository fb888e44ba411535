"""The hotroll case of a flat PyRolL roll pass (``hotroll.pyroll``; issues 17, 32, 51, 52):
``pass_case`` builds it from the pass, its rolls and the strip entering (the flow stress is
``pyroll_flow_stress.py``'s, the rolls and the strip are read by ``pyroll_inputs.py``, an
asymmetric pass's two rolls by ``pyroll_asymmetric.py``), and ``Config`` holds the plugin's
defaults where PyRolL's objects give no value (``hotroll.pyroll.Config`` is this class)."""
from __future__ import annotations

import math
from pathlib import Path

from hotroll import pyroll_asymmetric as _asym
from hotroll import pyroll_flow_stress as _flow
from hotroll import pyroll_inputs as _in
from hotroll.config.case import Case, case_from_dict
from hotroll.config.full_strip import asymmetric_refusal


class Config:
    """The plugin's defaults, used where PyRolL's objects do not give a value."""

    FRICTION: dict = {"law": "coulomb", "mu": 0.3}
    MESH: dict = {}                   # the pass cases' [mesh], e.g. {"h_contact": 0.001}
    SOLVER: dict = {}                 # the pass cases' [solver]; {}: its defaults (threads "auto")
    THERMAL: dict = {"htc_contact": 2.0e4, "roll_temperature": 353.15, "htc_air": 20.0,
                     "emissivity": 0.8, "ambient_temperature": 293.15}
    PROPERTIES: dict = {"density": 7600.0, "specific_heat": 650.0, "conductivity": 28.0}
    OUTPUT_DIR: Path | None = None    # each FE run into OUTPUT_DIR/<label>; None: a temp dir
    #: a plain Transport after a hotroll pass cools by hotroll's interpass model, unless another
    #: plugin gives transports a temperature (pyroll-integral-thermal: its model is kept)
    TRANSPORT_COOLING: bool = True
    PLATE_CONTACT_LENGTHS: float = 5.0
    #: the pass cases' [roll] (model, youngs_modulus, ...); {}: rigid, or elastic where the
    #: Roll gives its elastic_modulus
    ROLL: dict = {}
    #: a recrystallisation set's name (e.g. "hodgson_gibbs_cmn") runs hotroll's austenite
    #: kinetics through the sequence (``hotroll/pyroll_microstructure.py``); None: off
    MICROSTRUCTURE: str | None = None
    #: m of the Norton-Hoff law a constant ``flow_stress`` on the profile is rolled as
    #: (``hotroll/pyroll_flow_stress.py``): sigma equals it at the pass's mean strain rate
    FLOW_STRESS_RATE_EXPONENT: float = 0.1
    #: the least share of its bounding box a profile's cross-section fills for hotroll to roll
    #: it as a flat strip (a rectangle: 1; a round 0.79, a hexagon 0.75, a diamond 0.5)
    MIN_RECTANGULARITY: float = 0.9


_value = _in.value     # a hook's value if it can be computed, else the default


def properties(profile):
    """The profile's thermal properties, else ``Config.PROPERTIES`` (``pyroll_inputs``)."""
    return _in.properties(profile, Config.PROPERTIES)


def pass_case(rp) -> tuple[Case, dict]:
    """The hotroll case of a flat PyRolL roll pass and its flow-stress description. An
    asymmetric pass (``upper_roll`` and ``lower_roll``, ``hotroll/pyroll_asymmetric.py``)
    takes each roll's radius and speed from that roll (the roll temperature and contact heat
    transfer the upper roll's: one [thermal] for both), a roll's own elastic modulus as that
    roll's model, and its strip's elasticity as a symmetric pass's; what the full strip does
    not carry is refused naming what PyRolL described (``ValueError``)."""
    from hotroll import pyroll_microstructure as _micro  # hotroll.pyroll imports it after its hooks

    ip = rp.in_profile
    two = _asym.is_asymmetric(rp)
    R = _in.roll_radius(rp.upper_roll) if two else _in.radius(rp)
    h0, h1 = round(float(ip.height), 6), round(float(rp.height), 6)
    width = float(ip.width)
    if "vertical" in _value(ip, "classifiers", set()) and h0 > width:
        raise ValueError(f"hotroll.pyroll: pass {rp.label!r}: the strip enters on edge "
                         f"({h0:g} m high, {width:g} m wide): PyRolL turned it by 90 degrees "
                         f"before this flat pass; give the pass rotation=False (or put a "
                         f"Rotator(rotation=0) before it)")
    U = round(_asym.rolls(rp)[0][1] if two else _in.roll_speed(rp), 9)
    T0 = round(float(ip.temperature), 2)
    e0 = round(float(_value(ip, "strain", 0.0)), 6)
    lc = math.sqrt(R * 0.5 * (h0 - h1))
    material, fit = _flow.material(rp, T0, e0, h0, h1, U, lc, Config.FLOW_STRESS_RATE_EXPONENT)
    props = properties(ip)
    material.update(density=props.density, specific_heat=props.specific_heat,
                    conductivity=props.conductivity)
    mu = _value(rp, "coulomb_friction_coefficient", None)
    thermal = dict(Config.THERMAL)
    roll = rp.upper_roll if two else rp.roll
    thermal["roll_temperature"] = float(_value(roll, "temperature",
                                               thermal["roll_temperature"]))
    thermal["htc_contact"] = float(_value(roll, "contact_heat_transfer_coefficient",
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
        "roll": _in.roll_table(roll, Config.ROLL),
        "contact": _in.contact_table(ip),
    }
    if not two:
        return case_from_dict(d), fit
    d["pass"].update(_asym.pass_rolls(rp))
    lower = _in.roll_table(rp.lower_roll, Config.ROLL)
    # one [roll] elasticity for both rolls: the lower roll's where only it gives one; two
    # different ones refused (below) rather than one dropped
    problems = []
    for key in ("youngs_modulus", "poissons_ratio"):
        if key in lower and key not in d["roll"]:
            d["roll"][key] = lower[key]
        elif key in lower and lower[key] != d["roll"][key]:
            problems.append(f"roll.{key}: one value for both rolls (the upper roll's "
                            f"{d['roll'][key]:g}), the lower roll gives {lower[key]:g}")
    if lower.get("model", "rigid") != d["roll"].get("model", "rigid"):
        d["roll"]["lower"] = {"model": lower.get("model", "rigid")}
    case = case_from_dict(d)
    refused = asymmetric_refusal(case)
    problems += [] if refused is None else list(refused.problems)
    for attr, key in (("temperature", "roll_temperature"),
                      ("contact_heat_transfer_coefficient", "htc_contact")):
        own = _value(rp.lower_roll, attr, None)
        if own is not None and float(own) != thermal[key]:
            problems.append(f"thermal.{key}: one value for both rolls (the upper roll's "
                            f"{thermal[key]:g}), the lower roll gives {float(own):g}")
    if problems:
        raise ValueError(_asym.refusal(rp, problems))
    return case, fit
