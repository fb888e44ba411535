"""A field over the strip's quarter cross-section (issue 53): values on a tensor grid of
eta = y / half thickness (0 at mid-thickness, 1 at the surface) and zeta = z / half width
(0 at mid-width, 1 at the edge), bilinear between. The entry temperature of a 3D pass whose
edges cooled before it (a schedule's interpass cooling across the width,
``model/interpass_section.py``)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hotroll.model.profile import ProfileError, ThicknessProfile


def _axis(name: str, values) -> np.ndarray:
    a = np.asarray(values, dtype=float)
    if a.ndim != 1 or a.size < 2 or not np.all(np.isfinite(a)) or a[0] != 0.0 or a[-1] != 1.0 \
            or np.any(np.diff(a) <= 0.0):
        raise ProfileError(f"a cross-section's {name} must increase strictly from 0 to 1 "
                           f"(>= 2 values), got {np.asarray(values).tolist()}")
    return a


@dataclass(frozen=True)
class SectionProfile:
    """Values (``values[i][j]`` at ``eta[i]``, ``zeta[j]``) over the quarter cross-section."""

    eta: tuple[float, ...]
    zeta: tuple[float, ...]
    values: tuple[tuple[float, ...], ...]

    def __post_init__(self):
        eta, zeta = _axis("eta", self.eta), _axis("zeta", self.zeta)
        v = np.asarray(self.values, dtype=float)
        if v.shape != (eta.size, zeta.size) or not np.all(np.isfinite(v)):
            raise ProfileError(f"a cross-section's values must be finite, {eta.size} rows (eta) "
                               f"of {zeta.size} (zeta), got shape {v.shape}")
        object.__setattr__(self, "eta", tuple(float(e) for e in eta))
        object.__setattr__(self, "zeta", tuple(float(z) for z in zeta))
        object.__setattr__(self, "values", tuple(tuple(float(x) for x in row) for row in v))

    @classmethod
    def from_dict(cls, d: dict) -> SectionProfile:
        """From {"eta": [...], "zeta": [...], "values": [[...], ...]} (the case file's form)."""
        return cls(tuple(d["eta"]), tuple(d["zeta"]), tuple(tuple(r) for r in d["values"]))

    def to_dict(self) -> dict:
        return {"eta": list(self.eta), "zeta": list(self.zeta),
                "values": [list(r) for r in self.values]}

    @property
    def array(self) -> np.ndarray:
        return np.asarray(self.values)

    def __call__(self, eta, zeta) -> np.ndarray:
        """The values at (eta, zeta) (arrays of one shape, clipped into [0, 1]): bilinear."""
        e = np.clip(np.asarray(eta, dtype=float), 0.0, 1.0)
        z = np.clip(np.asarray(zeta, dtype=float), 0.0, 1.0)
        ge, gz, v = np.asarray(self.eta), np.asarray(self.zeta), self.array
        i = np.clip(np.searchsorted(ge, e, side="right") - 1, 0, ge.size - 2)
        j = np.clip(np.searchsorted(gz, z, side="right") - 1, 0, gz.size - 2)
        a = (e - ge[i]) / (ge[i + 1] - ge[i])
        b = (z - gz[j]) / (gz[j + 1] - gz[j])
        return ((1 - a) * (1 - b) * v[i, j] + a * (1 - b) * v[i + 1, j]
                + (1 - a) * b * v[i, j + 1] + a * b * v[i + 1, j + 1])

    def mid_width(self) -> ThicknessProfile:
        """The profile through the thickness at mid-width (zeta = 0)."""
        return ThicknessProfile(self.eta, tuple(self.array[:, 0]))

    def offset(self, eta, zeta) -> np.ndarray:
        """The values less mid-width's at the same eta: what the width adds."""
        eta = np.asarray(eta, dtype=float)
        return self(eta, zeta) - self(eta, np.zeros_like(eta))

    def is_uniform_across(self, up_to: float = 1.0, rel: float = 1e-9) -> bool:
        """True if every row equals its mid-width value for zeta <= ``up_to``."""
        v = self.array
        cols = np.asarray(self.zeta) <= up_to
        at = self(np.asarray(self.eta), np.full(len(self.eta), min(up_to, 1.0)))
        scale = np.max(np.abs(v))
        return bool(np.all(np.abs(v[:, cols] - v[:, :1]) <= rel * scale)
                    and np.all(np.abs(at - v[:, 0]) <= rel * scale))

    def uniform_up_to(self, cut: float) -> SectionProfile:
        """The section with mid-width's column everywhere up to ``cut`` (zeta; a node put
        there): an edge zone's interior, uniform across the width."""
        z = np.asarray(self.zeta)
        keep = z > cut
        zeta = np.concatenate([[0.0, cut] if cut > 0.0 else [0.0], z[keep]])
        mid = self.array[:, :1]
        inner = np.repeat(mid, 2 if cut > 0.0 else 1, axis=1)
        values = np.concatenate([inner, self.array[:, keep]], axis=1)
        return SectionProfile(self.eta, tuple(zeta), tuple(tuple(r) for r in values))

    @classmethod
    def across(cls, profile: ThicknessProfile, offset: dict | None = None) -> SectionProfile:
        """A profile through the thickness, the same at every width, plus ``offset`` (K, a
        dict of ``eta``, ``zeta`` and ``values``: a 3D pass's ``exit_temperature_offset``,
        linear in eta between its rows; None: nothing added), on the union of the two eta
        grids (the profile's grading, fine under the roll's chill, kept)."""
        if offset is None:
            v = np.asarray(profile.values)
            return cls(profile.eta, (0.0, 1.0), tuple((x, x) for x in v))
        e_off = np.asarray(offset["eta"], dtype=float)
        eta = np.union1d(np.asarray(profile.eta), e_off)
        add = np.asarray(offset["values"], dtype=float)
        add = np.stack([np.interp(eta, e_off, add[:, j]) for j in range(add.shape[1])], axis=1)
        values = profile(eta)[:, None] + add
        return cls(tuple(eta), tuple(offset["zeta"]), tuple(tuple(r) for r in values))

    def offset_dict(self) -> dict:
        """``offset`` for ``across``: the values less mid-width's at each eta (K)."""
        v = self.array
        return {"eta": list(self.eta), "zeta": list(self.zeta),
                "values": (v - v[:, :1]).tolist()}

    def edge_mean(self) -> float:
        """The edge face's mean over the thickness (zeta = 1; K)."""
        return ThicknessProfile(self.eta, tuple(self.array[:, -1])).mean()
