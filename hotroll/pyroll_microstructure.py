"""hotroll's austenite microstructure through a PyRolL sequence (issue 33, item 4).

Switched on by ``hotroll.pyroll.Config.MICROSTRUCTURE`` = a recrystallisation set's name
(``model/microstructure``, e.g. ``"hodgson_gibbs_cmn"``); None (the default) leaves every
profile as before. ``hotroll.pyroll`` installs it (``install``) when it is imported.

With it on:

- a flat pass hotroll solves needs ``in_profile.grain_size`` (m; a ValueError naming it
  otherwise) and enters with the strain profile through the half thickness a transport handed
  on (``hotroll_strain_profile`` over ``hotroll_profile_eta``, when its mean is the profile's
  ``strain``; else the uniform ``strain``). Its exit state (``softening.pass_state`` on the
  exit profile's streamlines: strain = entry + pass strain, ln Z, exit temperature) is kept on
  the pass: ``RollPass.hotroll_pass_state``. Its out profile keeps the grain size it entered
  with (hotroll softens in the transport: Hodgson and Gibbs' and Sellars' shortcut, static
  or metadynamic recrystallisation after the pass, no dynamic recrystallised fraction in it),
  ``recrystallized_fraction`` 0 and the FE exit strain profile;
- a plain ``Transport`` after it (one or several in a row) softens that state point by point
  over hotroll's recorded cooling of the exit temperature profile (``model/interpass.cool``,
  record=True, the transports' durations and air data one after the other; the additivity
  rule over the whole history from the pass's exit, ``softening.soften``) and sets on its out
  profile the section means PyRolL's recrystallisation plugin uses, ``grain_size`` (m),
  ``recrystallized_fraction`` and ``strain`` (the mean retained strain, lambda = 1 as
  PyRolL's), and the arrays over ``hotroll_profile_eta`` (eta = y / half thickness, 0 centre,
  1 surface): ``hotroll_strain_profile`` (retained), ``hotroll_grain_size_profile``,
  ``hotroll_recrystallized_fraction_profile``. ``Transport.hotroll_microstructure`` is the
  per-eta record and the means (``workflows/microstructure.py``'s columns).

Who owns the values when pyroll-jmak-recrystallization is loaded too: with MICROSTRUCTURE on,
hotroll sets the values above on the out profiles of the passes it solves and of the plain
transports after them, as post-processors (``Unit.post_processors``, as the temperature;
``hotroll/pyroll_out_profile.py``), and on a sequence's out profile when its last unit got them:
a value set on a profile wins over every hook function, whatever the plugins' import order and
``tryfirst``. Everywhere else (MICROSTRUCTURE off, a grooved pass, a cooling pipe, a transport
after a pass hotroll did not solve) PyRolL's plugin keeps them. Its own unit hooks
(``recrystallization_mechanism``, ``Unit.recrystallized_fraction``, ...) are not hotroll's and
describe its own model, not hotroll's values.

``mean_kinetics`` is hotroll's kinetics on one point (mean strain, rate and temperature), and
``jmak_parameters`` the set in pyroll-jmak-recrystallization's parameter form: the three-way
comparison of docs/validation/microstructure-pyroll.md.
"""
from __future__ import annotations

import logging

import numpy as np

try:
    from pyroll.core import Hook, Profile, RollPass, Transport
except ImportError as e:      # pragma: no cover - the extra is not installed
    raise ImportError("hotroll.pyroll_microstructure needs pyroll-core: pip install "
                      "'hotroll[pyroll]'") from e

from hotroll import pyroll_out_profile as out_profile
from hotroll.model.interpass import cool
from hotroll.model.microstructure import get_set
from hotroll.model.microstructure.base import RecrystallisationSet
from hotroll.model.microstructure.softening import PassState, Softened, pass_state, soften
from hotroll.model.profile import ThicknessProfile, folded
from hotroll.workflows import microstructure as MS

_LOG = logging.getLogger("hotroll.pyroll")

#: The share of the unrecrystallised strain handed on (lambda of Beynon and Sellars): 1, as
#: PyRolL's plugin (transport out strain = in strain (1 - X)).
RETAINED_SHARE = 1.0

_P = None      # the hotroll.pyroll module (``install``)

_ARRAYS = {
    "hotroll_profile_eta": "eta = y / half thickness (0 centre, 1 surface) of the hotroll_*_profile arrays",
    "hotroll_strain_profile": "equivalent strain over hotroll_profile_eta (after a transport: retained)",
    "hotroll_grain_size_profile": "austenite grain size (m) over hotroll_profile_eta",
    "hotroll_recrystallized_fraction_profile": "recrystallised fraction over hotroll_profile_eta",
}


def _declare(cls, name: str, doc: str) -> None:
    if not isinstance(getattr(cls, name, None), Hook):
        hook = Hook[object]()
        hook.__doc__ = doc
        setattr(cls, name, hook)


