"""A free surface losing heat by convection and grey-body radiation to the surroundings:
q = h (T - T_a) + eps sigma (T^4 - T_a^4) (Newton's law of cooling; Stefan-Boltzmann, sigma =
5.670374419e-8 W/(m^2 K^4), CODATA 2018)."""
from __future__ import annotations

from dataclasses import dataclass

from hotroll.model.heat_transfer.base import HeatTransferLaw
from hotroll.model.heat_transfer.registry import HeatTransferSpec, register
from hotroll.model.parameters import Parameter

SIGMA_SB = 5.670374419e-8   # Stefan-Boltzmann constant, W/(m^2 K^4)


@dataclass(frozen=True)
class ConvectionRadiation(HeatTransferLaw):
    """q = htc (T - T_env) + emissivity sigma (T^4 - T_env^4), W/m^2."""

    htc: float
    emissivity: float

    name = "convection_radiation"
    kind = "surface"

    def flux(self, T, T_env):
        return self.htc * (T - T_env) + self.emissivity * SIGMA_SB * (T ** 4 - T_env ** 4)

    def dflux(self, T, T_env):
        return self.htc + 4.0 * self.emissivity * SIGMA_SB * T ** 3


register(HeatTransferSpec(
    name="convection_radiation", kind="surface",
    summary="q = htc_air (T - T_ambient) + emissivity sigma (T^4 - T_ambient^4)",
    source="Newton's law of cooling and the Stefan-Boltzmann law (grey body)",
    parameters=(Parameter("htc_air", "convective heat transfer coefficient on the free surfaces",
                          "W/(m^2 K)", ">= 0", ge=0),
                Parameter("emissivity", "emissivity of the free surfaces (radiation)", "",
                          "in [0, 1]", ge=0, le=1)),
    build=lambda v: ConvectionRadiation(v["htc_air"], v["emissivity"])))
