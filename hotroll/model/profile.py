"""A quantity through the strip's half thickness (issue 17): what a pass hands to the next.

A schedule carries the temperature and the strain from pass to pass as profiles over
eta = y / (half thickness) in [0, 1] (0 the centre line, 1 the surface), piecewise linear in
eta. The steady solver takes them as the inlet's values (``fem/thermal_field.py``,
``fem/strain.py``) and measures them at the exit (``results/profiles.py``).

An asymmetric pass's exit profile spans the whole thickness, eta in [-1, 1] (-1 the lower
surface); ``fold`` makes it a half-thickness profile, the mean of the two halves (its section
mean unchanged), for a next pass that takes one.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


class ProfileError(ValueError):
    """A profile that is not a function of eta on [0, 1]."""


@dataclass(frozen=True)
class ThicknessProfile:
    """Values at eta = y / half thickness (strictly increasing from 0 to 1), linear between."""

    eta: tuple[float, ...]
    values: tuple[float, ...]

    def __post_init__(self):
        eta = np.asarray(self.eta, dtype=float)
        vals = np.asarray(self.values, dtype=float)
        if eta.ndim != 1 or eta.shape != vals.shape or len(eta) < 2:
            raise ProfileError(f"a profile needs >= 2 (eta, value) pairs of equal length, got "
                               f"{eta.shape} eta and {vals.shape} values")
        if not (np.all(np.isfinite(eta)) and np.all(np.isfinite(vals))):
            raise ProfileError("a profile's eta and values must be finite numbers")
        if eta[0] != 0.0 or eta[-1] != 1.0 or np.any(np.diff(eta) <= 0.0):
            raise ProfileError(f"a profile's eta must increase strictly from 0 (centre) to 1 "
                               f"(surface), got {eta.tolist()}")
        object.__setattr__(self, "eta", tuple(float(e) for e in eta))
        object.__setattr__(self, "values", tuple(float(v) for v in vals))

    @classmethod
    def from_pairs(cls, pairs) -> ThicknessProfile:
        """From [[eta, value], ...] (the case file's form)."""
        arr = np.asarray(pairs, dtype=float)
        if arr.ndim != 2 or arr.shape[1] != 2:
            raise ProfileError(f"a profile is a list of [eta, value] pairs, got shape {arr.shape}")
        return cls(tuple(arr[:, 0]), tuple(arr[:, 1]))

    @classmethod
    def uniform(cls, value: float) -> ThicknessProfile:
        return cls((0.0, 1.0), (float(value), float(value)))

    def pairs(self) -> list[list[float]]:
        return [[e, v] for e, v in zip(self.eta, self.values)]

    def __call__(self, eta) -> np.ndarray:
        """The values at eta (clipped into [0, 1])."""
        return np.interp(np.clip(np.asarray(eta, dtype=float), 0.0, 1.0), self.eta, self.values)

    def weights(self) -> np.ndarray:
        """Trapezoid weights of the values over eta (they sum to 1)."""
        d = np.diff(np.asarray(self.eta))
        w = np.zeros(len(self.eta))
        w[:-1] += 0.5 * d
        w[1:] += 0.5 * d
        return w

    def mean(self) -> float:
        """The section mean int_0^1 value d eta (exact for the piecewise-linear profile)."""
        e, v = np.asarray(self.eta), np.asarray(self.values)
        return float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(e)))

    def scaled(self, factor: float) -> ThicknessProfile:
        return ThicknessProfile(self.eta, tuple(factor * v for v in self.values))

    @classmethod
    def fold(cls, eta, values) -> ThicknessProfile:
        """The half-thickness profile of a whole-thickness one (``eta`` increasing from -1 to
        1, piecewise linear): (f(eta) + f(-eta)) / 2 at every |eta| of either half, so that its
        mean over [0, 1] is f's over [-1, 1] exactly."""
        e, v = np.asarray(eta, dtype=float), np.asarray(values, dtype=float)
        if e.ndim != 1 or e.shape != v.shape or len(e) < 2 or e[0] != -1.0 or e[-1] != 1.0 \
                or np.any(np.diff(e) <= 0.0):
            raise ProfileError(f"a whole-thickness profile's eta must increase strictly from -1 "
                               f"to 1, got {e.tolist()}")
        nodes = np.unique(np.abs(e))
        if nodes[0] != 0.0:
            nodes = np.concatenate([[0.0], nodes])
        return cls(tuple(nodes), tuple(0.5 * (np.interp(nodes, e, v) + np.interp(-nodes, e, v))))

    @property
    def is_uniform(self) -> bool:
        return max(self.values) == min(self.values)


def folded(prof: dict | None) -> dict | None:
    """A summary's exit profile over the half thickness: a whole-thickness one (eta from -1, an
    asymmetric pass's) with each of its lists folded about the middle (``ThicknessProfile.
    fold``: the mean of the two halves; the shear strain, odd about the middle, left out), a
    half-thickness one (or None) as it is."""
    if prof is None or prof["eta"][0] >= 0.0:
        return prof
    out, eta = {}, None
    for key, values in prof.items():
        if key in ("eta", "shear_strain"):
            continue
        if values is None:
            out[key] = None
            continue
        f = ThicknessProfile.fold(prof["eta"], values)
        out[key], eta = list(f.values), list(f.eta)
    out["eta"] = eta if eta is not None else [0.0, 1.0]
    return out
