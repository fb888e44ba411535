"""Temperature field of the strip (issue 16; beyond the report: Touloupoulos 2020 has no
temperature). The coupling to the mechanics is not here: the velocity, the plastic power density
and the friction power are given as CoefficientFunctions (SI: m/s, W/m^3, W/m^2; mesh in m).

Equations (T in K, H(T) = int rho c dT the enthalpy per volume, beta the Taylor-Quinney factor):

- steady strip (``solve_steady``, Eulerian, current strip mesh):
  ``rho c v.grad T - div(k grad T) = beta q``, T = T_entry on the inlet face;
- report's scheme (``step``, Lagrangian: the mesh moves with the material, 3.7), implicit Euler
  in enthalpy form ``(H(T) - H(T_old)) / dt - div(k grad T) = beta q`` (= rho c (T - T_old)/dt
  for a constant rho c; exact energy bookkeeping otherwise), no advection, inlet face insulated.

Heat flux into the strip on the top (``top``), ``chi`` the contact indicator (1 in contact):
``chi (f_s q_f - h_c (T - T_roll)) + (1 - chi) (-h_a (T - T_amb) - eps sigma (T^4 - T_amb^4))``,
q_f the friction power per area, f_s its share entering the strip. ``sym`` and ``out`` have no
diffusive flux (natural condition).

Discretisation: H1 (P1 by default). The steady solve is SUPG-stabilised (Brooks-Hughes):
test function w + tau v.grad w on every term of the strong residual (the diffusion part only from
P2 up: for P1 it vanishes in the elements), tau = h_v / (2 |v|) (coth Pe - 1/Pe),
Pe = |v| h_v rho c / (2 k), h_v = 2 |v| / sum_i |v.grad N_i| the element length along the flow
(Tezduyar; exact for P1 triangles: long thin elements get their streamline length), rho c and k
of the previous iterate, one value per element. Measured (tests/fem/test_thermal.py): it removes
the node-to-node zigzag of the plain Galerkin method (``supg=0``) before a cold roll; it adds
O(h) streamline diffusion where U dT/dx ~ alpha d2T/dy2 (Graetz series at U H / alpha = 2000:
max error 1.3e-3 of T0 - T_roll on rows of H/32 near the top, 2.4x the Galerkin error; rate 1.8
over rows of H/8..H/32). Known limit: neither method keeps the maximum principle across a cooled
layer thinner than the elements (sqrt(alpha l / U) under a roll of contact length l): the row of
nodes under a cold roll overshoots T_entry by 37, 27, 14, 7 K for rows of H/4..H/32 at
U H / alpha = 2000, h_c H / k = 6.7 (the mixing-cup temperature is right to 1.7-0.05 K); resolve
that layer near the top. ``step`` has the same issue with the consistent mass (a sudden contact:
9 K with rows of H/32); ``lumped_mass=True`` (vertex quadrature, an M-matrix on non-obtuse
meshes) keeps T within its bounds at some cost in accuracy (7.1 K against 5.2 K error there).

The SUPG parameter is the L2 projection of its CF onto P0; a caller whose velocity is constant
on each triangle and whose properties are constant may give it instead (``element_tau``:
``p1_supg_tau``, the same formula in numpy, 1e-15 apart and ~10x cheaper; the coupling's strip),
and with it the steady load of a P1 source (``element_load``: ``p1_supg_load``, exact as the
order-2 rule is; 1e-15 of the assembled vector apart, ~8x cheaper).

Nonlinearity (radiation, T-dependent rho c and k): Newton's method with the exact Jacobian of
NGSolve's symbolic linearisation (tau frozen per iteration; 5 iterations to 1e-12 with tables and
radiation), direct solves (UMFPACK).
"""
from __future__ import annotations

import math
import re
from functools import cached_property
from typing import NamedTuple

import numpy as np

from hotroll.fem.heat_p1 import SteadyP1Operator
from hotroll.fem.nonlinear import newton
from hotroll.fem.reproducible import fe_space, integrate, parallel
from hotroll.model.thermal_properties import ThermalBoundary, ThermalProperties


class SolveInfo(NamedTuple):
    iterations: int   # Newton iterations done
    change: float     # last max |dT| / max |T|


