"""What the two temperature couplings share (issue 16): the flow stress at the temperature, the
lagged rate of its exponent correction, and the contact's temperature columns.

``coupling.ThermalCoupling`` (steady solver, the temperature on its own strip mesh) and
``lagrangian.LagrangianThermal`` (the report's scheme, the temperature carried by the moving
plate mesh) differ only in where the temperature lives and how it is advanced.
"""
from __future__ import annotations

import math

import numpy as np

from .field import SolveInfo
from .properties import ThermalBoundary, ThermalProperties


class FlowStressFeedback:
    """The consistency K(eps, T)/K_ref a temperature gives the form. The form has one rate
    exponent m_ref (the law's at the entry temperature); where the law's m(T) differs, the
    consistency carries the difference at the last strain rate e*: K_eff = K(eps, T)
    (3 e*^2)^((m(T) - m_ref)/2), e*^2 = eps0^2 + edot^2, so that the stress is the law's at
    e* exactly; e* is updated with the temperature (``_lag_rate``)."""

    def __init__(self, mesh, props: ThermalProperties, bc: ThermalBoundary, K_ref: float,
                 m_ref: float, eps0: float, flow=None, strain=None, entry_strain: float = 0.0):
        from ngsolve import H1, GridFunction

        self.mesh, self.props, self.bc = mesh, props, bc
        self.K_ref, self.m_ref, self.eps0 = float(K_ref), float(m_ref), eps0
        self.flow, self.strain, self.entry_strain = flow, strain, float(entry_strain)
        self._rate2 = GridFunction(H1(mesh, order=1))   # e*^2 = eps0^2 + edot^2, lagged
        self._rate2.vec[:] = 1.0
        self.form = None
        self.last = SolveInfo(0, 0.0)
        # whether the law's rate exponent depends on the temperature (Hensel-Spittel m8)
        self.m_varies = flow is not None and (float(flow.rate_exponent(1000.0))
                                              != float(flow.rate_exponent(1500.0)))

    def _consistency_at(self, T):
        """K(eps, T)/K_ref at the temperature CF ``T`` and the strain field, with the rate
        exponent correction; 1.0 for a temperature-free law."""
        if self.flow is None:
            return 1.0
        from ngsolve import exp, log

        eps = self.strain.gf if self.strain is not None else self.entry_strain
        ratio = self.flow.consistency(eps, T) / self.K_ref
        if self.m_varies:
            ratio = ratio * exp(0.5 * (self.flow.rate_exponent(T) - self.m_ref)
                                * (math.log(3.0) + log(self._rate2)))
        return ratio

    def _e2(self):
        from ..discretisation.forms import strain_rate
        from ..physics.material import edot_squared

        return edot_squared(strain_rate(self.form.problem.velocity))

    def _lag_rate(self) -> None:
        """e*^2 = eps0^2 + edot^2 of the current flow, P1; floored at eps0^2 (the projection
        of a steep rate field overshoots below zero, and its log would be NaN)."""
        if self.m_varies:
            self._rate2.Set(self._e2() + self.eps0**2)
            vals = self._rate2.vec.FV().NumPy()
            vals[:] = np.maximum(vals, self.eps0**2)

    def vertex_temperature(self) -> np.ndarray:  # pragma: no cover - each coupling has one
        raise NotImplementedError

    def contact_columns(self) -> dict[str, np.ndarray]:
        """Vertex fields for the contact and top profiles: the temperature (K) and, on the
        contact, the heat flux to the roll htc_contact (T - T_roll) (W/m^2)."""
        T, bc = self.vertex_temperature(), self.bc
        return {"temperature": T, "heat_flux_to_roll": bc.htc_contact * (T - bc.roll_temperature)}
