"""hotroll as PyRolL's model of flat roll passes (issues 17, 32, 51): ``import hotroll.pyroll``.

Importing this module registers hook functions with pyroll-core (3.1), as any PyRolL plugin.
hotroll solves a ``RollPass`` whose groove is a ``FlatGroove`` and for which it has its inputs
(a roll speed, a flow stress and a flat strip entering, ``handles``): the roll force, the roll
torque, the forward slip, the neutral angle, the contact length, the flattened radius
(``flattened_radius``, ``flattening_ratio``: the names of pyroll-hitchcock-roll-flattening),
the exit velocity, strain and temperature come from one steady thermo-mechanical hotroll solve
of the pass, and the exit width is the entry width (plane strain: no spread). Every other
unit, and a flat pass without those inputs (logged once at WARNING, with the reason), is left
to PyRolL's own models and other plugins: every hook returns None there, and nothing else
changes. A flat strip entering a flat pass hotroll solves is not turned by 90 degrees (PyRolL's
rotation rule for flat after flat is an edging pass's). The temperatures hotroll sets on out
profiles (a pass's, a transport's after it, a sequence's: its last unit's) are
``hotroll/pyroll_out_profile.py``'s; the flow stress a pass is rolled with (a constant
``flow_stress`` on the profile, a ``flow_stress_function``, a hotroll grade) is
``hotroll/pyroll_flow_stress.py``'s.

PyRolL's conventions (docs/notes/pyroll-api.md): SI, heights are full thicknesses, the roll
force is the force on one roll over the whole width (N), the torque that of one roll (N m),
temperatures in K, tensions are stresses (Pa).

What the FE pass takes from PyRolL (its case: ``hotroll/pyroll_case.py``, with ``Config``):
- geometry and speed: ``in_profile.height``, ``gap``, ``in_profile.width``, the roll's
  ``nominal_radius`` (or the ``working_radius`` set on it), its ``rotational_frequency``,
  ``surface_velocity`` or ``working_velocity``, or the pass's ``velocity`` (PyRolL's strip
  speed at the neutral point, U cos(phi_n)); tensions ``back_tension``, ``front_tension``;
- the roll's ``elastic_modulus`` and ``poissons_ratio`` (an elastic roll; ``Config.ROLL``
  the case's [roll] otherwise); the in profile's ``elastic_modulus`` and ``poissons_ratio``
  (the strip's, in the contact; else its grade's E(T), or rigid-plastic without a grade);
- the strip: ``in_profile.temperature``, ``in_profile.strain``; the flow stress: a constant
  ``in_profile.flow_stress`` (Pa) as a Norton-Hoff law equal to it at the pass's mean strain
  rate (m = ``Config.FLOW_STRESS_RATE_EXPONENT``), else ``in_profile.flow_stress_function``
  (e.g. pyroll-freiberg-flow-stress) as a Hensel-Spittel law fitted over the pass's range
  (``model/flow_stress_fit.py``), else the hotroll grade ``in_profile.material`` names (what
  was used, with K and m or the fit's error, is ``RollPass.hotroll_result["flow_stress_fit"]``);
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
import sys
import tempfile
from pathlib import Path

try:
    import pyroll.core as _core
    from pyroll.core import (
        BaseRollPass,
        FlatGroove,
        Hook,
        RollPass,
        Rotator,
        SymmetricRollPass,
        Transport,
    )
except ImportError as e:      # pragma: no cover - the extra is not installed
    raise ImportError("hotroll.pyroll needs pyroll-core: pip install 'hotroll[pyroll]'") from e

from hotroll import pyroll_asymmetric as _asym
from hotroll import pyroll_flow_stress as _flow
from hotroll import pyroll_inputs as _in
from hotroll.pyroll_case import Config, pass_case
from hotroll.pyroll_case import properties as _properties  # noqa: F401 (the sub-plugins' _P._properties)
from hotroll.workflows.runner import run_case
from hotroll.workflows.sweep import Sweep

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
    """A flat pass: its roll's groove (both rolls' of an asymmetric pass) a ``FlatGroove``."""
    rolls = (rp.upper_roll, rp.lower_roll) if _asym.is_asymmetric(rp) else (rp.roll,)
    return all(isinstance(getattr(r, "groove", None), FlatGroove) for r in rolls)


_value = _in.value     # a hook's value if it can be computed, else the default


def _missing(rp, profile=None) -> str | None:
    """What hotroll lacks to solve the flat pass ``rp`` (None: it solves it): a roll speed, a
    temperature, a flow stress (``pyroll_flow_stress.missing``) and a flat strip (filling at
    least ``Config.MIN_RECTANGULARITY`` of its bounding box). ``profile``: the strip entering
    (default the pass's in profile)."""
    if _asym.is_asymmetric(rp):
        why = _asym.missing(rp)
        if why is not None:
            return why
    elif _in.roll_speed(rp) is None:
        return ("no roll speed (the roll's rotational_frequency, surface_velocity or "
                "working_velocity, or the pass's velocity)")
    ip = rp.in_profile if profile is None else profile
    if _value(ip, "temperature", None) is None:
        return "no temperature (K) on the profile"
    why = _flow.missing(ip)
    if why is not None:
        return why
    return _in.not_a_strip(ip, Config.MIN_RECTANGULARITY)


def handles(rp) -> bool:
    """Whether hotroll solves this pass: a flat one with its inputs (``_missing``). Others are
    left to PyRolL's own models and plugins (every hook returns None); a flat pass left so is
    logged once at WARNING, with the reason."""
    if not is_flat(rp):
        return False
    why = _missing(rp)
    if why is not None:
        if not rp.__dict__.get("_hotroll_told"):
            rp.__dict__["_hotroll_told"] = True
            _LOG.warning("hotroll.pyroll: flat pass %r left to PyRolL's own models: %s",
                         rp.label, why)
        return False
    return True


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
        from hotroll.results.outcome import EXIT_CODES

        code = summary.get("exit_code")
        why = f": {summary['failure']}" if summary.get("failure") else ""
        raise RuntimeError(f"hotroll.pyroll: pass {rp.label!r} ended with exit code {code}, "
                           f"{EXIT_CODES.get(code, '?')} (status {summary.get('status')}{why}); "
                           f"its output is in {out}")
    # PyRolL's pass velocity is U cos(phi_n): the next call's roll speed uses this phi_n
    rp.__dict__["_hotroll_neutral"] = float(summary.get("neutral_angle") or 0.0)
    T_out, e_out = _in.outlet_means(case, summary)
    summary = dict(summary, flow_stress_fit=fit, case_toml=key, output_dir=str(out),
                   outlet_temperature_mean=T_out, outlet_strain_mean=e_out)
    cache[key] = summary
    return summary


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


def contact_length(self):
    """hotroll's contact length (m): where the strip touches the (flattened) roll (an
    asymmetric pass: this roll's)."""
    rp = self.roll_pass
    if not handles(rp):
        return None
    return _asym.roll_figure(solve(rp), int(self is getattr(rp, "lower_roll", None)),
                             "contact_length")


def flattened_radius(self):
    """R' (m): the radius of the circle fitted to hotroll's flattened roll over the contact
    (``roll_equivalent_radius``); the rigid radius for a rigid roll. The names are those of
    pyroll-hitchcock-roll-flattening: with hotroll's pass PyRolL reads hotroll's R'."""
    rp = self.roll_pass
    if not handles(rp):
        return None
    return solve(rp).get("roll_equivalent_radius", _in.roll_radius(self))


def flattening_ratio(self):
    rp = self.roll_pass
    if not handles(rp):
        return None
    return solve(rp).get("roll_equivalent_radius", _in.roll_radius(self)) / _in.radius(rp)


#: pyroll-core's asymmetric pass (its PR #251), None in pyroll-core 3.1
ASYMMETRIC_PASS = getattr(_core, "AsymmetricTwoRollPass", None)


def register_roll_hooks(host) -> None:
    """The base pass's roll hooks on ``host`` (``_asym.roll_hosts``): hotroll's contact length;
    the flattened radius and ratio, declared there if no other plugin did."""
    host.contact_length(tryfirst=True)(contact_length)
    _declare(host, "flattened_radius", "the flattened roll's radius R' (m)")
    _declare(host, "flattening_ratio", "R'/R, the flattened over the rigid radius")
    host.flattened_radius(tryfirst=True)(flattened_radius)
    host.flattening_ratio(tryfirst=True)(flattening_ratio)


for _host in _asym.roll_hosts(BaseRollPass, SymmetricRollPass, ASYMMETRIC_PASS):
    register_roll_hooks(_host)
if ASYMMETRIC_PASS is not None:
    _asym.install_on(ASYMMETRIC_PASS, lambda rp: solve(rp), handles, _declare)


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


from hotroll import pyroll_microstructure as _micro  # noqa: E402  (they need the above)
from hotroll import pyroll_out_profile as _out  # noqa: E402

_out.install(sys.modules[__name__])
_micro.install(sys.modules[__name__])