class TemperatureField:
    """Temperature (K) on H1 of ``mesh``, with the steady and the moving-mesh heat equation."""

    def __init__(self, mesh, props: ThermalProperties, bc: ThermalBoundary, order: int = 1,
                 inlet: str = "in", top: str = "top|arc|exit", outlet: str = "out",
                 supg: float = 1.0, lumped_mass: bool = False, volume_bonus: int = 2):
        from ngsolve import H1, L2, BitArray, GridFunction

        self.mesh, self.props, self.bc, self.order = mesh, props, bc, int(order)
        self.inlet, self.top, self.outlet = inlet, top, outlet
        self.supg = float(supg)   # scale of tau: 0 gives the plain Galerkin method (comparisons)
        if lumped_mass and self.order != 1:
            raise ValueError(f"lumped_mass needs order 1, got order {self.order}")
        self.lumped = bool(lumped_mass)   # step(): vertex quadrature of the T terms
        self.space = fe_space(H1, mesh, order=self.order, dirichlet=inlet)
        self.gf = GridFunction(self.space)
        self.gf.Set(bc.entry_temperature)
        self._frozen = GridFunction(self.space)   # previous iterate (SUPG tau)
        self._old = GridFunction(self.space)      # previous time level (step)
        self._all = BitArray(self.space.ndof)     # step(): no Dirichlet face
        self._all.Set()
        self._tau_gf = GridFunction(fe_space(L2, mesh, order=0))   # SUPG tau, one value per element
        self._tau_cf = None
        #: None, or a callable giving tau per element (numpy, element order) in place of the
        #: projection of the tau CF: only for a velocity constant on each element and constant
        #: properties (the coupling's strip: ``p1_supg_tau``)
        self.element_tau = None
        #: None, or a callable (tau per element) -> int q (w + tau v.grad w) dx for each DOF's
        #: w (numpy): the steady load's volume part in place of its assembly (then beta times
        #: it). Only with ``element_tau``'s conditions and a P1 source on this mesh; set
        #: before the first steady solve (the forms are built without that term then)
        self.element_load = None
        #: None, or (the velocity CF it describes, a callable giving (triangles, barycentric
        #: gradients, Jacobian determinants, velocity per triangle)): with ``element_tau``'s
        #: conditions the steady residual's and Jacobian's volume terms are then numpy's
        #: (``fem/heat_p1.SteadyP1Operator``; 1e-13 of NGSolve's, ~5x cheaper) for a solve
        #: with that very velocity object; with any other, NGSolve's (from the review)
        self.element_flow = None
        self._load_hook = None       # (the steady f built without its volume source, the hook)
        self._steady = None          # (inputs, forms, tau) of the last steady solve: reused
        self._system = None          # the HeatSystem of the last solve (its kept factors)
        self._f_assembled = None     # the load form assembled by the last solve (balance)
        # quadrature: T^4 w on the top and the piecewise (IfPos) properties in the volume;
        # ``volume_bonus = 0`` where the volume terms are polynomials the default rule
        # integrates exactly (P1, constant properties, P1 sources: the strip mesh; 1.8x faster)
        self._bonus_dx, self._bonus_ds = int(volume_bonus), 3

    @property
    def values(self) -> np.ndarray:
        """The coefficient vector (the nodal temperatures for P1), a live numpy view."""
        return self.gf.vec.FV().NumPy()

    # --- forms ---------------------------------------------------------------------------------
    def _h_flow(self, velocity):
        """Element length along v: 2 |v| / sum |v.grad N_i| (P1 triangle: b = J^-1 v gives
        v.grad N_i = b1, b2, -(b1 + b2))."""
        from ngsolve import IfPos, Inv, specialcf, sqrt

        b = Inv(specialcf.JacobianMatrix(2)) * velocity
        speed = sqrt(velocity * velocity + 1e-300)
        total = sum(IfPos(c, c, -c) for c in (b[0], b[1], b[0] + b[1]))  # no sqrt(0) in AD
        safe = IfPos(total - 1e-300, total, 1.0)
        return IfPos(total - 1e-300, 2.0 * speed / safe, specialcf.mesh_size)   # v = 0: size

    def _tau(self, velocity):
        """SUPG parameter h_v / (2 |v|) (coth Pe - 1/Pe) (s: it multiplies the residual of the
        equation in W/m^3), properties of ``_frozen``."""
        from ngsolve import IfPos, exp, sqrt

        speed = sqrt(velocity * velocity + 1e-300)
        h = self._h_flow(velocity)
        rc, k = self.props.rho_c(self._frozen), self.props.k(self._frozen)
        pe = speed * h * rc / (2.0 * k)
        big = IfPos(pe - 1e-2, pe, 1e-2)          # no overflow in the unused branch
        e = exp(-2.0 * big)
        xi = IfPos(pe - 1e-2, (1.0 + e) / (1.0 - e) - 1.0 / big, pe / 3.0 - pe ** 3 / 45.0)
        return self.supg * h / (2.0 * speed) * xi

    @staticmethod
    def _vertex_rule_dx():
        """Quadrature at the vertices of the triangles: the lumped mass for P1."""
        from ngsolve import TRIG, IntegrationRule, dx

        return dx(intrules={TRIG: IntegrationRule([(1, 0), (0, 1), (0, 0)], [1 / 6] * 3)})

    def _top_terms(self, u, w, a, f, friction_flux, contact, lumped=False):
        """-(heat flux into the strip) w on the top: the T part in ``a``, the rest in ``f``."""
        from ngsolve import CF, SEGM, IntegrationRule, ds

        bc, chi = self.bc, CF(contact)
        if lumped:   # vertex quadrature on the edges too
            dtop = ds(self.top, intrules={SEGM: IntegrationRule([(0,), (1,)], [0.5, 0.5])})
        else:
            dtop = ds(self.top, bonus_intorder=self._bonus_ds)
        # the laws' heat flux out of the strip (model/heat_transfer), in the residual
        a += (chi * bc.contact.flux(u, bc.roll_temperature)
              + (1.0 - chi) * bc.surface.flux(u, bc.ambient_temperature)) * w * dtop
        # the friction heat by Gauss (it peaks at the contact's ends)
        f += (chi * bc.friction_heat_to_strip * CF(friction_flux)) * w * ds(
            self.top, bonus_intorder=self._bonus_ds)

    def _forms(self, velocity, heat_density, friction_flux, contact, dt=None):
        """Residual a(T; w) - f(w) of the steady (dt None) or the implicit-Euler equation."""
        from ngsolve import CF, BilinearForm, LinearForm, Trace, ds, dx, grad, specialcf

        p, bc = self.props, self.bc
        u, w = self.space.TnT()
        a, f = BilinearForm(self.space), LinearForm(self.space)
        self._tau_cf = None
        dvol = dx(bonus_intorder=self._bonus_dx)
        k = p.k(u)
        vol = k * grad(u) * grad(w)
        if dt is None:
            v = CF(velocity)
            self._tau_cf = self._tau(v).Compile()   # ~10x faster to evaluate
            supg = self._tau_gf * (v * grad(w))
            # advection in conservative form, -int H v.grad w + int_out H v.n w: no heat is
            # carried through the top and the symmetry line even where the discrete velocity
            # crosses them (the penalty contact lets v.n ~ 1e-3 U through the arc), so energy
            # is conserved exactly (w = 1); the SUPG part takes the strong residual
            H = p.enthalpy(u, bc.entry_temperature)
            vol = vol - H * (v * grad(w)) + p.rho_c(u) * (v * grad(u)) * supg
            a += H * (v * specialcf.normal(2)) * w * ds(self.outlet, bonus_intorder=self._bonus_ds)
            if self.order > 1:
                vol = vol - k * Trace(u.Operator("hesse")) * supg
            numpy_volume = (self.element_flow is not None and self.order == 1
                            and p.is_constant() and velocity is self.element_flow[0])
            if not numpy_volume:
                a += vol.Compile() * dvol          # one compiled integrand: ~2x faster
            if self.element_load is None:
                f += (bc.taylor_quinney * CF(heat_density) * (w + supg)).Compile() * dvol
            # with element_load set, the plastic heat's load is that hook's (its own source,
            # the coupling's P1 field), not ``heat_density``'s: the coupling passes the same
            self._load_hook = (f, self.element_load) if self.element_load is not None else None
        else:
            ref = bc.entry_temperature
            dm = self._vertex_rule_dx() if self.lumped else dvol
            a += vol * dvol
            a += p.enthalpy(u, ref) / dt * w * dm
            f += p.enthalpy(self._old, ref) / dt * w * dm
            # the source by Gauss even when the mass is lumped: the plastic power density
            # varies within an element (a vertex rule put 10 % of it in the wrong place)
            f += bc.taylor_quinney * CF(heat_density) * w * dvol
        self._top_terms(u, w, a, f, friction_flux, contact, lumped=dt is not None and self.lumped)
        if dt is None and numpy_volume:
            # the volume terms in numpy (fem/heat_p1.py): the form keeps the boundary terms
            pattern = BilinearForm(self.space)
            pattern += u * w * dx
            T0 = bc.entry_temperature
            a = SteadyP1Operator(a, pattern, self.element_flow[1],
                                 lambda: self._tau_gf.vec.FV().NumPy(),
                                 float(p.k_values(T0)), float(p.rho_c_values(T0)), T0)
        return a, f

    def _refresh(self, tau: bool = True) -> None:
        """Freeze the current iterate for tau; tau's element means (steady forms only)."""
        self._frozen.vec.data = self.gf.vec
        if self._tau_cf is not None and tau:
            if self.element_tau is not None:
                self._tau_gf.vec.FV().NumPy()[:] = self.element_tau()
            else:
                self._tau_gf.Set(self._tau_cf)

    def _assemble_load(self, f) -> None:
        """Assemble the load f; the steady form built without its volume source gets it from
        ``element_load`` (at the current tau)."""
        with parallel():
            f.Assemble()
        hook = self._load_hook
        if hook is not None and hook[0] is f:
            f.vec.FV().NumPy()[:] += self.bc.taylor_quinney * hook[1](
                self._tau_gf.vec.FV().NumPy())

    def _newton(self, a, f, free, tol, max_iter, chord: bool = False) -> SolveInfo:
        """The one Newton (``fem/nonlinear.py``) on a(T; w) = f(w) from the current T, full
        steps; ``chord``: the Jacobian's factors of the last solve of the same form instead of
        new ones (Newton-chord)."""
        system = self._system
        if system is None or system.a is not a or system.freedofs is not free:
            system = self._system = HeatSystem(self, a, f, free)
        stats = newton(system, tol, max_iter, min_step=1.0, chord=chord, last_residual=False)
        return SolveInfo(stats.iterations, stats.update)

    # --- solves --------------------------------------------------------------------------------
    def solve_steady(self, velocity, heat_density, friction_flux, contact, tol: float = 1e-8,
                     max_iter: int = 30, chord: bool = False) -> SolveInfo:
        """Steady rho c v.grad T - div(k grad T) = beta q on the current strip, T = T_entry on
        the inlet (SUPG, Newton from the current field). Returns (iterations, last max |dT| /
        max |T|); not converged if the change is still above ``tol``."""
        self.values[self._fixed] = self._inlet_values
        a, f = self._steady_forms(velocity, heat_density, friction_flux, contact)
        self._f_assembled = None
        return self._newton(a, f, self._free, tol, max_iter, chord=chord)

    @cached_property
    def _free(self):
        return self.space.FreeDofs()

    @cached_property
    def _fixed(self) -> np.ndarray:
        """The inlet's (Dirichlet) DOFs, a boolean mask."""
        return ~np.array(list(self._free), dtype=bool)

    @cached_property
    def _inlet_values(self) -> np.ndarray:
        """T = T_entry at the inlet's DOFs, or the entry profile T(eta) at eta = y / (the
        inlet's highest y) in the undeformed mesh (P1: the DOFs are the vertices)."""
        from ngsolve import BND, GridFunction

        profile = self.bc.entry_profile
        if profile is not None:
            if self.order != 1:
                raise ValueError("an entry temperature profile needs the P1 temperature")
            y = np.asarray(self.mesh.ngmesh.Coordinates())[: self.mesh.nv, 1]
            # |y|: the full strip's inlet spans both halves (the profile mirrored about y = 0)
            y_in = np.abs(y[self._fixed[: self.mesh.nv]])
            return np.asarray(profile(y_in / np.max(y_in)), dtype=float)
        inlet = GridFunction(self.space)
        inlet.Set(self.bc.entry_temperature, BND, definedon=self.mesh.Boundaries(self.inlet))
        return inlet.vec.FV().NumPy()[self._fixed].copy()

    def _steady_forms(self, velocity, heat_density, friction_flux, contact):
        """The steady forms of these inputs, built once while the same objects come back
        (GridFunctions and Parameters whose values change between solves)."""
        inputs = (velocity, heat_density, friction_flux, contact)
        if self._steady is None or any(a is not b for a, b in zip(inputs, self._steady[0])):
            forms = self._forms(*inputs)
            self._steady = (inputs, forms, self._tau_cf)
        self._tau_cf = self._steady[2]          # (step() clears it)
        return self._steady[1]

    def _residual_sum(self, a, f, rows: np.ndarray, sources_unchanged: bool = False) -> float:
        """Sum of the assembled residual a(T; w_i) - f(w_i) over ``rows`` at the current T.
        ``sources_unchanged``: the caller has not changed the sources since the last solve;
        with constant properties f (sources and tau, not T) is then the one that solve
        assembled, and is not assembled again."""
        constant = self.props.is_constant()
        self._refresh(tau=not constant)
        if not (sources_unchanged and constant and self._f_assembled is f):
            self._assemble_load(f)
        res = self.gf.vec.CreateVector()
        with parallel():
            a.Apply(self.gf.vec, res)
        res.data -= f.vec
        return float(np.sum(res.FV().NumPy()[rows]))

    def step(self, velocity, heat_density, friction_flux, contact, dt: float,
             tol: float = 1e-10, max_iter: int = 30) -> SolveInfo:
        """One implicit-Euler step (H(T) - H(T_old))/dt - div(k grad T) = beta q on the mesh as
        it is now (the caller has moved it: the nodes are material points and keep their
        values), same top fluxes, no advection, inlet insulated. ``velocity`` is not used
        (the motion is in the mesh); it is kept so that both modes take the same arguments."""
        if not dt > 0.0:
            raise ValueError(f"dt = {dt!r}: must be > 0 (s)")
        self._old.vec.data = self.gf.vec
        self._f_assembled = None
        a, f = self._forms(velocity, heat_density, friction_flux, contact, dt=float(dt))
        return self._newton(a, f, self._all, tol, max_iter)

    # --- figures -------------------------------------------------------------------------------
    def _integrate(self, cf, region=None) -> float:
        from ngsolve import BND, VOL

        if region is None:
            return integrate(cf, self.mesh, VOL, order=2 * self.order + self._bonus_dx)
        return integrate(cf, self.mesh, BND, order=2 * self.order + self._bonus_ds,
                         definedon=self.mesh.Boundaries(region))

    def balance(self, velocity, heat_density, friction_flux, contact,
                sources_unchanged: bool = False) -> dict:
        """Heat flows in W/m (per unit width, over the mesh as given) and the relative error
        |out - in - (plastic + friction - roll - air)| / max(plastic + friction, |roll| + |air|).

        The enthalpy fluxes use H(T) - H(T_entry) (a constant reference cancels when the mass
        flux in equals the flux out; this one keeps a discrete mass-flux error from weighing
        with rho c T_entry). Closure of the steady discrete solution: testing its equations with
        w = 1 (the SUPG part vanishes) gives int rho c v.grad T = sources - losses + R_in, R_in
        the reaction of the Dirichlet inlet, reported as ``conducted_in`` (the heat the discrete
        solution conducts in through the inlet face), and int rho c v.grad T = int v.grad H =
        out - in for v divergence-free and tangent to the top and sym. So the error is
        |R_in| / scale (measured 1e-9 to 1e-4 in the tests: largest when the top is cooled or
        heated right from the inlet corner) plus the discrete div v and v.n of the velocity
        given and the Newton tolerance; with ``conducted_in`` added the tests close to 1e-12.
        ``advected_in`` is 0 after ``solve_steady`` (T = T_entry on the inlet). These are the
        steady equations: the storage term of ``step`` is not in them. ``sources_unchanged``:
        the sources (their values too) are those of the last ``solve_steady``, whose load
        vector is then reused (``_residual_sum``)."""
        from ngsolve import CF, specialcf

        p, bc, T = self.props, self.bc, self.gf
        vel, n = CF(velocity), specialcf.normal(2)
        H = p.enthalpy(T, bc.entry_temperature)
        out = self.heat_flows(heat_density, friction_flux, contact)
        out.update(
            advected_in=-self._integrate(H * (vel * n), self.inlet),
            advected_out=self._integrate(H * (vel * n), self.outlet),
            conducted_in=self._inlet_reaction(velocity, heat_density, friction_flux, contact,
                                              sources_unchanged))
        gain = out["plastic_heat"] + out["friction_heat_to_strip"]
        net = gain - out["heat_to_roll"] - out["heat_to_air"]
        scale = max(gain, abs(out["heat_to_roll"]) + abs(out["heat_to_air"]), 1e-300)
        out["heat_balance_error"] = abs(out["advected_out"] - out["advected_in"] - net) / scale
        return out

    def heat_flows(self, heat_density, friction_flux, contact) -> dict:
        """The sources and losses at the current T (W/m): plastic heat (beta q), the strip's
        share of the friction heat, heat to the roll through the contact, to the air
        (convection and radiation) through the free top."""
        from ngsolve import CF

        bc, T, chi = self.bc, self.gf, CF(contact)
        return dict(
            plastic_heat=bc.taylor_quinney * self._integrate(CF(heat_density)),
            friction_heat_to_strip=bc.friction_heat_to_strip
            * self._integrate(chi * CF(friction_flux), self.top),
            heat_to_roll=self._integrate(chi * bc.contact.flux(T, bc.roll_temperature), self.top),
            heat_to_air=self._integrate((1.0 - chi) * bc.surface.flux(T, bc.ambient_temperature),
                                        self.top))

    def _inlet_reaction(self, velocity, heat_density, friction_flux, contact,
                        sources_unchanged: bool = False) -> float:
        """Sum of the steady residual over the inlet (Dirichlet) dofs, W/m: the heat the
        discrete solution conducts in through the inlet face."""
        a, f = self._steady_forms(velocity, heat_density, friction_flux, contact)
        return self._residual_sum(a, f, self._fixed, sources_unchanged)

    def face_mean(self, face: str, velocity) -> float:
        """Mixing-cup (flux-weighted) mean temperature int T v.n / int v.n over ``face`` (the
        energy mean for a constant rho c)."""
        from ngsolve import CF, specialcf

        vn = CF(velocity) * specialcf.normal(2)
        return self._integrate(self.gf * vn, face) / self._integrate(vn, face)

    def surface_value(self, face: str) -> float:
        """T at the top end (largest current y) of ``face``."""
        from ngsolve import BND, H1, VERTEX, GridFunction, NodeId, y

        pattern = re.compile(f"^({face})$")
        verts = sorted({v.nr for el in self.mesh.Elements(BND) if pattern.match(el.mat)
                        for v in el.vertices})
        if not verts:
            raise ValueError(f"no boundary named {face!r} in the mesh")
        ycoord = GridFunction(fe_space(H1, self.mesh, order=1))   # vertex v is dof v
        ycoord.Set(y, dual=True)                  # nodal values: the current (deformed) y
        best = max(verts, key=lambda v: ycoord.vec[v])
        return float(self.values[self.space.GetDofNrs(NodeId(VERTEX, best))[0]])


