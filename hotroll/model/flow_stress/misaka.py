"""Misaka's law for plain carbon steels, the flow stress of many mill set-up models.

    sigma = exp(0.126 - 1.75 C + 0.594 C^2 + (2851 + 2968 C - 1120 C^2) / T) eps^0.21 edot^0.13

in kgf/mm^2 (x 9.80665e6 for Pa), T in kelvin, C the carbon content in weight percent, eps the
equivalent strain, edot the equivalent strain rate in 1/s. Source: Y. Misaka, T. Yoshimoto,
"Formularization of mean resistance to deformation of plain carbon steels at elevated
temperature", J. JSTP 8 (79), 1967, from hammer-drop tests; valid for strains up to 0.5, 750 to
1200 degC, strain rates 30 to 200 1/s and C up to 1.2 %. Read in the PyRolL plugin's
documentation and code (github.com/pyroll-project/pyroll-misaka-flow-stress, docs/docs.tex and
pyroll/misaka_flow_stress.py, with the same coefficients and the citation above).

The formula is Misaka's *mean* resistance to deformation of a pass; like PyRolL, hotroll uses it
as the local flow stress. PyRolL's plugin evaluates it at (eps + 0.1, edot + 0.1); this module
keeps the published form, so PyRolL's value at (eps, edot, T) is ``sigma(eps + 0.1, edot + 0.1,
T)`` here. The strain is floored at ``strain_min`` (the policy of ``base.py``): eps^0.21 is 0 at
eps = 0. The rate exponent is 0.13 at every temperature, so the law reduces to Norton-Hoff at
each (strain, T) with K = sigma(eps, 1, T) / 3^(1.13/2).
"""
from __future__ import annotations

from typing import Optional

import numpy as np

from hotroll.model.flow_stress.base import (
    DEFAULT_EPS0,
    DEFAULT_STRAIN_MIN,
    FlowStressLaw,
    ValidityRange,
    backend,
    backend_of,
    finite,
)
from hotroll.model.flow_stress.registry import LawSpec, Parameter, register

#: 1 kgf/mm^2 in Pa (standard gravity 9.80665 m/s^2).
KGF_PER_MM2 = 9.80665e6
#: The published ranges (strain up to 0.5, its lower bound not stated).
VALIDITY = ValidityRange.from_celsius(strain=(0.0, 0.5), strain_rate=(30.0, 200.0),
                                      temperature_c=(750.0, 1200.0))
CARBON_MAX = 1.2   # weight percent


class Misaka(FlowStressLaw):
    """Misaka's law at carbon content ``carbon`` (weight percent, 0 to 1.2)."""

    STRAIN_EXPONENT = 0.21
    RATE_EXPONENT = 0.13
    depends_on_strain = True

    def __init__(self, carbon: float, *, eps0: float = DEFAULT_EPS0,
                 strain_min: Optional[float] = None, name: str = "Misaka"):
        self.carbon = finite("carbon", carbon)
        if not 0.0 <= self.carbon <= CARBON_MAX:
            raise ValueError(f"carbon must be in [0, {CARBON_MAX}] weight percent, got {carbon!r}")
        self.eps0 = finite("eps0", eps0)
        if not self.eps0 > 0.0:
            raise ValueError(f"eps0 must be > 0 (1/s), got {eps0!r}")
        self.strain_min = finite("strain_min", DEFAULT_STRAIN_MIN if strain_min is None
                                 else strain_min)
        if not self.strain_min > 0.0:
            raise ValueError(f"strain_min must be > 0, got {strain_min!r}")
        self.validity = VALIDITY
        self.name = name
        c = self.carbon
        self.ln_a = 0.126 - 1.75 * c + 0.594 * c**2        # ln of the factor, kgf/mm^2
        self.theta = 2851.0 + 2968.0 * c - 1120.0 * c**2   # K

    def rate_exponent(self, temperature=None):
        return self.RATE_EXPONENT

    def sigma(self, strain, strain_rate, temperature):
        ops = backend(strain, strain_rate, temperature)
        T = backend_of(temperature).prep(temperature)
        eps = backend_of(strain).floor(backend_of(strain).prep(strain), self.strain_min)
        rate = backend_of(strain_rate).prep(strain_rate)
        with np.errstate(divide="ignore"):  # edot = 0 gives sigma = 0 (log -> -inf, exp -> 0)
            ln_rate = backend_of(strain_rate).log(rate)
        expo = (self.ln_a + self.theta / T + self.STRAIN_EXPONENT * backend_of(strain).log(eps)
                + self.RATE_EXPONENT * ln_rate)
        return KGF_PER_MM2 * ops.exp(expo)

    def describe(self) -> dict:
        return {
            "law": "Misaka",
            "name": self.name,
            "formula": ("sigma = 9.80665e6 exp(0.126 - 1.75 C + 0.594 C^2 + (2851 + 2968 C - "
                        "1120 C^2)/T) eps^0.21 edot^0.13, T in K, C in wt %"),
            "parameters": {"carbon": self.carbon},
            "parameter_units": {"carbon": "wt %"},
            "validity": self.validity.as_dict(),
            "strain_min": self.strain_min,
            "eps0_1_per_s": self.eps0,
            "units": {"sigma": "Pa", "strain_rate": "1/s", "temperature": "K"},
        }

    def __repr__(self) -> str:
        return f"Misaka(carbon={self.carbon!r}, strain_min={self.strain_min!r})"


SPEC = register(LawSpec(
    name="misaka",
    summary="sigma = exp(0.126 - 1.75 C + 0.594 C^2 + (2851 + 2968 C - 1120 C^2)/T) eps^0.21 "
            "edot^0.13 kgf/mm^2, plain carbon steels",
    source="Y. Misaka, T. Yoshimoto, J. JSTP 8 (79), 1967",
    parameters=(Parameter("carbon", "carbon content (Misaka)", "wt %", f"in [0, {CARBON_MAX}]",
                          ge=0.0, le=CARBON_MAX),),
    build=lambda p, eps0: Misaka(p["carbon"], eps0=eps0),
))
