"""Strip-roll contact with a constant heat-transfer coefficient: q = h_c (T - T_roll)
(Newton's law of cooling across the interface; h_c given by the user, W/(m^2 K))."""
from __future__ import annotations

from dataclasses import dataclass

from hotroll.model.heat_transfer.base import HeatTransferLaw
from hotroll.model.heat_transfer.registry import HeatTransferSpec, register
from hotroll.model.parameters import Parameter


@dataclass(frozen=True)
class ConstantConductance(HeatTransferLaw):
    """q = htc (T - T_env), W/m^2."""

    htc: float

    name = "constant"
    kind = "contact"

    def flux(self, T, T_env):
        return self.htc * (T - T_env)

    def dflux(self, T, T_env):
        return self.htc + 0.0 * T


register(HeatTransferSpec(
    name="constant", kind="contact",
    summary="q = htc_contact (T - roll_temperature)",
    source="Newton's law of cooling across the strip-roll interface",
    parameters=(Parameter("htc_contact", "heat transfer coefficient strip -> roll in the contact",
                          "W/(m^2 K)", ">= 0", ge=0),),
    build=lambda v: ConstantConductance(v["htc_contact"])))