for _name, _doc in _ARRAYS.items():
    _declare(Profile, _name, _doc)
# pyroll-jmak-recrystallization's name (it declares it again when loaded: same meaning)
_declare(Profile, "recrystallized_fraction", "Fraction of microstructure which is recrystallized")
RollPass.hotroll_pass_state = Hook[PassState]()
"""hotroll's deformed state at the pass's exit per eta (``softening.PassState``), with
``Config.MICROSTRUCTURE``."""
Transport.hotroll_microstructure = Hook[dict]()
"""hotroll's softening in a plain transport after a hotroll pass: the per-eta record
(``eta``, ``recrystallised_fraction``, ``grain_size``, ``retained_strain``, ...) and the
section means (``*_mean``), with ``Config.MICROSTRUCTURE``."""


def kinetics() -> RecrystallisationSet | None:
    """The set ``Config.MICROSTRUCTURE`` names (None: off)."""
    name = _P.Config.MICROSTRUCTURE
    return None if name is None else get_set(str(name))


def _grain(ip) -> float:
    d = _P._value(ip, "grain_size", None)
    if d is None or not np.isfinite(float(d)) or float(d) <= 0.0:
        raise ValueError(f"hotroll.pyroll: Config.MICROSTRUCTURE = {_P.Config.MICROSTRUCTURE!r} "
                         f"needs in_profile.grain_size (the austenite grain size entering the "
                         f"pass, m, > 0), got {d!r}")
    return float(d)


def _arrays(ip, name: str, mean: float, rtol: float, atol: float):
    """The profile ``name`` over ``hotroll_profile_eta`` as a ThicknessProfile, if both are set
    and its section mean is ``mean`` (else another unit changed the mean: None)."""
    eta, vals = _P._value(ip, "hotroll_profile_eta", None), _P._value(ip, name, None)
    if eta is None or vals is None or len(eta) != len(vals):
        return None
    prof = ThicknessProfile(tuple(float(e) for e in eta), tuple(float(v) for v in vals))
    if abs(prof.mean() - mean) > atol + rtol * abs(mean):
        _LOG.info("hotroll.pyroll: %s's mean %.6g is not the profile's %.6g: not used",
                  name, prof.mean(), mean)
        return None
    return prof


def entry_strain_profile(rp) -> list[list[float]] | None:
    """The pass case's ``plate.strain_profile`` (pairs [eta, strain], strains to 1e-6): the
    strain profile the strip enters with, with ``Config.MICROSTRUCTURE`` (None: off, or no
    profile handed on: the uniform ``in_profile.strain``). Checks ``in_profile.grain_size``."""
    if _P.Config.MICROSTRUCTURE is None:
        return None
    kinetics()                       # an unknown set name fails here, before the FE solve
    ip = rp.in_profile
    _grain(ip)
    e0 = float(_P._value(ip, "strain", 0.0))
    prof = _arrays(ip, "hotroll_strain_profile", e0, 0.0, 2e-6)
    if prof is None or prof.is_uniform:
        return None
    return [[round(e, 9), round(max(v, 0.0), 6)] for e, v in prof.pairs()]


def entry_plate(rp) -> dict:
    """The pass case's [plate] entries for the microstructure: ``strain_profile`` when a
    profile was handed on (``entry_strain_profile``), else none."""
    prof = entry_strain_profile(rp)
    return {} if prof is None else {"strain_profile": prof}


def _entry(rp) -> tuple[ThicknessProfile, ThicknessProfile]:
    """(strain, grain size) profiles entering the pass (as its case took them)."""
    ip = rp.in_profile
    pairs = entry_strain_profile(rp)
    strain = (ThicknessProfile.from_pairs(pairs) if pairs is not None
              else ThicknessProfile.uniform(round(float(_P._value(ip, "strain", 0.0)), 6)))
    d0 = _grain(ip)
    grain = _arrays(ip, "hotroll_grain_size_profile", d0, 1e-9, 0.0)
    return strain, grain if grain is not None else ThicknessProfile.uniform(d0)


def deformed(rp) -> PassState | None:
    """The pass's exit state (``softening.pass_state``, as ``workflows/microstructure.deformed``):
    strain = the entry's at each exit eta + the streamline's pass strain; cached on the pass.
    None when off or not a pass hotroll solves."""
    kin = kinetics()
    if kin is None or not isinstance(rp, RollPass) or not _P.handles(rp):
        return None
    s = _P.solve(rp)
    strain, grain = _entry(rp)
    key = (kin.name, s["case_toml"], grain.pairs().__repr__())
    cache = rp.__dict__.setdefault("_hotroll_pass_state", {})
    if key not in cache:
        prof = folded(s.get("exit_profile")) or {}     # an asymmetric pass's: folded
        if prof.get("pass_strain") is None:
            raise RuntimeError(f"hotroll.pyroll: pass {rp.label!r}: its exit profile has no "
                               f"streamline histories (pass_strain, log_rate_mean, "
                               f"inverse_temperature_mean)")
        eta = np.asarray(prof["eta"], dtype=float)
        cache[key] = pass_state(kin, eta, strain(eta) + np.asarray(prof["pass_strain"], float),
                                grain(eta), prof["log_rate_mean"],
                                prof["inverse_temperature_mean"], prof["temperature"])
    return cache[key]


