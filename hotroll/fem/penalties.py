"""The penalties of the rolling form (report Table 1, (3.2)) and its unit-free scales: the
report's table (``PenaltyTable``, for the report's scheme and the penalty contact), the
penalties scaled with the viscosity that stay beside exact contact (``ScaledPenalties``), the
reference viscosity they and the multiplier scale with, and the elements next to a boundary
(the element-boundary integrals of the contact). Split from ``fem/rolling_form.py``."""
from __future__ import annotations

from dataclasses import dataclass

from hotroll.model.geometry import RollPass
from hotroll.model.material import NortonHoff


@dataclass(frozen=True)
class PenaltyTable:
    """Table 1 of the report (for K = 1), with h the contact mesh size."""

    h: float
    soft: float = 10.0   # gamma_v0 = gamma_vC in the zone I
    hard: float = 25.0   # gamma_v0 = gamma_vC elsewhere
    inout: float = 2.0   # gamma_in = gamma_out = inout / h^(m+1)

    def surface(self, x, zone):
        from ngsolve import IfPos

        lo, hi = zone
        return IfPos((x - lo) * (hi - x), self.soft / self.h, self.hard / self.h)

    def inlet_outlet(self, m):
        return self.inout / self.h ** (m + 1.0)

    def at_nodes(self, x, zone):
        """gamma_vC at the points x (numpy)."""
        import numpy as np

        lo, hi = zone
        return np.where((x - lo) * (hi - x) > 0, self.soft, self.hard) / self.h


@dataclass(frozen=True)
class ScaledPenalties:
    """The penalties that stay beside exact contact, scaled with the viscosity (Nitsche's
    gamma = gamma0 mu / h): gamma_v0 = 25 mu_ref / h, gamma_in = gamma_out = 2 mu_ref / h, with
    mu_ref the reduced secant viscosity at the pass's reference strain rate. Under a change of
    roll speed, time or length unit they scale as the stresses do; no soft zone."""

    h: float
    mu_ref: object       # a number or a Parameter (RollingForm: it follows the roll speed)
    hard: float = 25.0
    inout: float = 2.0

    def surface(self, x, zone):
        return self.hard * self.mu_ref / self.h

    def inlet_outlet(self, m):
        return self.inout * self.mu_ref / self.h

    def at_nodes(self, x, zone):
        import numpy as np

        mu = self.mu_ref.Get() if hasattr(self.mu_ref, "Get") else self.mu_ref
        return np.full(np.shape(x), self.hard * mu / self.h)



def reference_viscosity(material: NortonHoff, rp: RollPass) -> float:
    """Reduced secant viscosity at the strain rate U / l_c: the scale of every unit-free
    penalty and of the multiplier."""
    rate = rp.u_roll / rp.contact_length
    return float(material.viscosity(rate * rate))


def _elements_on(mesh, regions: str):
    """BitArray of the volume elements with a facet (an edge; a face in 3D) on the boundary
    ``regions``."""
    import re

    from ngsolve import BND, BitArray

    pattern = re.compile(f"^({regions})$")
    # a boundary element is one facet of the volume mesh: an edge in 2D, a face in 3D
    nodes = (lambda el: el.edges) if mesh.dim == 2 else (lambda el: el.faces)
    facets = {nodes(el)[0].nr for el in mesh.Elements(BND) if pattern.match(el.mat)}
    ba = BitArray(mesh.ne)
    ba.Clear()
    for el in mesh.Elements():
        if any(f.nr in facets for f in nodes(el)):
            ba.Set(el.nr)
    return ba
