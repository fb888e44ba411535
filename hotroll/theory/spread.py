"""Empirical spread of a flat rectangle: Hill, Sparling and Wusatowski as PyRolL implements them.

An independent reference for the 3D strip's mean exit width (issue 53).  Each function returns
the exit width b1 (m) of a rectangle b0 x h0 rolled to h1 between flat rolls of radius R (m);
numpy only, scalars or broadcastable arrays.  The formulas are transcribed from the width hooks
of PyRolL's spreading plugins (pyroll-project on GitHub, files ``pyroll/<name>_spreading.py``):

* Hill, plugin pyroll-hill-spreading 3.0.0, commit 1bec893ee9927f04aebd0fad9536c3d6bc038ca7,
  docs/docs.tex eqs. (hill), (exponent):
      b1 / b0 = (h0 / h1)^w,   w = k exp(-b0 / (2 sqrt(R dh))),   k = 0.5 (``hill_pre_factor``).
* Sparling, pyroll-sparling-spreading 3.0.0, commit eb79d7c44ee723a87dc543a00c2cf82c40f8f46e,
  docs/docs.tex eqs. (sparling), (exponent):
      b1 / b0 = (h0 / h1)^(w a b f g j),
      w = 0.981 exp(-0.6735 * 2.395 b0^0.9 / (R^0.55 h0^0.1 dh^0.25)),   a = b = f = g = j = 1.
* Wusatowski, pyroll-wusatowski-spreading 3.0.0, commit 4bc1ee15f088f6b84735403ed7d2c4e607bac541,
  docs/docs.tex eqs. (wusatowski), (exponent_low), (exponent_high):
      b1 / b0 = a c d f gamma^(-w),   gamma = h1 / h0,
      w = 10^(-1.269 (h0 / 2R)^0.556 b0 / h0)   for gamma >= 0.5,
      w = 10^(-3.457 (h0 / 2R)^0.968 b0 / h0)   for gamma <  0.5  (the code's 0.968; the docs print 0.958),
  a = d = f = 1.  The plugin's default velocity coefficient c is not 1 but
  :func:`wusatowski_velocity_coefficient` (eq. velocity-coefficient, < 1 at roughing speeds, so wide
  stock narrows); here c defaults to 1 (all correction factors 1), pass it explicitly for PyRolL's.
  Before commit ad4985a (2022-05-30) code and docs had a single exponent with (h0/2R)^0.56.

dh = h0 - h1.  For a sharp-cornered rectangle in a flat groove PyRolL's equivalent rectangle is
the rectangle itself (pyroll-core profile/hookimpls.py: sqrt(A h / w) = h) and its working radius
the nominal one (FlatGroove.groove_factor = 0), so b0, h0, h1 and R here are the plugins' quantities.
"""

from __future__ import annotations

import numpy as np

__all__ = ["hill", "sparling", "wusatowski", "wusatowski_velocity_coefficient"]


def _check(b0, h0, h1, R):
    """Arrays of the pass geometry; ValueError naming the first non-physical argument."""
    b0, h0, h1, R = (np.asarray(x, dtype=float) for x in (b0, h0, h1, R))
    for name, v in (("b0", b0), ("h0", h0), ("h1", h1), ("R", R)):
        if not np.all(v > 0) or not np.all(np.isfinite(v)):
            raise ValueError(f"{name} must be finite and > 0, got {v}")
    if not np.all(h1 < h0):
        raise ValueError(f"h1 must be < h0 (a reduction), got h1 = {h1}, h0 = {h0}")
    return b0, h0, h1, R


def _out(x):
    return float(x) if np.ndim(x) == 0 else x


def hill(b0, h0, h1, R, *, pre_factor=0.5):
    """Exit width b1 (m) after Hill: b1 = b0 (h0/h1)^w, w = k exp(-b0 / (2 sqrt(R dh))), k = 0.5."""
    b0, h0, h1, R = _check(b0, h0, h1, R)
    w = pre_factor * np.exp(-b0 / (2.0 * np.sqrt(R * (h0 - h1))))
    return _out(b0 * (h0 / h1) ** w)


def sparling(b0, h0, h1, R, *, roll_surface_coefficient=1.0, bar_surface_coefficient=1.0,
             material_coefficient=1.0, temperature_coefficient=1.0, strain_rate_coefficient=1.0):
    """Exit width b1 (m) after Sparling: b1 = b0 (h0/h1)^(w a b f g j),
    w = 0.981 exp(-0.6735 * 2.395 b0^0.9 / (R^0.55 h0^0.1 dh^0.25))."""
    b0, h0, h1, R = _check(b0, h0, h1, R)
    w = 0.981 * np.exp(-0.6735 * (2.395 * b0 ** 0.9 / (R ** 0.55 * h0 ** 0.1 * (h0 - h1) ** 0.25)))
    c = (roll_surface_coefficient * bar_surface_coefficient * material_coefficient
         * temperature_coefficient * strain_rate_coefficient)
    return _out(b0 * (h0 / h1) ** (w * c))


def wusatowski(b0, h0, h1, R, *, temperature_coefficient=1.0, velocity_coefficient=1.0,
               material_coefficient=1.0, friction_coefficient=1.0):
    """Exit width b1 (m) after Wusatowski: b1 = b0 a c d f (h1/h0)^-w, w = 10^(-1.269 (h0/2R)^0.556 b0/h0)
    for h1/h0 >= 0.5, 10^(-3.457 (h0/2R)^0.968 b0/h0) below."""
    b0, h0, h1, R = _check(b0, h0, h1, R)
    gamma = h1 / h0
    x = h0 / (2.0 * R)
    w = np.where(gamma >= 0.5, 10.0 ** (-1.269 * x ** 0.556 * b0 / h0), 10.0 ** (-3.457 * x ** 0.968 * b0 / h0))
    c = temperature_coefficient * velocity_coefficient * material_coefficient * friction_coefficient
    return _out(b0 * c * gamma ** -w)


def wusatowski_velocity_coefficient(h0, h1, v):
    """PyRolL's default Wusatowski velocity coefficient c = (-0.002958 + 0.00341 gamma) v + 1.07168
    - 0.10431 gamma, gamma = h1/h0, v the roll pass velocity in m/s."""
    gamma = np.asarray(h1, dtype=float) / np.asarray(h0, dtype=float)
    return _out((-0.002958 + 0.00341 * gamma) * np.asarray(v, dtype=float) + 1.07168 - 0.10431 * gamma)
