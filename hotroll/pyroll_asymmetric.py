"""PyRolL's asymmetric two-roll pass in hotroll's plugin (``hotroll.pyroll``; issue 52 item 4).

pyroll-core 3.1 has no asymmetric pass. Its open pull request #251 adds
``AsymmetricTwoRollPass(upper_roll, lower_roll, ...)`` with the hook hosts ``UpperRoll`` and
``LowerRoll``, and removes ``BaseRollPass.Roll`` (its roll hooks move to
``SymmetricRollPass.Roll``: docs/notes, ../shared/notes/asymmetric-rolling.md 5). This module
keeps the plugin working on either layout, detecting by attributes, not by import:

- ``roll_hosts``: the classes the base pass's roll hooks go on: ``BaseRollPass.Roll`` where it
  exists, else ``SymmetricRollPass.Roll``, and the asymmetric pass's ``UpperRoll``/``LowerRoll``
  where that class exists;
- ``is_asymmetric``: a pass with ``upper_roll`` and ``lower_roll`` (the PR's class);
- ``pass_rolls``: the hotroll case's [pass] keys of such a pass, each roll's radius and surface
  speed read from ITS roll (``Roll.working_radius`` if set, else ``nominal_radius``;
  ``working_velocity``, ``rotational_frequency`` or ``surface_velocity``, as
  ``pyroll_inputs.roll_radius``/``surface_speed``). Each roll must give its own speed (the
  pass's ``velocity`` is one strip speed, not two roll speeds). The strip enters at hotroll's
  own pass line (both rolls bite at the same x), not at the PR's ``InProfile.pass_line``;
- ``refusal``: what PyRolL described against what hotroll's full-thickness strip needs;
- ``install_on``: the asymmetric pass's hook implementations (tryfirst): ``roll_force`` (the
  two rolls' mean, whole width: their vertical forces balance), ``UpperRoll``/``LowerRoll``
  ``roll_torque`` (each roll's own, < 0: a braking roll) and ``neutral_angle`` (PyRolL's sign),
  ``OutProfile`` ``velocity``, ``width``, ``strain`` and the declared ``curvature`` (1/m, > 0
  curls up), and ``hotroll_result`` (the summary, ``rolls`` per roll).
"""
from __future__ import annotations

from hotroll import pyroll_inputs as _in


def roll_hosts(base, symmetric, asymmetric=None) -> list:
    """The roll classes the base pass's roll hooks (contact length, flattened radius) go on:
    ``base.Roll`` (pyroll-core 3.1) or, where it is gone (PR #251), ``symmetric.Roll``; and the
    asymmetric pass's ``UpperRoll`` and ``LowerRoll`` where ``asymmetric`` is given."""
    hosts = [getattr(base, "Roll", None) or symmetric.Roll]
    for name in ("UpperRoll", "LowerRoll"):
        host = getattr(asymmetric, name, None) if asymmetric is not None else None
        if host is not None and host not in hosts:
            hosts.append(host)
    return hosts


def is_asymmetric(rp) -> bool:
    """Whether ``rp`` is a two-roll pass with its own upper and lower roll (PR #251's
    ``AsymmetricTwoRollPass``), told by its attributes."""
    return (getattr(rp, "upper_roll", None) is not None
            and getattr(rp, "lower_roll", None) is not None)


def rolls(rp) -> tuple[tuple[float, float | None], tuple[float, float | None]]:
    """((R, U) upper, (R, U) lower): each roll's radius (m) and surface speed (m/s or None)."""
    return tuple((_in.roll_radius(r), _in.surface_speed(r))
                 for r in (rp.upper_roll, rp.lower_roll))


def missing(rp) -> str | None:
    """What hotroll lacks of an asymmetric pass's rolls (None: nothing)."""
    names = [n for n, (_, U) in zip(("upper_roll", "lower_roll"), rolls(rp)) if U is None]
    if names:
        return (f"no roll speed on {' and '.join(names)} (each roll's own rotational_frequency, "
                f"surface_velocity or working_velocity: an asymmetric pass needs two)")
    return None


def pass_rolls(rp) -> dict:
    """The case's [pass] keys of an asymmetric pass's two rolls: the upper roll's radius and
    angular velocity as the pass's, the lower roll's as [pass.lower]."""
    (R1, U1), (R2, U2) = rolls(rp)
    return {"roll_radius": R1, "roll_angular_velocity": U1 / R1,
            "lower": {"roll_radius": R2, "roll_surface_speed": U2}}


def described(rp) -> str:
    """What PyRolL describes of the pass's rolls, in words with units."""
    (R1, U1), (R2, U2) = rolls(rp)
    return (f"PyRolL describes an asymmetric two-roll pass (upper roll R = {1e3 * R1:g} mm, "
            f"U = {U1:.6g} m/s; lower roll R = {1e3 * R2:g} mm, U = {U2:.6g} m/s)")


def refusal(rp, problems: list[str]) -> str:
    """The message refusing the asymmetric pass ``rp``: what PyRolL described, and the case
    keys hotroll's full-thickness strip needs otherwise (``problems``, each naming its key)."""
    return (f"hotroll.pyroll: pass {rp.label!r}: {described(rp)}; hotroll solves it on its "
            f"full-thickness strip, which needs: " + "; ".join(problems))


def roll_figure(summary: dict, k: int, key: str):
    """The k-th roll's (0 upper, 1 lower) figure ``key`` of hotroll's summary: its ``rolls``
    entry; two equal rolls are the half model's pass, whose one roll's figure both share."""
    rolls_ = summary.get("rolls")
    return summary[key] if rolls_ is None else rolls_[k][key]


def install_on(cls, solve, handles, declare) -> None:
    """The hook implementations on the asymmetric pass class ``cls`` (module docstring), each
    None where ``handles(rp)`` is false; ``solve(rp)`` is hotroll's summary; ``declare(host,
    name, doc)`` declares a hook. Hooks the class does not have are skipped."""
    from pyroll.core import Hook

    def on(host, name, func):
        if host is not None and isinstance(getattr(host, name, None), Hook):
            getattr(host, name)(tryfirst=True)(func)

    def width(rp):
        return float(rp.in_profile.width)

    if not isinstance(getattr(cls, "hotroll_result", None), Hook):
        cls.hotroll_result = Hook[dict]()
    on(cls, "hotroll_result", lambda self: solve(self) if handles(self) else None)
    on(cls, "roll_force", lambda self: solve(self)["roll_force"] * width(self)
       if handles(self) else None)
    for k, name in enumerate(("UpperRoll", "LowerRoll")):
        host = getattr(cls, name, None)

        def torque(self, k=k):
            rp = self.roll_pass
            return roll_figure(solve(rp), k, "roll_torque") * width(rp) if handles(rp) else None

        def neutral(self, k=k):
            rp = self.roll_pass
            if not handles(rp):
                return None
            ang = roll_figure(solve(rp), k, "neutral_angle")
            return None if ang is None else -ang

        on(host, "roll_torque", torque)
        on(host, "neutral_angle", neutral)
    out = getattr(cls, "OutProfile", None)
    if out is not None:
        declare(out, "curvature", "the strip's exit curvature, 1/m (> 0 curls up)")
        for name, key in (("velocity", "exit_velocity"), ("strain", "outlet_strain_mean"),
                          ("curvature", "exit_curvature")):
            on(out, name, lambda self, key=key: solve(self.roll_pass).get(key, 0.0)
               if handles(self.roll_pass) else None)
        on(out, "width", lambda self: width(self.roll_pass) if handles(self.roll_pass)
           else None)
