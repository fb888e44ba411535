"""What the two temperature couplings share (issue 16): the flow stress at the temperature (its
consistency and its rate exponent) and the contact's temperature columns.

``coupling.ThermalCoupling`` (steady solver, the temperature on its own strip mesh) and
``lagrangian.LagrangianThermal`` (the report's scheme, the temperature carried by the moving
plate mesh) differ only in where the temperature lives and how it is advanced.
"""
from __future__ import annotations

import numpy as np

from hotroll.fem.forms import strain_rate
from hotroll.fem.thermal_field import SolveInfo
from hotroll.model.material import edot_squared
from hotroll.model.thermal_properties import ThermalBoundary, ThermalProperties


def rate_exponent_varies(flow) -> bool:
    """Whether the law's rate exponent depends on the temperature (Hensel-Spittel m8)."""
    return float(flow.rate_exponent(1000.0)) != float(flow.rate_exponent(1500.0))


class FlowStressFeedback:
    """The flow stress a temperature gives the form: the consistency K(eps, T)/K_ref and,
    where the law's rate exponent depends on the temperature (Hensel-Spittel m8), the offset
    m(T) - m_ref the form adds to its exponent (``RollingForm``'s ``rate_offset``). The form's
    stress K(eps, T) 3^((m(T)+1)/2) (eps0^2 + edot^2)^(m(T)/2) is then the law's at every strain
    rate, in the residual and in Newton's tangent alike."""

    def __init__(self, mesh, props: ThermalProperties, bc: ThermalBoundary, K_ref: float,
                 m_ref: float, eps0: float, flow=None, strain=None, entry_strain: float = 0.0):
        self.mesh, self.props, self.bc = mesh, props, bc
        self.K_ref, self.m_ref, self.eps0 = float(K_ref), float(m_ref), eps0
        self.flow, self.strain, self.entry_strain = flow, strain, float(entry_strain)
        self.form = None
        self.last = SolveInfo(0, 0.0)
        self.m_varies = flow is not None and rate_exponent_varies(flow)

    def _consistency_at(self, T):
        """K(eps, T)/K_ref at the temperature ``T`` (a CF, or numbers) and the strain field;
        1.0 for a temperature-free law."""
        if self.flow is None:
            return 1.0
        eps = self.strain.gf if self.strain is not None else self.entry_strain
        return self.flow.consistency(eps, T) / self.K_ref

    def _rate_offset_at(self, T):
        """m(T) - m_ref at the temperature ``T`` (a CF, or numbers)."""
        return self.flow.rate_exponent(T) - self.m_ref

    def rate_offset(self):  # pragma: no cover - each coupling has one
        """The form's rate-exponent offset (a CF), or None where the exponent is m_ref."""
        raise NotImplementedError

    def _heat_sources(self, k=None):
        """(plastic power density s:eps_dot = K_ref mu eps_dot:eps_dot, W/m^3, of the form's
        own law; friction power per contact area K_ref k_f |v_s|^2, W/m^2) as CFs of the
        form's fields; ``k``: RollingForm.friction_coefficient's."""
        from ngsolve import InnerProduct

        f = self.form
        u = f.nonlinear.velocity
        eps = strain_rate(u)
        mu = f.material.viscosity(self._e2(), m=f.m_material, K=f.consistency)
        s = f.slip(u)
        return (self.K_ref * mu * InnerProduct(eps, eps),
                self.K_ref * f.friction_coefficient(u, k) * s * s)

    def _e2(self):
        return edot_squared(strain_rate(self.form.nonlinear.velocity))

    def vertex_temperature(self) -> np.ndarray:  # pragma: no cover - each coupling has one
        raise NotImplementedError

    def contact_columns(self) -> dict[str, np.ndarray]:
        """Vertex fields for the contact and top profiles: the temperature (K) and, on the
        contact, the heat flux to the roll, the contact law's q(T, T_roll) (W/m^2)."""
        T, bc = self.vertex_temperature(), self.bc
        return {"temperature": T, "heat_flux_to_roll": bc.contact.flux(T, bc.roll_temperature)}
