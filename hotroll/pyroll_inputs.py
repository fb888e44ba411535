"""What a flat pass's hotroll case reads from PyRolL's objects (``hotroll.pyroll``; issues 17,
32, 51), the flow stress aside (``hotroll/pyroll_flow_stress.py``): the roll's radius and
surface speed, whether the strip entering is a flat strip at all, the roll's and the strip's
elastic data. Only plain reads through PyRolL's ``has_value``/``has_set`` (no pyroll-core
import, no ``hotroll.pyroll``); SI units as PyRolL's (m, m/s, Pa).
"""
from __future__ import annotations

import math

from hotroll.model.interpass import enthalpy_mean
from hotroll.model.profile import ThicknessProfile, folded
from hotroll.model.thermal_properties import ThermalProperties


def value(obj, name: str, default):
    """A PyRolL hook's value on ``obj`` if it can be computed, else ``default``."""
    try:
        return getattr(obj, name) if obj.has_value(name) else default
    except (AttributeError, ValueError, TypeError):
        return default


def radius(rp) -> float:
    """The rigid roll's radius (m): the working radius the user set, else the nominal one
    (not PyRolL's working radius, which a flattening plugin raises to R')."""
    return roll_radius(rp.roll)


def roll_radius(roll) -> float:
    """A PyRolL ``Roll``'s rigid radius (m), as ``radius``."""
    if roll.has_set("working_radius"):
        return float(roll.working_radius)
    return float(roll.nominal_radius)


def roll_speed(rp) -> float | None:
    """The roll's surface speed (m/s) from what the user set: the roll's working_velocity,
    rotational_frequency or surface_velocity, or the pass's velocity v, PyRolL's strip speed
    at the neutral point, U cos(phi_n) (hotroll's phi_n of the last solve, rounded to 1e-9
    rad: the pass is solved again until U settles); None if nothing is set."""
    own = surface_speed(rp.roll)
    if own is not None:
        return own
    if rp.has_set("velocity"):
        phi = round(rp.__dict__.get("_hotroll_neutral", 0.0), 9)
        return float(rp.velocity) / math.cos(phi)
    return None


def surface_speed(roll) -> float | None:
    """A PyRolL ``Roll``'s surface speed (m/s) from what the user set on it: its
    working_velocity, rotational_frequency (2 pi f R) or surface_velocity (at the nominal
    radius, scaled to R); None if none is set."""
    R = roll_radius(roll)
    if roll.has_set("working_velocity"):
        return float(roll.working_velocity)
    if roll.has_set("rotational_frequency"):
        return 2.0 * math.pi * float(roll.rotational_frequency) * R
    if roll.has_set("surface_velocity"):
        return float(roll.surface_velocity) * R / float(roll.nominal_radius)
    return None


def not_a_strip(profile, min_fill: float) -> str | None:
    """Why the profile is no flat strip for hotroll's plane-strain pass (None: it is one): its
    cross-section fills less than ``min_fill`` of its bounding box (a rectangle fills it, a
    box with rounded corners nearly; a round bar 0.79, a hexagon 0.75, a diamond 0.5). Such a
    bar is what PyRolL turns by 90 degrees before a flat pass (pyroll-core's own tests roll
    hexagons and diamonds so: ``roll/test_roll_contact_areas.py``)."""
    cs = value(profile, "cross_section", None)
    if cs is None:
        return None
    x0, y0, x1, y1 = cs.bounds
    fill = cs.area / ((x1 - x0) * (y1 - y0)) if x1 > x0 and y1 > y0 else 0.0
    if fill >= min_fill:
        return None
    classes = sorted(value(profile, "classifiers", set()))
    return (f"the strip entering ({', '.join(classes) or 'unclassified'}, "
            f"{(y1 - y0) * 1e3:.4g} mm high, {(x1 - x0) * 1e3:.4g} mm wide) fills {fill:.0%} of "
            f"its bounding box: no flat strip (hotroll's pass is a plane-strain strip; "
            f"Config.MIN_RECTANGULARITY = {min_fill:.0%})")


def contact_table(ip) -> dict:
    """The case's [contact]: the strip's elastic_modulus and poissons_ratio (Pa, -) where the in
    profile gives them (its elastic exit zone, docs/theory.md 1e); else the grade's E(T), or
    rigid-plastic without a grade (``strip_youngs_modulus = "auto"``)."""
    E, nu = value(ip, "elastic_modulus", None), value(ip, "poissons_ratio", None)
    table = {}
    if E is not None:
        table["strip_youngs_modulus"] = float(E)
    if nu is not None:
        table["strip_poissons_ratio"] = float(nu)
    return table


def roll_table(roll, base: dict) -> dict:
    """The case's [roll]: ``base`` (``Config.ROLL``) with the Roll's elastic_modulus and
    poissons_ratio where PyRolL gives them (the model then elastic unless ``base`` names
    one)."""
    table = dict(base)
    E, nu = value(roll, "elastic_modulus", None), value(roll, "poissons_ratio", None)
    if E is not None:
        table["youngs_modulus"] = float(E)
        table.setdefault("model", "elastic")
    if nu is not None:
        table["poissons_ratio"] = float(nu)
    return table


def properties(profile, defaults: dict) -> ThermalProperties:
    """The profile's density, specific heat and conductivity (else ``defaults``: ``Config.PROPERTIES``)."""
    props = defaults
    return ThermalProperties(
        float(value(profile, "density", props["density"])),
        float(value(profile, "specific_heat_capacity", props["specific_heat"])),
        float(value(profile, "thermal_conductivity", props["conductivity"])))


def outlet_means(case, s: dict) -> tuple[float, float]:
    """(temperature K, strain) means of the profile at the FE strip's outlet (the temperature
    by its heat content)."""
    import numpy as np

    prof = folded(s["exit_profile"])        # an asymmetric pass's: folded about the middle

    def profile(values):
        return ThicknessProfile(tuple(prof["eta"]), tuple(values))

    e = s.get("exit_strain")
    if prof is None or prof["temperature"] is None:    # an isothermal pass
        return case.plate.temperature, s["homogeneous_exit_strain"] if e is None else e
    T = profile(prof["temperature"])
    T_mean = enthalpy_mean(case.material.thermal_properties(), np.asarray(T.values),
                           T.weights())
    e = (profile(prof["strain"]).mean()
         if prof.get("strain") is not None else s["homogeneous_exit_strain"])
    return T_mean, e
