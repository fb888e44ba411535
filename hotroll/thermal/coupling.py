"""Thermo-mechanical coupling of a rolling form and its temperature field (issue 16; beyond the
report: Touloupoulos 2020 is isothermal).

Mechanics -> heat: the plastic power density s:eps_dot = K_ref mu eps_dot:eps_dot (W/m^3, the
form's law, reduced stresses times K_ref) and the friction power per area K_ref k_f |v_s|^2
(W/m^2) on the contact feed ``TemperatureField`` (``field.py``). For the laws with k = sigma/sqrt3
(Coulomb's cap, Tresca), k enters the heat flux through its P1 projection (the surface has no
volume gradient).

Heat -> mechanics: the form's consistency is K(eps, T)/K_ref of the flow-stress law at the local
temperature (and strain). The form has one rate exponent m_ref (the law's at the entry
temperature); where the law's m(T) differs, the consistency carries the difference at the last
strain rate e*: K_eff = K(eps, T) (3 e*^2)^((m(T) - m_ref)/2), e*^2 = eps0^2 + edot^2, so that
K_eff 3^((m_ref+1)/2) e*^m_ref equals the law's stress at e* exactly; e* is updated with the
temperature, and at the joint fixed point the stress is the law's everywhere.
"""
from __future__ import annotations

import math

import numpy as np

from ..discretisation.rolling_form import TOP
from .field import SolveInfo, TemperatureField
from .properties import ThermalBoundary, ThermalProperties