class HeatSystem:
    """The heat equation's residual a(T; w) - f(w) as a system of the one Newton
    (``fem/nonlinear.py: NonlinearSystem``): an update is measured by max |dT| / max |T|; the
    SUPG parameter (and f, with it) is frozen at the iterate in ``prepare`` (every iteration
    for temperature-dependent properties, the first only for constant ones); UMFPACK, as SUPG
    makes the matrix non-symmetric; its factors are kept while the same form comes back."""

    a_jacobian = None
    pressure_row_scale = 1.0
    multiplier_tol = math.inf
    linear_solvers = ("umfpack",)
    linear_rtol = 1e-6               # UMFPACK: the accuracy test only

    def __init__(self, field: TemperatureField, a, f, free):
        self.field, self.a, self.f, self.freedofs = field, a, f, free
        self.gf = field.gf
        self.a_newton = self           # the residual form: Apply, AssembleLinearization, mat
        self.inverses: dict = {}
        self.free_mask = np.array(list(free), dtype=bool)

    def prepare(self, iteration: int) -> bool:
        fresh = iteration == 1 or not self.field.props.is_constant()
        self.field._refresh(tau=fresh)
        if fresh:
            self.field._assemble_load(self.f)
            self.field._f_assembled = self.f
        return fresh

    def Apply(self, vec, out) -> None:            # noqa: N802 - NGSolve's form interface
        self.a.Apply(vec, out)
        out.data -= self.f.vec

    def AssembleLinearization(self, vec) -> None:  # noqa: N802
        self.a.AssembleLinearization(vec)

    @property
    def mat(self):
        return self.a.mat

    @property
    def velocity_scale(self) -> float:
        return max(float(np.max(np.abs(self.field.values))), 1e-300)

    def max_nodal_velocity(self, vec) -> float:
        return float(np.max(np.abs(vec.FV().NumPy())))

    def max_multiplier(self, vec) -> float:
        return 0.0
