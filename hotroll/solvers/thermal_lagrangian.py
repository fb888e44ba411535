"""The temperature in the report's scheme (issue 16): carried with the material.

In the explicit Lagrangian scheme (3.7) the mesh nodes are material points. The temperature
is a P1 field on that moving plate mesh and keeps its nodal values when the nodes move. Each
time step, after the flow is solved and before the nodes move, one implicit step of
``TemperatureField.step`` advances it:
(H(T) - H(T_old))/dt - div(k grad T) = beta q, with the top's contact and air terms. The
mass is lumped (positive weights: no under- or overshoot at the chilled surface). The flow
stress reads it through the same consistency K(eps, T)/K_ref and rate exponent m(T) as the
steady coupling (``coupling.ThermalCoupling``).

Resolution: the layer the roll chills is resolved only as far as the plate mesh resolves it.
The steady solver puts the temperature on a strip mesh of its own
(docs/studies/thermal_mesh.md); this scheme does not.
"""
from __future__ import annotations

import math

import numpy as np

from hotroll.fem.mesh import mesh_triangles
from hotroll.fem.reproducible import fe_space, integrate
from hotroll.fem.thermal_field import SolveInfo, TemperatureField
from hotroll.model.thermal_properties import ThermalBoundary, ThermalProperties
from hotroll.solvers.thermal_coupling import HEAT_FLOWS
from hotroll.solvers.thermal_feedback import FlowStressFeedback


class LagrangianThermal(FlowStressFeedback):
    """The strip temperature carried with the material of the transient scheme."""

    def __init__(self, mesh, props: ThermalProperties, bc: ThermalBoundary, K_ref: float,
                 m_ref: float, eps0: float, flow=None, strain=None, entry_strain: float = 0.0):
        from ngsolve import H1, GridFunction, LinearForm

        super().__init__(mesh, props, bc, K_ref, m_ref, eps0, flow, strain, entry_strain)
        self.field = TemperatureField(mesh, props, bc, inlet="in", top="top|arc|exit",
                                      outlet="out", lumped_mass=True)
        P1 = fe_space(H1, mesh, order=1)
        self._k = GridFunction(P1)            # k (reduced), P1: the top has no volume gradient
        # each vertex's lumped area (the step's storage weights), assembled on the moved mesh
        self._lump = LinearForm(P1)
        self._lump += P1.TestFunction() * self.field._vertex_rule_dx()
        self._top = self._disp = None
        self.step_balance = dict.fromkeys(("storage", "heat_balance_error"), math.nan)

    @property
    def values(self) -> np.ndarray:
        """The nodal temperatures (K), a live view (checkpoints write and read it)."""
        return self.field.values

    def consistency(self):
        """K(eps, T)/K_ref at the carried temperature (``FlowStressFeedback``)."""
        return self._consistency_at(self.field.gf)

    def rate_offset(self):
        """m(T) - m_ref at the carried temperature, or None (``FlowStressFeedback``)."""
        return self._rate_offset_at(self.field.gf) if self.m_varies else None

    def attach(self, form, disp, top) -> None:
        self.form, self._disp, self._top = form, disp, top

    def sources(self):
        """(velocity, plastic power density W/m^3, friction power per area W/m^2, contact); k
        from a P1 field (the top's boundary integrals have no volume gradient)."""
        f = self.form
        if f.friction.uses_k:
            self._k.Set(f.shear_flow_stress(f.nonlinear.velocity))
        plastic, friction = self._heat_sources(k=self._k)
        return f.nonlinear.velocity, plastic, friction, f.chi

    def step(self, dt: float) -> SolveInfo:
        """One implicit step on the current mesh (before the nodes move), and its energy
        identity: the lumped enthalpy change over dt against the heat flows at the new T
        (equal up to the quadrature of the top terms: vertex rule in the step, Gauss here)."""
        srcs = self.sources()
        old = self.field.values.copy()
        self.last = self.field.step(*srcs, dt)
        self._lump.Assemble()
        dH = self.props.enthalpy_values(self.field.values) - self.props.enthalpy_values(old)
        storage = float(self._lump.vec.FV().NumPy() @ dH) / dt
        flows = self.field.heat_flows(*srcs[1:])
        gain = flows["plastic_heat"] + flows["friction_heat_to_strip"]
        loss = flows["heat_to_roll"] + flows["heat_to_air"]
        self.step_balance = {"storage": storage, "heat_balance_error":
                             abs(storage - (gain - loss)) / max(gain, abs(loss), 1e-300)}
        return self.last

    # --- outputs (as ``coupling.ThermalCoupling``'s) -----------------------------------------
    @property
    def T(self):
        return self.field.gf

    def vertex_temperature(self) -> np.ndarray:
        return self.field.values[:self.mesh.nv].copy()

    def flow_temperature(self) -> np.ndarray:
        """The temperature the flow stress takes: the nodal one here."""
        return self.vertex_temperature()

    def strip_fields(self) -> dict[str, np.ndarray]:
        """The plate as drawn: current vertex positions (m), triangles and T (K)."""
        top, d, nv = self._top, self._disp.vec.FV().NumPy(), self.mesh.nv
        pts = top.X0 + np.stack([d[:nv], d[top.n_scalar:top.n_scalar + nv]], -1)
        return {"points": pts, "triangles": mesh_triangles(self.mesh),
                "temperature": self.vertex_temperature()}

    def measure(self, x_exit: float, h: float) -> dict:
        """The thermal figures of the current state (K, W/m): the mixing-cup mean over the plate
        between the roll gap and 2 h after it (NaN until the head is past), the top's
        temperature at the gap, the heat flows of the current flow and temperature, and the
        last step's energy identity; the advected and conducted flows of the steady balance
        do not apply (NaN)."""
        from ngsolve import IfPos, x

        u, T, mesh = self.form.nonlinear.velocity, self.field.gf, self.mesh
        sel = IfPos(x - x_exit, IfPos(x_exit + 2.0 * h - x, 1.0, 0.0), 0.0)
        flux = integrate(sel * u[0], mesh)
        mean = integrate(sel * u[0] * T, mesh) / flux if flux > 0 else math.nan
        top, d = self._top, self._disp.vec.FV().NumPy()
        xy = top.vertex_positions(d)
        near = np.argmin(np.abs(xy[:, 0] - x_exit) + np.where(xy[:, 0] < x_exit - h, 1e9, 0.0))
        surface = (float(self.field.values[top.verts[near]])
                   if abs(xy[near, 0] - x_exit) < h else math.nan)
        vals = self.field.values
        out = {"exit_temperature_mean": mean, "exit_temperature_surface": surface,
               "max_temperature": float(np.max(vals)), "min_temperature": float(np.min(vals)),
               "thermal_iterations": self.last.iterations, "thermal_dofs": int(len(vals)),
               "thermal_layer": math.nan}
        out.update(dict.fromkeys(HEAT_FLOWS, math.nan))
        out.update(self.field.heat_flows(*self.sources()[1:]))
        out["heat_balance_error"] = self.step_balance["heat_balance_error"]
        return out
