"""The interface of a heat-transfer law at the strip's surface: the heat flux out of the strip
q(T, T_env) (W/m^2) through the roll contact or a free surface, with T the strip's surface
temperature and T_env the roll's or the ambient's (K). The same arithmetic serves numbers,
numpy arrays and NGSolve CoefficientFunctions (the FE forms differentiate it for Newton)."""
from __future__ import annotations

#: Where a law acts: the strip-roll contact or the free surfaces (air, radiation).
KINDS = ("contact", "surface")


class HeatTransferLaw:
    """q(T, T_env): the heat flux out of the strip, W/m^2 (positive when the strip loses heat)."""

    name = ""
    kind = ""

    def flux(self, T, T_env):
        raise NotImplementedError

    def dflux(self, T, T_env):
        """dq/dT, W/(m^2 K) (the 1D interpass cooling's Newton)."""
        raise NotImplementedError