def _chain(tr):
    """(the hotroll pass, [the plain transports from it to ``tr``]) or None."""
    if type(tr) is not Transport:
        return None
    chain, u = [tr], tr
    while True:
        try:
            u = u.prev
        except (ValueError, IndexError, AttributeError):
            return None
        if type(u) is Transport:
            chain.insert(0, u)
            continue
        if isinstance(u, RollPass) and _P.handles(u):
            return u, chain
        return None


def cooling_history(rp, chain) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(times s, T[i, node] K, node y m) of the strip from the pass's exit temperature profile
    through the transports ``chain`` one after the other (``interpass.cool``, record=True,
    each with its own duration and air data, as
    ``hotroll.pyroll_out_profile.transport_temperature``)."""
    prof = folded(_P.solve(rp)["exit_profile"])
    y, T = np.asarray(prof["eta"], float), np.asarray(prof["temperature"], float)
    half = 0.5 * float(rp.out_profile.height)
    th = _P.Config.THERMAL
    times, rows, t0 = [], [], 0.0
    for i, tr in enumerate(chain):
        duration = _P._value(tr, "duration", None)
        if duration is None:
            raise ValueError(f"hotroll.pyroll: transport {tr.label!r} has no duration: the "
                             f"microstructure needs it")
        res = cool(y, T, half, float(duration), _P._properties(tr.in_profile),
                   float(_P._value(tr, "convection_heat_transfer_coefficient", th["htc_air"])),
                   float(_P._value(tr, "relative_radiation_coefficient", th["emissivity"])),
                   float(_P._value(tr, "environment_temperature", th["ambient_temperature"])),
                   record=True)
        first = 0 if i == 0 else 1        # a later transport starts where the last ended
        times.append(t0 + res.times[first:])
        rows.append(res.history[first:])
        t0 += float(duration)
        y, T = res.y, res.temperature
    return np.concatenate(times), np.concatenate(rows), y


def softened(tr) -> tuple[PassState, Softened] | None:
    """The pass state softened over the cooling from the pass's exit to the end of ``tr``
    (None: off, or not a plain transport after a hotroll pass); cached on the transport."""
    kin = kinetics()
    if kin is None:
        return None
    if type(tr) is Transport and tr.parent is None:     # its sequence is gone: the last
        return tr.__dict__.get("_hotroll_last")         # result, as its out profile's
    found = _chain(tr)
    if found is None:
        return None
    rp, chain = found
    ps = deformed(rp)
    times, T, y = cooling_history(rp, chain)
    key = (id(ps), times.tobytes(), T.tobytes())
    cache = tr.__dict__.setdefault("_hotroll_softened", {})
    if key not in cache:
        cache.clear()
        cache[key] = (ps, soften(kin, ps, times, MS.on_rows(T, y, ps.eta), RETAINED_SHARE,
                                 f"transport {tr.label!r}"))
    tr.__dict__["_hotroll_last"] = cache[key]
    return cache[key]


def _mean(eta, values) -> float:
    return ThicknessProfile(tuple(eta), tuple(np.asarray(values, dtype=float))).mean()


def transport_values(tr) -> dict | None:
    """The values hotroll sets on the transport's out profile (module docstring)."""
    got = softened(tr)
    if got is None:
        return None
    ps, soft = got
    retained = np.maximum(soft.retained_strain, 0.0)
    return {"grain_size": _mean(soft.eta, soft.grain),
            "recrystallized_fraction": _mean(soft.eta, soft.fraction),
            "strain": _mean(soft.eta, retained),
            "hotroll_profile_eta": soft.eta.tolist(),
            "hotroll_strain_profile": retained.tolist(),
            "hotroll_grain_size_profile": soft.grain.tolist(),
            "hotroll_recrystallized_fraction_profile": soft.fraction.tolist()}


def pass_values(rp) -> dict | None:
    """The values hotroll sets on a hotroll pass's out profile (module docstring)."""
    ps = deformed(rp)
    if ps is None:
        return None
    prof = folded(_P.solve(rp)["exit_profile"])
    eta = np.asarray(prof["eta"], dtype=float)
    exit_strain = (np.maximum(np.asarray(prof["strain"], float), 0.0)
                   if prof.get("strain") is not None else ps.strain)
    return {"grain_size": _mean(ps.eta, ps.grain), "recrystallized_fraction": 0.0,
            "hotroll_profile_eta": eta.tolist(), "hotroll_strain_profile": exit_strain.tolist(),
            "hotroll_grain_size_profile": ps.grain.tolist(),
            "hotroll_recrystallized_fraction_profile": [0.0] * eta.size}


