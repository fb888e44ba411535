"""Thermo-mechanical coupling of a steady rolling form and its temperature field (issue 16;
beyond the report: Touloupoulos 2020 is isothermal).

The temperature lives on its own mesh (``strip_mesh.ThermalStrip``: structured, thin rows at
the top for the roll-chill layer), the mechanics on theirs. Each coupling update:
1. places the strip mesh on the current strip (the mechanics' displacement at its reference
   points);
2. carries the flow over as a stream function: psi = the flux below each strip vertex along
   its column, rescaled per column to the inlet's flux, and v = curl psi. That velocity is
   divergence-free, tangent to the top and the symmetry line, and carries the same flux
   through every section, so the advected heat balances exactly (the mechanics' discrete
   velocity has a mass-flux error of ~1e-3, which times rho c T would be a heat source the
   size of the plastic heat);
3. evaluates the plastic power density and the friction flux of the mechanics' fields as
   means over each strip vertex's dual cell and its surface's dual segment in contact
   (Gauss points found once in the reference mesh, evaluated on the deformed one:
   solvers/thermal_sampling.py), and takes the contact as the x-range of the contact edges;
4. solves the steady temperature there and carries it back: as each mechanics element's mean
   (the strip's vertices inside it, weighted by their lumped areas), which the flow stress
   reads, and as the values at the mechanics' vertices (the profiles, fields.npz). A vertex
   value would spread the chilled surface over the whole element (the layer is a fraction
   of it): measured +4.4 % on the force against -0.7 % with the element means.

Mechanics -> heat: the plastic power density s:eps_dot = K_ref mu eps_dot:eps_dot (W/m^3, the
form's law, reduced stresses times K_ref) and the friction power per area K_ref k_f |v_s|^2
(W/m^2) on the contact feed ``TemperatureField`` (``field.py``); for the laws with
k = sigma/sqrt3 (Coulomb's cap, Tresca), k is the volume gradient's at the strip's points.

Heat -> mechanics: the form's consistency K(eps, T)/K_ref and rate exponent m(T) at the elements'
temperatures (``feedback.FlowStressFeedback``).
"""
from __future__ import annotations

import math

import numpy as np

from hotroll.fem.heat_p1 import p1_supg_load, p1_supg_tau
from hotroll.fem.mesh import mesh_triangles
from hotroll.fem.point_search import mesh_points
from hotroll.fem.reproducible import fe_space, find_points, integrate
from hotroll.fem.spaces import P2PointValues
from hotroll.fem.strip_mesh import ThermalStrip, layer_thickness
from hotroll.fem.thermal_field import TemperatureField
from hotroll.model.thermal_properties import ThermalBoundary, ThermalProperties
from hotroll.solvers.thermal_feedback import FlowStressFeedback
from hotroll.solvers.thermal_sampling import cell_means, contact_means, k_means, strip_samples

SUBSAMPLES = 4   # points per strip row interval for the flux integral along a column
CHORD_BELOW = 1e-3   # update_steady keeps the heat equation's factors below this change


