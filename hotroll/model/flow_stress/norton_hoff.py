"""The Norton-Hoff law (2.17): sigma_f = K 3^((m+1)/2) edot^m, the report's material."""
from __future__ import annotations

from typing import Optional

from hotroll.model.flow_stress.base import DEFAULT_EPS0, FlowStressLaw, ValidityRange, backend_of, finite
from hotroll.model.flow_stress.registry import LawSpec, Parameter, register


class NortonHoffStress(FlowStressLaw):
    """sigma_f = K 3^((m+1)/2) edot^m (2.17), independent of strain and temperature.

    K in Pa s^m, 0 < m <= 1, eps0 > 0 (1/s).  ``viscosity`` equals
    :meth:`hotroll.model.material.NortonHoff.viscosity` for the same (K, m, eps0).
    """

    def __init__(self, K: float, m: float, eps0: float = DEFAULT_EPS0, *,
                 validity: Optional[ValidityRange] = None, name: str = "Norton-Hoff"):
        self.K = finite("K", K)
        if not self.K > 0.0:
            raise ValueError(f"K must be > 0 (Pa s^m), got {K!r}")
        self.m = finite("m", m)
        if not 0.0 < self.m <= 1.0:
            raise ValueError(f"m (rate exponent) must lie in (0, 1], got {m!r}")
        self.eps0 = finite("eps0", eps0)
        if not self.eps0 > 0.0:
            raise ValueError(f"eps0 must be > 0 (1/s), got {eps0!r}")
        self.validity = validity if validity is not None else ValidityRange()
        self.name = name

    def sigma(self, strain, strain_rate, temperature=None):
        r = backend_of(strain_rate).prep(strain_rate)
        return self.K * 3.0 ** ((self.m + 1.0) / 2.0) * r**self.m  # CF ** float works in NGSolve

    def rate_exponent(self, temperature=None):
        return self.m

    def consistency(self, strain=None, temperature=None):
        return self.K

    def describe(self) -> dict:
        return {
            "law": "NortonHoff",
            "formula": "sigma = K 3^((m+1)/2) edot^m",
            "K_Pa_s^m": self.K,
            "m": self.m,
            "eps0_1_per_s": self.eps0,
            "validity": self.validity.as_dict(),
            "units": {"sigma": "Pa", "strain_rate": "1/s", "temperature": "K"},
        }


SPEC = register(LawSpec(
    name="norton-hoff",
    summary="sigma = K 3^((m+1)/2) edot^m, independent of strain and temperature",
    source="Touloupoulos 2020 (the report), (2.17); Norton (1929), Hoff (1954)",
    parameters=(Parameter("K", "Norton-Hoff consistency K", "Pa s^m", "> 0", gt=0),
                Parameter("m", "strain-rate sensitivity m", "", "in (0, 1]", gt=0, le=1)),
    build=lambda p, eps0: NortonHoffStress(p["K"], p["m"], eps0),
))