def _pass_values(unit) -> dict | None:
    if not isinstance(unit, RollPass) or _P.Config.MICROSTRUCTURE is None:
        return None
    return pass_values(unit)


def _transport_values(unit) -> dict | None:
    if type(unit) is not Transport or _P.Config.MICROSTRUCTURE is None:
        return None
    return transport_values(unit)


def _pass_state_hook(self: RollPass):
    return deformed(self)


def _microstructure_hook(self: Transport):
    got = softened(self)
    if got is None:
        return None
    ps, soft = got
    return {**MS.profile_dict(ps, soft), **MS.transport_columns(soft)}


def install(plugin) -> None:
    """Register with ``plugin`` (the ``hotroll.pyroll`` module, which calls this once when it
    is imported): its Config, solve and handles; the values through
    ``hotroll.pyroll_out_profile.register`` (post-processors, and a sequence's out profile)."""
    global _P
    if _P is not None:
        return
    _P = plugin
    RollPass.hotroll_pass_state.add_function(_pass_state_hook)
    Transport.hotroll_microstructure.add_function(_microstructure_hook)
    out_profile.register(RollPass, _pass_values)
    out_profile.register(Transport, _transport_values)


def mean_kinetics(kin: RecrystallisationSet, strain: float, grain: float, rate: float,
                  T_pass: float, duration: float, T_hold: float | None = None,
                  times=None, history=None) -> dict:
    """hotroll's kinetics on mean values (one point): the pass state of the mean strain,
    grain size (m), strain rate (1/s) and deformation temperature (K), softened over an
    isothermal hold at ``T_hold`` (default ``T_pass``) for ``duration`` s, or over the
    history ``history`` (K) at ``times`` (s)."""
    ps = pass_state(kin, [0.0], [strain], [grain], [np.log(rate)], [1.0 / T_pass], [T_pass])
    if history is None:
        T = float(T_pass if T_hold is None else T_hold)
        times, history = [0.0, float(duration)], [T, T]
    soft = soften(kin, ps, np.asarray(times, float), np.asarray(history, float)[:, None],
                  RETAINED_SHARE, "mean_kinetics")
    return {"critical_strain": float(ps.critical[0]),
            "mechanism": "metadynamic" if soft.metadynamic[0] else "static",
            "half_time": float(soft.half_time[0]),
            "recrystallized_fraction": float(soft.fraction[0]),
            "recrystallized_grain_size": float(soft.rex_grain[0]),
            "grain_size": float(soft.grain[0]), "strain": float(soft.retained_strain[0])}


def _jmak_term(term, q_def: float, prefix: str) -> dict:
    """A PowerTerm as pyroll-jmak-recrystallization's x1 eps^x2 edot^x3 d^x4 exp(qx/RT):
    Z^z = edot^z exp(z Q_def / RT), PyRolL's Z at the unit's own mean temperature."""
    return {f"{prefix}1": term.a, f"{prefix}2": term.strain,
            f"{prefix}3": term.rate + term.zener, f"{prefix}4": term.grain,
            f"q{prefix}": term.q + term.zener * q_def}


def jmak_parameters(kin: RecrystallisationSet) -> dict:
    """The set in pyroll-jmak-recrystallization 3.0.0's form: keyword arguments of its
    ``JMAKRecrystallizationParameters`` (``dynamic``, ``metadynamic``, ``static``) and
    ``JMAKGrainGrowthParameters`` (``growth``). ``dynamic``: the critical strain (a); no
    dynamic fraction in the pass (b1 = 0: PyRolL's X_drx is 0 when eps_c > eps_ref) and no
    dynamic grain size, so that a pass past eps_c goes on to metadynamic recrystallisation
    with its grain unchanged, as hotroll's bookkeeping; PyRolL evaluates the metadynamic Z at
    the transport's mean temperature (hotroll at the pass's)."""
    q = kin.q_def
    return {"dynamic": {"n": 1.0, **_jmak_term(kin.critical, q, "a")},
            "metadynamic": {"n": kin.mdrx_exponent, **_jmak_term(kin.mdrx_time, q, "b"),
                            **_jmak_term(kin.mdrx_grain, q, "c")},
            "static": {"n": kin.srx_exponent, **_jmak_term(kin.srx_time, q, "b"),
                       **_jmak_term(kin.srx_grain, q, "c")},
            "growth": {"d1": kin.growth.exponent, "d2": kin.growth.K, "qd": -kin.growth.q}}