class ThermalCoupling:
    """The temperature of a rolling strip, its heat sources and its flow-stress feedback."""

    def __init__(self, mesh, props: ThermalProperties, bc: ThermalBoundary, K_ref: float,
                 m_ref: float, eps0: float, flow=None, strain=None, entry_strain: float = 0.0,
                 order: int = 1):
        from ngsolve import H1, GridFunction

        self.field = TemperatureField(mesh, props, bc, order=order)
        self.mesh, self.K_ref, self.m_ref, self.eps0 = mesh, float(K_ref), float(m_ref), eps0
        self.flow, self.strain, self.entry_strain = flow, strain, float(entry_strain)
        self._rate2 = GridFunction(H1(mesh, order=1))   # e*^2 = eps0^2 + edot^2, lagged
        self._rate2.vec[:] = 1.0
        self._k = GridFunction(H1(mesh, order=1))       # k = sigma_ef/sqrt3 (reduced), P1
        self.form = None
        self.last = SolveInfo(0, 0.0)
        # whether the law's rate exponent depends on the temperature (Hensel-Spittel m8)
        self.m_varies = flow is not None and (float(flow.rate_exponent(1000.0))
                                              != float(flow.rate_exponent(1500.0)))

    def consistency(self):
        """K(eps, T)/K_ref at the field's temperature (and the strain field), with the rate
        exponent correction of the module docstring; 1.0 for a temperature-free law."""
        if self.flow is None:
            return 1.0
        from ngsolve import exp, log

        T = self.field.gf
        eps = self.strain.gf if self.strain is not None else self.entry_strain
        ratio = self.flow.consistency(eps, T) / self.K_ref
        if self.m_varies:
            ratio = ratio * exp(0.5 * (self.flow.rate_exponent(T) - self.m_ref)
                                * (math.log(3.0) + log(self._rate2)))
        return ratio

    def attach(self, form) -> None:
        """The form whose flow heats the strip (built with ``consistency()``)."""
        self.form = form

    # --- sources ---------------------------------------------------------------------------
    def _e2(self, u):
        from ..discretisation.forms import strain_rate
        from ..physics.material import edot_squared

        return edot_squared(strain_rate(u))

    def sources(self):
        """(velocity, plastic power density W/m^3, friction power per area W/m^2, contact)."""
        from ngsolve import InnerProduct

        from ..discretisation.forms import strain_rate

        f = self.form
        u = f.problem.velocity
        eps = strain_rate(u)
        mu = f.material.viscosity(self._e2(u), m=f.m, K=f.consistency)
        plastic = self.K_ref * mu * InnerProduct(eps, eps)
        s = f.slip(u)
        law = f.friction
        if law.uses_k:
            self._k.Set(f.shear_flow_stress(u))
        kf = law.coefficient(s * s, a_f=f.a_f, m=f.m,
                             pressure=f.pressure(u) if law.uses_pressure else None,
                             k=self._k if law.uses_k else None)
        return u, plastic, self.K_ref * kf * s * s, f.chi

    # --- updates ---------------------------------------------------------------------------
    def _lag_rate(self) -> None:
        if self.m_varies:
            self._rate2.Set(self._e2(self.form.problem.velocity) + self.eps0**2)

    def update_steady(self, tol: float = 1e-8) -> float:
        """The steady temperature of the current flow (and the lagged rate); returns the
        largest temperature change over the largest temperature."""
        old = self.field.values.copy()
        self.last = self.field.solve_steady(*self.sources(), tol=tol)
        self._lag_rate()
        return float(np.max(np.abs(self.field.values - old))) / float(np.max(np.abs(old)))

    def step(self, dt: float) -> SolveInfo:
        """One implicit step of the material temperature on the current (Lagrangian) mesh."""
        self.last = self.field.step(*self.sources(), dt)
        self._lag_rate()
        return self.last

    # --- figures ---------------------------------------------------------------------------
    def vertex_temperature(self) -> np.ndarray:
        """The temperature at the mesh vertices (K), a copy."""
        return self.field.values[:self.mesh.nv].copy()

    def contact_columns(self) -> dict[str, np.ndarray]:
        """Vertex fields for the contact and top profiles: the temperature (K) and, on the
        contact, the heat flux to the roll htc_contact (T - T_roll) (W/m^2)."""
        T, bc = self.vertex_temperature(), self.field.bc
        return {"temperature": T, "heat_flux_to_roll": bc.htc_contact * (T - bc.roll_temperature)}

    def balance(self) -> dict:
        """Heat flows (W/m) and the balance error of ``TemperatureField.balance``."""
        return self.field.balance(*self.sources())

    def section_means(self, x0: float, band: float) -> tuple[float, float]:
        """(mixing-cup mean int T v_x / int v_x over the strip between x0 and x0 + band, mean
        of T on the top over the same stretch): the exit temperatures at the roll gap section
        x0 = X_roll, band a few elements long."""
        from ngsolve import BND, IfPos, Integrate, x

        u, T = self.form.problem.velocity, self.field.gf
        sel = IfPos(x - x0, IfPos(x0 + band - x, 1.0, 0.0), 0.0)
        flux = float(Integrate(sel * u[0], self.mesh))
        mean = float(Integrate(sel * u[0] * T, self.mesh)) / flux if flux else math.nan
        top = self.mesh.Boundaries(TOP)
        length = float(Integrate(sel, self.mesh, BND, definedon=top))
        surface = (float(Integrate(sel * T, self.mesh, BND, definedon=top)) / length
                   if length else math.nan)
        return mean, surface

    def measure(self, x_exit: float, h: float) -> dict:
        """The thermal figures of one state (K, W/m): exit mean (mixing cup) and surface
        temperatures over 2 h after the roll gap section ``x_exit``, the heat flows and the
        balance error, the extreme temperatures."""
        mean, surface = self.section_means(x_exit, 2.0 * h)
        out = {"exit_temperature_mean": mean, "exit_temperature_surface": surface,
               "max_temperature": float(np.max(self.field.values)),
               "min_temperature": float(np.min(self.field.values)),
               "thermal_iterations": self.last.iterations}
        out.update(self.balance())
        return out


#: Units of the thermal figures in summary.json and history.csv.
THERMAL_UNITS = {
    "exit_temperature_mean": "K", "exit_temperature_surface": "K", "max_temperature": "K",
    "min_temperature": "K", "plastic_heat": "W/m", "friction_heat_to_strip": "W/m",
    "heat_to_roll": "W/m", "heat_to_air": "W/m", "advected_in": "W/m", "advected_out": "W/m",
    "conducted_in": "W/m", "heat_balance_error": "-", "thermal_iterations": "-",
}