class ThermalCoupling(FlowStressFeedback):
    """The temperature of a steady rolling strip, its heat sources and its flow-stress
    feedback (module docstring)."""

    def __init__(self, mesh, props: ThermalProperties, bc: ThermalBoundary, K_ref: float,
                 m_ref: float, eps0: float, flow=None, strain=None, entry_strain: float = 0.0,
                 refine: float = 1.0):
        from ngsolve import H1, L2, GridFunction

        super().__init__(mesh, props, bc, K_ref, m_ref, eps0, flow, strain, entry_strain)
        self.refine = float(refine)
        self.T = GridFunction(fe_space(H1, mesh, order=1))   # the temperature at the mechanics' vertices
        self.T.Set(bc.entry_temperature)
        self.T_mean = GridFunction(fe_space(L2, mesh, order=0))   # each element's mean temperature, K
        self.T_mean.Set(bc.entry_temperature)
        self._ratio = GridFunction(fe_space(L2, mesh, order=0))   # K/K_ref per element (see consistency)
        self._offset = GridFunction(fe_space(L2, mesh, order=0))  # m(T) - m_ref per element
        self.strip = self.field = None
        self._change = math.inf      # the last update's change (update_steady)
        # no strain field: the ratio is a number per element, kept in a P0 field (the form
        # then reads values, not the law's formula: half the residual's cost)
        self._per_element = flow is not None and strain is None
        self._set_ratio()

    def _set_ratio(self) -> None:
        """The P0 fields of the elements' temperatures: K/K_ref (without a strain field) and
        the rate-exponent offset."""
        T = self.T_mean.vec.FV().NumPy()
        if self._per_element:
            self._ratio.vec.FV().NumPy()[:] = np.asarray(self._consistency_at(T), dtype=float)
        if self.m_varies:
            self._offset.vec.FV().NumPy()[:] = np.asarray(self._rate_offset_at(T), dtype=float)

    def consistency(self):
        """K(eps, T)/K_ref at the elements' mean temperature (``FlowStressFeedback``)."""
        return self._ratio if self._per_element else self._consistency_at(self.T_mean)

    def rate_offset(self):
        """m(T) - m_ref at the elements' mean temperature, or None (``FlowStressFeedback``)."""
        return self._offset if self.m_varies else None

    def attach(self, form, disp, top, lower=None, rp=None, breaks=(), rolls=()) -> None:
        """The form whose flow heats the strip (built with ``consistency()``), the mechanics'
        displacement GridFunction and its ``TopBoundary``: builds the strip mesh. The full
        strip between two rolls (issue 52): ``lower`` its lower surface's ``TopBoundary``
        (the strip mesh then spans the whole thickness, each surface in contact with its
        own roll), ``rp`` the roll its reference mesh was built for (default ``form.rp``),
        ``breaks`` more x (m) for the fine columns (the other roll's contact start), ``rolls``
        the rolls whose chill layers the rows resolve (the thinnest: a faster roll's
        shorter contact chills a thinner layer)."""
        from ngsolve import H1, GridFunction, IfPos, Parameter, x, y

        self.form, self._disp = form, disp
        rp = form.rp if rp is None else rp
        full = lower is not None
        T0 = self.bc.entry_temperature
        alpha = float(self.props.k_values(T0) / self.props.rho_c_values(T0))
        self.delta = min(layer_thickness(r, alpha) for r in (rp, *rolls))
        self.strip = ThermalStrip(rp, top.X0[top.verts], form.penalties.h, self.delta,
                                  self.refine, full=full, breaks=breaks)
        # P1 temperature, P1 sources and a velocity constant per triangle: with constant
        # properties every volume term is a polynomial of degree <= 2 (no bonus order needed)
        self.field = TemperatureField(self.strip.mesh, self.props, self.bc,
                                      inlet="left", top="top|bottom" if full else "top",
                                      outlet="right",
                                      volume_bonus=0 if self.props.is_constant() else 2)
        self._flow = None            # the strip's element_flow at the current placement
        if self.props.is_constant():
            # the velocity curl psi is constant on each triangle: the SUPG parameter and the
            # plastic heat's load in numpy (the same formulas, 1e-15 apart; 1 ms against 10 ms
            # for the CF's projection and 9 ms for the load's assembly)
            self.field.element_tau = self._element_tau
            self.field.element_load = self._element_load
            # ... and the residual's and Jacobian's volume terms (fem/heat_p1.py)
            self.field.element_flow = (self.strip.velocity(),
                                       lambda: (self._strip_tris, *self._element_flow()))
        self._qs = GridFunction(fe_space(H1, self.strip.mesh, order=1))
        self._qfs = GridFunction(fe_space(H1, self.strip.mesh, order=1))
        # each surface's TopBoundary and its contact's x-range (Parameters), upper first; the
        # contact indicator: the upper's range above the mid-plane, the lower's below it
        self._surfaces = [(t, Parameter(0.0), Parameter(0.0))
                          for t in ((top, lower) if full else (top,))]
        chis = [IfPos(x - lo, IfPos(hi - x, 1.0, 0.0), 0.0) for _, lo, hi in self._surfaces]
        self._chi = IfPos(y, chis[0], chis[1]) if full else chis[0]
        self._mech_logical = self.strip.logical(top.X0)   # the mechanics' vertices
        # the strip's vertices and its columns' flux points, found once in the mechanics'
        # reference mesh; the top row's vertices. Every SUBSAMPLES-th row of flux points is
        # a row of strip vertices (the same reference coordinates, bit for bit): one search
        # finds both, and one evaluation gives the vertices' positions and the columns' flux
        strip = self.strip
        self._fine, col_ref = self._column_points()
        self._col_pts = self._find(col_ref)
        # their positions and velocities from the P2 fields' nodal values (spaces.P2PointValues:
        # 0.5 ms an update where NGSolve's evaluation at the 16k points took 5.5)
        self._col_ref = col_ref
        mech_tris = mesh_triangles(self.mesh)
        self._col_p2 = P2PointValues(form.nonlinear.p2_nodes, mech_tris,
                                     self._col_pts["nr"],
                                     np.stack([self._col_pts["x"], self._col_pts["y"]], -1))
        self._top_row = np.arange(strip.nv - strip.shape[1], strip.nv)
        # the rows on a roll's surface (the friction heat's): the top, and the bottom in full
        self._surface_rows = (np.concatenate([np.arange(strip.shape[1]), self._top_row])
                              if full else self._top_row)
        # the mechanics element of each strip vertex (the elements with none take the
        # temperature at their centroid), and where the fields that jump between elements
        # are sampled from both sides (solvers/thermal_sampling.py)
        samples = strip_samples(strip, self._find, self.mesh.ne)
        self._owner, self._empty = samples.owner, samples.empty
        self._mid, self._cells, self._surface_cells = samples.mid, samples.cells, samples.surface
        centroids = top.X0[mech_tris[self._empty]].mean(axis=1)
        self._empty_logical = self.strip.logical(centroids)
        # where those are in the strip mesh: searched once (its logical coordinates do not
        # move; NGSolve's point search ignores the deformation)
        smesh = self.strip.mesh
        self._mech_strip_pts = find_points(smesh, *self._mech_logical)
        self._empty_strip_pts = (find_points(smesh, *self._empty_logical) if len(self._empty)
                                 else None)
        self._strip_tris = mesh_triangles(self.strip.mesh)
        # the CFs evaluated at every update, built and compiled once (they read GridFunctions
        # and Parameters): 2-3x faster to evaluate than the plain expression trees
        plastic, friction = self.sources()
        self._plastic_cf, self._friction_cf = plastic.Compile(), friction.Compile()

    def reset(self, T: float) -> None:
        """A uniform temperature T (K) on both meshes."""
        self.T.Set(float(T))
        self.T_mean.Set(float(T))
        self._set_ratio()
        self._change = math.inf
        if self.field is not None:
            self.field.gf.Set(float(T))

    # --- sources on the mechanics mesh -----------------------------------------------------
    def sources(self):
        """(plastic power density W/m^3, friction power per area W/m^2 where in contact) of the
        mechanics' fields, as CFs to evaluate at volume points (k from the volume gradient)."""
        return self._heat_sources()

    # --- mechanics -> strip ----------------------------------------------------------------
    def _find(self, ref: np.ndarray):
        """Mesh points of the mechanics mesh at reference positions (N, 2): found in the
        undeformed mesh (``fem/point_search.py``); a CF evaluated at them later is evaluated
        on the deformed mesh, at their current positions."""
        pts = mesh_points(self.mesh, ref[:, 0], ref[:, 1], self._disp)
        missing = int(np.sum(np.asarray(pts["nr"]) < 0))
        if missing:
            raise RuntimeError(f"{missing} strip points outside the mechanics mesh")
        return pts

    @staticmethod
    def _at(cf, pts) -> np.ndarray:
        """A CF (or GridFunction) at mesh points: (N, dim)."""
        return np.asarray(cf(pts), dtype=float).reshape(len(pts), -1)

    def _column_points(self):
        """(fine eta, reference points): SUBSAMPLES points per row interval on every column."""
        strip = self.strip
        eta = strip.eta
        fine = np.concatenate([np.linspace(a, b, SUBSAMPLES + 1)[:-1]
                               for a, b in zip(eta[:-1], eta[1:])] + [eta[-1:]])
        # each SUBSAMPLES-th is the row's eta itself (attach takes the vertices from them)
        assert np.array_equal(fine[::SUBSAMPLES], eta)
        Xg, Eg = np.meshgrid(strip.X, fine)
        return fine, np.stack([Xg.ravel(), Eg.ravel() * strip.top_height(Xg.ravel())], -1)

    def _column_values(self) -> np.ndarray:
        """(x, y, v_x, v_y) at every fine column point, (len(_fine), nx+1, 4): current
        positions (m) and the mechanics' velocity (m/s)."""
        shape = (len(self._fine), len(self.strip.X), 4)
        pos = self._col_ref + self._col_p2(self._disp.vec.FV().NumPy())
        vel = self._col_p2(self.form.nonlinear.gf.vec.FV().NumPy())
        return np.concatenate([pos, vel], axis=1).reshape(shape)

    def fine_column_flux(self, both: np.ndarray | None = None) -> np.ndarray:
        """The flux below every fine column point (``_fine`` eta, all columns), m^2/s: int v.n
        ds over the column's current (deformed) line; ``both``: ``_column_values()`` if the
        caller has them."""
        if both is None:
            both = self._column_values()
        shape = both.shape
        pos, vel = both[..., :2], both[..., 2:]
        dx, dy = np.diff(pos[..., 0], axis=0), np.diff(pos[..., 1], axis=0)
        vm = 0.5 * (vel[1:] + vel[:-1])
        flux = np.concatenate([np.zeros((1, shape[1])),
                               np.cumsum(vm[..., 0] * dy - vm[..., 1] * dx, axis=0)])
        return flux

    def _transfer(self) -> None:
        """Place the strip, and carry the flow, the heat sources and the contact over."""
        strip = self.strip
        both = self._column_values()
        # the strip vertices' positions: the rows of column points that are vertex rows
        strip.place(both[::SUBSAMPLES, :, :2].reshape(-1, 2))
        # the flux below each strip vertex along its column (ny+1, nx+1), m^2/s
        flux = self.fine_column_flux(both)[::SUBSAMPLES]
        strip.set_stream_function(flux, total=float(flux[-1, 0]))
        self._flow = None
        self._qs.vec.FV().NumPy()[:] = cell_means(
            self._at(self._plastic_cf, self._cells[0])[:, 0], self._cells[1])
        d = self._disp.vec.FV().NumPy()
        ranges = []
        for top, lo_p, hi_p in self._surfaces:
            rows = np.nonzero(top.edge_contact)[0]
            lo = hi = 0.0
            if len(rows):
                xs = top.vertex_positions(d, np.concatenate([top.ea[rows], top.eb[rows]]))[:, 0]
                tol = 1e-9 * max(1.0, float(np.max(np.abs(xs))))
                lo, hi = float(xs.min()) - tol, float(xs.max()) + tol
            lo_p.Set(lo)
            hi_p.Set(hi)
            ranges.append((lo, hi))
        # the friction flux: each surface vertex's mean over the part of its dual segment in
        # its roll's contact (the flux is the friction law's only there; the surfaces' points
        # lower first on the full strip, as _surface_rows)
        from ngsolve import x

        pts, w = self._surface_cells
        qf = np.zeros(strip.nv)
        qf[self._surface_rows] = contact_means(self._at(self._friction_cf, pts)[:, 0],
                                               self._at(x, pts)[:, 0], ranges[::-1], w)
        self._qfs.vec.FV().NumPy()[:] = qf

    def _element_flow(self):
        """The strip's ``element_flow`` (barycentric gradients, Jacobians, curl psi per
        triangle), once per placement (``_transfer`` clears it)."""
        if self._flow is None:
            self._flow = self.strip.element_flow(self._strip_tris)
        return self._flow

    def _element_tau(self) -> np.ndarray:
        """The SUPG parameter of each strip triangle at the current flow (``p1_supg_tau``):
        the velocity curl psi of the P1 stream function on the placed strip."""
        props, T0 = self.props, self.bc.entry_temperature
        return p1_supg_tau(*self._element_flow(), float(props.rho_c_values(T0)),
                           float(props.k_values(T0)), self.field.supg)

    def _element_load(self, tau: np.ndarray) -> np.ndarray:
        """int q (w + tau v.grad w) of the plastic power density at the strip's vertices
        (``p1_supg_load``)."""
        grads, det, v = self._element_flow()
        return p1_supg_load(self._strip_tris, grads, det, v, tau, self._qs.vec.FV().NumPy(),
                            self.strip.nv)

    def strip_sources(self):
        """(velocity, plastic density, friction flux, contact) on the strip mesh (the same
        objects every time: the field's forms are built once)."""
        return self.strip.velocity(), self._qs, self._qfs, self._chi

    # --- updates ---------------------------------------------------------------------------
    def update_steady(self, tol: float = 1e-8, max_iter: int = 30, fresh: bool = False) -> float:
        """The steady temperature of the current flow on the strip mesh, sampled back at the
        mechanics' vertices; returns the largest change of the elements'
        temperatures over the largest. ``max_iter = 1`` inside a fixed point that repeats
        until that change is small: one Newton step from the last temperature, whose error
        is then of the order of the change squared. ``fresh``: a new solve's first update
        (a warm start), never on the factors kept from an earlier case."""
        self._transfer()
        # inside the fixed point, once the temperature moves by less than CHORD_BELOW of
        # itself per update, the heat equation's factors are kept (Newton-chord): the flow,
        # and with it the matrix, then changes little between updates
        chord = max_iter == 1 and self._change < CHORD_BELOW and not fresh
        self.last = self.field.solve_steady(*self.strip_sources(), tol=tol, max_iter=max_iter,
                                            chord=chord)
        vals = self.field.values

        def at(pts):
            return np.asarray(self.field.gf(pts), dtype=float).reshape(-1)

        self.T.vec.FV().NumPy()[:] = at(self._mech_strip_pts)
        # element means: the strip vertices' lumped areas (current positions) as weights
        p, t = self.strip.physical, self._strip_tris
        e1, e2 = p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]]
        area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
        w = np.bincount(t.ravel(), np.repeat(area / 3.0, 3), minlength=len(vals))
        mean = self._element_means(vals, w)
        if len(self._empty):
            mean[self._empty] = at(self._empty_strip_pts)
        old = self.T_mean.vec.FV().NumPy().copy()
        self.T_mean.vec.FV().NumPy()[:] = mean
        self._set_ratio()
        self._change = float(np.max(np.abs(mean - old))) / float(np.max(np.abs(old)))
        return self._change

    def _element_means(self, vals: np.ndarray, w: np.ndarray) -> np.ndarray:
        """Each mechanics element's temperature from the strip vertices inside it (weights
        ``w``; the full strip's mid-plane vertices half above, half below): their K-mean at
        the entry strain (``thermal_sampling.k_means``)."""
        ne, owner = self.mesh.ne, self._owner
        if getattr(self, "_mid", None) is not None:   # the mid-plane's: half above, half below
            rows, _, below = self._mid                  # (``_owner`` holds the above's)
            owner = np.concatenate([owner, np.asarray(below["nr"], dtype=int)])
            w = np.concatenate([w, 0.5 * w[rows]])
            w[rows] *= 0.5
            vals = np.concatenate([vals, vals[rows]])
        consistency = (None if self.flow is None else
                       (lambda T: self.flow.consistency(self.entry_strain, T)))
        return k_means(owner, ne, vals, w, consistency)

    # --- figures ---------------------------------------------------------------------------
    def vertex_temperature(self) -> np.ndarray:
        """The temperature at the mechanics mesh's vertices (K), a copy."""
        return self.T.vec.FV().NumPy().copy()

    def flow_temperature(self) -> np.ndarray:
        """The temperature the flow stress takes (the elements' means, ``_element_means``),
        averaged at the mechanics' vertices (K)."""
        from ngsolve import H1, GridFunction

        g = GridFunction(fe_space(H1, self.mesh, order=1))
        g.Set(self.T_mean)
        return g.vec.FV().NumPy()[:self.mesh.nv].copy()

    def strip_fields(self) -> dict[str, np.ndarray]:
        """The strip mesh as drawn: current vertex positions (m), triangles and T (K)."""
        return {"points": self.strip.physical.copy(), "triangles": self._strip_tris.copy(),
                "temperature": self.field.values.copy()}

    def balance(self) -> dict:
        """Heat flows (W/m) and the balance error of ``TemperatureField.balance``; the
        sources are those of the last update (only ``_transfer`` changes them, and a solve
        follows it): its load vector is reused."""
        return self.field.balance(*self.strip_sources(), sources_unchanged=True)

    def section_means(self, x0: float, band: float) -> tuple[float, float, float]:
        """(mixing-cup mean int T v_x / int v_x over the strip between x0 and x0 + band, the
        top's temperature at the roll gap's column, the bottom's there (the lower roll's
        surface in the full strip; the mid-plane's in the half)): the exit temperatures."""
        from ngsolve import IfPos, x

        u, T, mesh = self.strip.velocity(), self.field.gf, self.strip.mesh
        sel = IfPos(x - x0, IfPos(x0 + band - x, 1.0, 0.0), 0.0)
        flux = integrate(sel * u[0], mesh)
        mean = integrate(sel * u[0] * T, mesh) / flux if flux else math.nan
        ny, nx1 = self.strip.shape
        surface = float(self.field.values[(ny - 1) * nx1 + self.strip.i_exit])
        return mean, surface, float(self.field.values[self.strip.i_exit])

    def measure(self, x_exit: float, h: float, heat_flows: bool = True) -> dict:
        """The thermal figures of one state (K, W/m): exit mean (mixing cup over 2 h after the
        roll gap section ``x_exit``) and the surface temperature at the gap's column (the full
        strip's both surfaces), the heat flows and the balance error (NaN without
        ``heat_flows``: the fixed point's intermediate rows), the extreme temperatures, the
        strip mesh's size."""
        mean, surface, bottom = self.section_means(x_exit, 2.0 * h)
        vals = self.field.values
        out = {"exit_temperature_mean": mean, "exit_temperature_surface": surface,
               "max_temperature": float(np.max(vals)), "min_temperature": float(np.min(vals)),
               "thermal_iterations": self.last.iterations, "thermal_dofs": int(len(vals)),
               "thermal_layer": self.delta}
        if self.strip.full:         # the lower roll's surface (issue 52)
            out["exit_temperature_surface_lower"] = bottom
        flows = self.balance() if heat_flows else dict.fromkeys(HEAT_FLOWS, math.nan)
        out.update(flows)
        return out


#: The heat flows and the balance error of ``TemperatureField.balance`` (W/m, -).
HEAT_FLOWS = ("plastic_heat", "friction_heat_to_strip", "heat_to_roll", "heat_to_air",
              "advected_in", "advected_out", "conducted_in", "heat_balance_error")

