"""The penalised weak form of the rolling problem, report (3.2), (3.3), (3.6).

Terms (all divided by K: the discrete problem is solved for p/K, so it is identical for every K
and stresses are K times the reduced ones; this is how the penalties of Table 1 "scale with K"):

- Norton-Hoff volume term (2.21) with the pressure as Lagrange multiplier (2.24);
- on the contact Gamma_C (edges flagged by ``chi``): the friction law (viscoplastic (2.29a),
  Coulomb or Tresca, ``model/friction/``) on the slip v_s = (v - U_roll).t t (2.27), and the
  bilateral penalty gamma_vC (dv.n)(phi.n) for (2.28a); n and t are the roll's normal and
  tangent at the point, so U_roll.n = 0 exactly. Coulomb's pressure is the penalty reaction
  gamma_vC (v.n) at the same point; the shear flow stress k = sigma_ef/sqrt3 of the Coulomb cap
  and of Tresca is that of the adjacent element's strain rate (element-boundary integral: a
  boundary integral sees only the surface gradient); both inside Newton;
- on the free top Gamma_0 (top edges not in contact): the one-sided inlet penalty (3.2a) for
  x <= X_roll (Gamma_0L) or outlet penalty (3.2b) for x > X_roll (Gamma_0R), and, in the
  ``"constrained"`` free-surface model only, gamma_v0 (v.n)(phi.n) (3.2d), n the mesh normal on
  Gamma_0L and e_y on the flat exit surface Gamma_0R (``free_normal``); ``"traced"`` tops are
  traction-free;
- on the tail face Gamma_in: (3.2a); on the head face Gamma_out: (3.2b) plus gamma_v0 v_y phi_y,
  the vertical-motion correction T* the report adds on Gamma_out; the back and front tensions
  as the normal traction sigma n on Gamma_in and Gamma_out (reduced by K like the rest).
Penalty parameters follow Table 1: gamma_v0 = gamma_vC = 10/h in the soft zone I around the
first touching point, 25/h elsewhere; gamma_in = gamma_out = 2/h^(m+1).

Exact contact (``contact="multiplier"``, the steady solver's default, docs/theory.md 1e): the
roll's impermeability u.n = 0 on the arc holds weakly against a continuous P1 multiplier
lambda on the arc, the contact pressure itself (no penalty: nothing leaks through the roll,
nothing depends on the roll speed or the units). The multiplier is carried scaled to a velocity,
p_c = s lambda~ with s = mu_ref / l_c (mu_ref the secant viscosity at the strain rate U / l_c),
so the constraint rows and the stopping test are in the units of the momentum rows and of the
velocity. The remaining penalties (inlet/outlet (3.2a,b), the head face's T*, the constrained
tops (3.2d)) scale with the same mu_ref / h (``ScaledPenalties``): unit-free.
"""
from __future__ import annotations

from dataclasses import replace

from hotroll.fem.forms import NonlinearProblem, norton_hoff_tangent, norton_hoff_volume, one_sided
from hotroll.fem.friction_terms import FrictionTerms
from hotroll.fem.penalties import PenaltyTable, ScaledPenalties, _elements_on, reference_viscosity
from hotroll.fem.primal_dual import FrictionDual, NortonHoffDual, TangentPoints
from hotroll.fem.reproducible import fe_space
from hotroll.fem.spaces import taylor_hood
from hotroll.model.friction import FrictionLaw
from hotroll.model.geometry import RollPass
from hotroll.model.material import NortonHoff

TOP = "top|arc|exit"   # the whole top boundary (the steady strip adds "exit")


#: Contact methods of the steady solver: the exact one (default) and the report's penalty.
CONTACT_METHODS = ("multiplier", "penalty")
#: Relative weight of the -delta s lambda xi term that only the Newton matrix carries (never the
#: residual): it gives the multiplier rows a non-zero pivot so that the LDL^T factorisation
#: (no pivoting) works; the solution is the exact one (docs/theory.md 1e).
MATRIX_REGULARISATION = 1e-8


class RollingForm(FrictionTerms):
    """Spaces, parameters and the Newton/Picard forms of (3.6) on one (moving) mesh."""

    #: the boundary the contact multiplier lives on (taylor_hood's ``multiplier_on``)
    MULTIPLIER_ON = "arc"
    #: the form's scalar data (ngsolve Parameters): the friction parameter, the rate exponent,
    #: the tops' split, the roll speed and the friction's regularisation, the reference
    #: viscosity and pressure scale, the tensions (a 3D strip starts from its 2D pass's)
    PARAMETERS = ("a_f", "m", "x_split", "U", "v_reg", "_mu", "_lam", "tension_back",
                  "tension_front")
    #: the contact's start (a named point of the mesh, ``mesh.strip_face``)
    START = "start"
    #: the space dimension (a 3D strip: ``fem/rolling_form_3d.py``)
    dim = 2

    def __init__(self, mesh, rp: RollPass, material: NortonHoff, friction: FrictionLaw,
                 penalties: PenaltyTable, free_surface: str, tensions: tuple = (0.0, 0.0),
                 consistency=1.0, rate_offset=None, contact: str = "penalty",
                 contact_regions: str = TOP, primal_dual: bool = True,
                 strip_compliance: float | None = None, strip_depth: float | None = None):
        from ngsolve import FacetFESpace, GridFunction, Parameter

        if contact not in CONTACT_METHODS:
            raise ValueError(f"contact.method must be one of {CONTACT_METHODS}, got {contact!r}")
        self.mesh, self.rp = mesh, rp
        self.free_surface = free_surface
        self.contact = contact
        #: the strip's elastic compliance (1 - nu_s^2) / E_s times K (per unit of reduced
        #: pressure), or None: rigid-plastic contact (``constraint``)
        self.compliance = strip_compliance
        #: the elastic layer's largest depth (m): c_e = compliance min(y, depth) (``Problem.
        #: strip_layer_depth``); None: the half thickness y
        self.strip_depth = strip_depth
        # what follows the roll speed is a Parameter (``set_roll_speed``: a tandem stand's speed
        # found inside the solve, issue 34): the surface speed U, the friction's v_reg, the
        # viscosity scale mu_ref of the penalties, and the multiplier's scale
        self._mu = Parameter(reference_viscosity(material, rp))
        if contact == "multiplier":
            penalties = ScaledPenalties(penalties.h, self._mu)
        # p_c = lam_scale * lambda~ (reduced): lambda~ is a velocity, of the order of U where
        # the pressure is of the order of the reference stress mu_ref U / l_c
        self._lam = Parameter(self.mu_ref / rp.contact_length)
        self.U = Parameter(rp.u_roll)
        self.v_reg = Parameter(friction.v_reg)
        self.law = friction                           # its floats (numpy evaluations)
        friction = replace(friction, v_reg=self.v_reg)   # the forms' (v_reg a Parameter)
        self.material, self.friction, self.penalties = material, friction, penalties
        # K(strain, T) / K_ref of a strain-dependent flow stress (a CF of the strain field,
        # fem/strain.py), 1 for Norton-Hoff
        self.consistency = consistency
        self.fes = self._spaces(self.MULTIPLIER_ON if contact == "multiplier" else None)
        self.m = Parameter(material.m)      # set to 1 for the very first iterate (Section 3.4)
        # the material's rate exponent: m, plus m(T) - m_ref (a CF) where a temperature-
        # dependent law's exponent varies (solvers/thermal_feedback.py); the friction law keeps m
        self.m_material = self.m if rate_offset is None else self.m + rate_offset
        self.a_f = Parameter(1.0)           # friction parameter, updated by (3.15) every step
        # free tops before this x are the entry's (3.2a), after it the exit's (3.2b): the roll
        # axis, or (steady solver) a point inside the contact, which may end before the axis
        self.x_split = Parameter(rp.axis_x)
        self.chi = GridFunction(fe_space(FacetFESpace, mesh, order=0))  # 1 on contact edges
        # back / front tension over K (reduced, like every stress in the form)
        self.tension_back, self.tension_front = Parameter(tensions[0]), Parameter(tensions[1])
        # the elements a law with k integrates its friction on (element boundaries): those
        # along the boundary the contact can be on (the steady strip's: its arc only; a third
        # of the Jacobian's assembly was the rest of the top's, multiplied by chi = 0)
        self.top_elements = _elements_on(mesh, contact_regions) if friction.uses_k else None
        self.contact_regions = contact_regions
        # a flattened roll (rp.shape): its normal's tilt from the radius and its rim's hoop
        # strain at the mesh vertices (P1; set_roll_shape), read on the arc
        self.roll_tilt = self.roll_hoop = None
        if rp.shape is not None:
            from ngsolve import H1

            P1 = fe_space(H1, mesh, order=1)
            self.roll_tilt, self.roll_hoop = GridFunction(P1), GridFunction(P1)
            self.roll_cx = Parameter(rp.centre[0])     # moves with the lowest point
        self._newton_problem(material.eps0, contact_regions, rp.u_roll, primal_dual)

    def _spaces(self, multiplier_on: str | None):
        """Taylor-Hood with v_y = 0 on the symmetry line (and the contact's multiplier)."""
        return taylor_hood(self.mesh, dirichlety="sym", multiplier_on=multiplier_on)

    def _newton_problem(self, eps0: float, contact_regions: str, velocity_scale: float,
                        primal_dual: bool) -> None:
        """The Newton problem of the form and its tangent's duals."""
        mesh = self.mesh
        # Newton's tangent: primal-dual (fem/primal_dual.py) or the primal one; the volume
        # terms of both forms are integrated on the dual's quadrature points either way
        self.dual = NortonHoffDual(mesh, eps0)
        self._dual_cf = self.dual.cf if primal_dual else None
        # ... and the friction's slip (FrictionDual) where the law has a tangent in the slip
        self.friction_dual = FrictionDual(mesh, contact_regions) if primal_dual else None
        # ... and the tangent's coefficients at those points, interpolated once an iteration
        self.tangent_points = TangentPoints(self.dual.space, mesh.dim) if primal_dual else None
        self.nonlinear = NonlinearProblem(self.fes, self.integrand,
                                          velocity_scale=velocity_scale,
                                          jacobian=self.jacobian,
                                          pressure_row_scale=self.mu_ref)
        if primal_dual:
            self.dual.attach(self.nonlinear.velocity)
            if self.friction_dual is not None:
                self.friction_dual.attach(self.nonlinear.velocity, self.slip, self.v_reg)
            self.nonlinear.prepare = self._prepare_duals

    def _prepare_duals(self, iteration: int) -> bool:
        """Newton's hook (``nonlinear.newton``): the two duals at the current iterate."""
        self.dual.prepare(iteration)
        self.tangent_points.prepare()
        if self.friction_dual is not None:
            self.friction_dual.prepare(iteration)
        return False

    @property
    def mu_ref(self) -> float:
        """The reduced secant viscosity at the strain rate U / l_c (``reference_viscosity``)."""
        return self._mu.Get()

    @property
    def lam_scale(self) -> float:
        """s = mu_ref / l_c: the contact pressure (reduced) per unit of lambda~."""
        return self._lam.Get()

    def set_roll_speed(self, rp: RollPass, v_reg: float) -> None:
        """The same pass at another roll speed (``rp``; the friction's regularisation speed
        ``v_reg``, m/s): the Parameters that follow U, as a form built for ``rp`` has them;
        the multiplier's DOFs rescaled so that the pressure they carry stays."""
        old = self._lam.Get()
        self.rp = rp
        self._mu.Set(reference_viscosity(self.material, rp))
        self._lam.Set(self.mu_ref / rp.contact_length)
        self.U.Set(rp.u_roll)
        self.v_reg.Set(v_reg)
        self.law = replace(self.law, v_reg=v_reg)
        nl = self.nonlinear
        nl.velocity_scale, nl.pressure_row_scale = rp.u_roll, self.mu_ref
        if self.exact:
            r = nl.multiplier_range()
            nl.gf.vec.FV().NumPy()[r] *= old / self._lam.Get()

    def set_roll_shape(self, vertices) -> None:
        """The flattened roll's tilt and hoop strain at the mesh vertices ``vertices`` (their
        current positions, m; one row per vertex)."""
        rp = self.rp
        self.roll_cx.Set(rp.centre[0])
        self.roll_tilt.vec.FV().NumPy()[:] = rp.tilt(vertices)
        self.roll_hoop.vec.FV().NumPy()[:] = rp.shape.strain(rp.angle(vertices))

    # --- geometry of the roll as coefficient functions ------------------------------------
    def roll_frame(self):
        """(n, t): roll normal (out of the plate, into the roll) and tangent along U_roll; a
        flattened roll's turned by its tilt b: (cos b n0 - sin b t0, sin b n0 + cos b t0)."""
        from ngsolve import CF, cos, sin, sqrt, x, y

        cx, cy = self.rp.centre
        if self.roll_tilt is not None:
            cx = self.roll_cx
        r = sqrt((x - cx) ** 2 + (y - cy) ** 2)
        n = CF(((cx - x) / r, (cy - y) / r))
        t = CF((-(y - cy) / r, (x - cx) / r))
        if self.roll_tilt is None:
            return n, t
        b = self.roll_tilt
        return cos(b) * n - sin(b) * t, sin(b) * n + cos(b) * t

    def roll_speed(self):
        """|U_roll|: omega R, times (1 + e_tt) on a flattened roll's rim."""
        if self.roll_hoop is None:
            return self.U
        return self.U * (1.0 + self.roll_hoop)

    def free_normal(self, u):
        """u.n on the free top for (3.2d): the mesh normal before the gap, the normal of the
        flat exit surface, e_y, after it (x > X_roll). The Lagrangian exit surface is never
        exactly flat: with its own normal, (3.2d) pins u_x wherever it wrinkles, the wrinkles
        grow and the mesh tangles (see docs/theory.md, "Free exit surface")."""
        from ngsolve import IfPos, specialcf, x

        return IfPos(x - self.rp.axis_x, u[1], u * specialcf.normal(self.dim))

    def tangential(self, u):
        """u's part along the roll's surface, where the friction acts: u.t (the tangent of
        the roll's circle; a 3D strip's is a vector in the roll's tangent plane)."""
        _, t = self.roll_frame()
        return u * t

    def slip(self, u):
        """Scalar slip v_s . t = u.t - |U_roll| (2.27); negative where the plate lags the roll."""
        return self.tangential(u) - self.roll_speed()

    @property
    def exact(self) -> bool:
        return self.contact == "multiplier"

    @property
    def multiplier(self):
        """The solution's scaled multiplier lambda~ (a GridFunction on the arc; None with
        penalties)."""
        return self.nonlinear.gf.components[2] if self.exact else None

    def multiplier_vertices(self):
        """(vertex numbers, multiplier DOFs) of the arc's P1 multiplier, in the component's
        numbering (cached)."""
        cached = getattr(self, "_mult_vertices", None)
        if cached is None:
            import numpy as np

            # the contact region's boundary elements' vertex DOFs (P1: one per vertex, in the
            # element's vertex order): one lookup per arc edge where one per mesh vertex took
            # 22 ms a pass
            L, found = self.fes.components[2], {}
            for el in self.mesh.Boundaries(self.MULTIPLIER_ON).Elements():
                for v, d in zip(el.vertices, L.GetDofNrs(el)):
                    if d >= 0:
                        found[v.nr] = d
            verts = np.array(sorted(found), int)
            cached = self._mult_vertices = (verts, np.array([found[v] for v in verts], int))
        return cached

    def layer_compliance(self, y):
        """c_e per unit reduced pressure at half thicknesses ``y`` (m, numbers): compliance
        min(y, strip_depth) (``constraint``)."""
        import numpy as np

        depth = y if self.strip_depth is None else np.minimum(y, self.strip_depth)
        return self.compliance * depth

    def vertex_pressure(self):
        """The multiplier's contact pressure (reduced) at every mesh vertex (0 off the arc)."""
        import numpy as np

        out = np.zeros(self.mesh.nv)
        verts, dofs = self.multiplier_vertices()
        out[verts] = self.lam_scale * self.multiplier.vec.FV().NumPy()[dofs]
        return out

    def pressure(self, u, lam=None):
        """Contact pressure (reduced units): the multiplier s lambda~ (``lam``: a trial function
        or the solution's by default) or the penalty reaction gamma_vC (u.n)."""
        from ngsolve import x

        if self.exact:
            return self._lam * (self.multiplier if lam is None else lam)
        n, _ = self.roll_frame()
        return self.penalties.surface(x, self.rp.soft_zone) * (u * n)

    def inlet_penalty(self, u, w):
        """(3.2a) per unit test v_x: gamma_in [v_x - |U_roll|]_+, active set taken at w."""
        U = self.U
        return self.penalties.inlet_outlet(self.m) * one_sided(u[0] - U, w[0] - U)

    def outlet_penalty(self, u, w):
        """(3.2b) per unit test v_x: -gamma_out [|U_roll| - v_x]_+, active set taken at w."""
        U = self.U
        return -self.penalties.inlet_outlet(self.m) * one_sided(U - u[0], U - w[0])

    # --- the form ---------------------------------------------------------------------------
    def integrand(self, u, p, w, v, q, lam=None, xi=None):
        """The residual form (3.6), coefficients at w (w = u: Newton; the last iterate: Picard);
        exact contact: the multiplier's trial and test ``lam``, ``xi`` (Newton: w = u)."""
        from ngsolve import dx

        vol = norton_hoff_volume(self.material, self.m_material, u, p, w, v, q,
                                 K=self.consistency)
        out = vol * dx(intrules=self.dual.intrules) + self.boundary(u, w, v, lam=lam)
        return out + self.constraint(u, v, lam, xi) if self.exact else out

    def constraint(self, u, v, lam, xi, regularise: float = 0.0, u_w=None, lam_w=None):
        """s (lambda~ v.n + xi u.n) on the arc: the contact pressure's work and the weak
        impermeability int xi u.n = 0; ``regularise`` adds -delta s lambda~ xi (matrix only).

        With the strip's compliance (``compliance``): the strip's surface sits delta = c_e p
        below its plastic flow's (its elastic thickness strain, c_e = (h/2)(1 - nu_s^2)/E_s,
        h = 2y the local thickness; at most ``strip_depth``): the plastic flow's surface lies
        delta beyond the roll, and the layer between carries the flux F = delta (u.t). The
        roll is impermeable to the plastic flow less what that layer takes up, u.n = dF/ds
        (linearised across the thin layer, incompressible), weakly: int w [u.n - dF/ds] ds -
        F(start) xi(start) = 0, w the test function upwinded along t (each segment's dF/ds
        on its downstream node, ``elastic_rate``) and F's jump from 0 on the free top to
        F(start) at the contact's start a point term there (``layer_ends``; a 3D strip's
        the line terms of the contact's boundary, ``RollingForm3D.layer_ends``): with
        xi = 1, int u.n = F(end), the layer's flux at the end (0 where p_end = 0): the volume
        is conserved. ``u_w``, ``lam_w``: the Jacobian at that iterate along (u, lam)."""
        from ngsolve import ds

        n, t = self.roll_frame()
        term = self._lam * (lam * (v * n) + xi * (u * n))
        if regularise:
            term = term - regularise * self._lam * lam * xi
        if not self.compliance:
            return term * ds(self.MULTIPLIER_ON, bonus_intorder=2)
        depth, slope = self.layer_depth()
        term = term - self.elastic_rate(u, lam, xi, t, n, depth, slope, u_w, lam_w)
        return (term * ds(self.MULTIPLIER_ON, bonus_intorder=2)
                + self.layer_ends(u, lam, xi, t, depth, u_w, lam_w))

    def layer_depth(self):
        """(c_e's depth d, a CF; its gradient, a vector CF): d = min(y, strip_depth)."""
        from ngsolve import CF, IfPos, y

        e_y = CF((0.0, 1.0) + (0.0,) * (self.dim - 2))
        if self.strip_depth is None:
            return y, e_y
        return (IfPos(y - self.strip_depth, self.strip_depth, y),
                IfPos(y - self.strip_depth, 0.0, 1.0) * e_y)

    def centre_distance(self):
        """r, the distance from the roll's centre (a CF; a flattened roll's centre moves with
        its lowest point, ``roll_cx``)."""
        from ngsolve import sqrt, x, y

        cx, cy = self.rp.centre
        if self.roll_tilt is not None:
            cx = self.roll_cx
        return sqrt((x - cx) ** 2 + (y - cy) ** 2)

    def roll_curvature(self):
        """The roll surface's curvature along t (dt/ds = kappa n): 1/r, plus a flattened
        roll's tilt's rate along t."""
        from ngsolve import grad

        kappa = 1.0 / self.centre_distance()
        if self.roll_tilt is None:
            return kappa
        _, t = self.roll_frame()
        return kappa + grad(self.roll_tilt) * t

    def layer_flux_rate(self, u, du, lam, glam, t, n, depth, slope):
        """dF/ds of the layer's flux F = c_e lambda~ (u.t) per unit s K (bilinear in (u, lam)):
        ``du`` u's derivative matrix on the surface, ``glam`` lambda~'s gradient on it (a 3D
        strip adds the flux's divergence across the width, ``RollingForm3D``)."""
        c = self.compliance * depth
        dut = (du * t) * t + self.roll_curvature() * (u * n)      # d(u.t)/ds
        return (c * ((u * t) * (glam * t) + lam * dut)
                + self.compliance * (slope * t) * lam * (u * t))

    def elastic_rate(self, u, lam, xi, t, n, depth, slope, u_w=None, lam_w=None):
        """The layer's flux rate in the constraint, s^2 K^-1 dF/ds w (``depth``: c_e's half
        thickness, a CF, ``slope`` its gradient; w the test function upwinded along t;
        ``u_w``, ``lam_w``: the Jacobian at that iterate along (u, lam))."""
        from ngsolve import grad

        w = xi + 0.5 * self.arc_step() * (xi.Trace().Deriv() * t)
        g_lam = lam.Trace().Deriv()
        du = u.Trace().Deriv()
        if u_w is None:
            rate = self.layer_flux_rate(u, du, lam, g_lam, t, n, depth, slope)
        else:
            rate = (self.layer_flux_rate(u, du, lam_w, grad(lam_w), t, n, depth, slope)
                    + self.layer_flux_rate(u_w, grad(u_w), lam, g_lam, t, n, depth, slope))
        return self._lam * self._lam * rate * w

    def layer_flux(self, u, lam, t, depth, u_w=None, lam_w=None):
        """The layer's flux along ``t``, F = c_e lambda~ (u.t) per unit s K (``u_w``,
        ``lam_w``: its derivative at that iterate along (u, lam))."""
        c = self.compliance * depth
        if u_w is None:
            return c * lam * (u * t)
        return c * (lam_w * (u * t) + lam * (u_w * t))

    def layer_ends(self, u, lam, xi, t, depth, u_w=None, lam_w=None):
        """The layer's flux at the contact's start, -s^2 K^-1 F xi there (a point integral on
        the ``START`` points, ``mesh.strip_face``): F's jump from 0 on the free top. The
        contact's end has no term (a searched end has p = 0 there; a held end passes F(end),
        docs/notes/elastic-layer-flux)."""
        flux = self._lam * self._lam * self.layer_flux(u, lam, t, depth, u_w, lam_w) * xi
        return -flux * self.layer_point(self.START)

    def layer_point(self, name: str):
        """The (BBND) integral on the mesh's named points (a 3D strip's lines) ``name``; a
        mesh without them raises (no silent zero)."""
        from ngsolve import BBND
        from ngsolve.comp import DifferentialSymbol

        region = self.mesh.BBoundaries(name)
        if not any(region.Mask()):
            raise ValueError(f"the elastic layer needs the contact's boundary as named mesh "
                             f"points or lines ({name!r}); the mesh has "
                             f"{self.mesh.GetBBoundaries()}")
        return DifferentialSymbol(BBND)(definedon=region)

    def arc_step(self):
        """The contact element's length along t (the elastic rate's upwinding): the arc
        segment's, ``mesh_size``."""
        from ngsolve import specialcf

        return specialcf.mesh_size

    def jacobian(self, w, u, p, v, q, lam=None, xi=None, lam_w=None):
        """Newton's Jacobian of (3.6) at w: the Norton-Hoff tangent and the friction tangent
        by hand, the other boundary terms differentiated symbolically (w is the iterate's
        GridFunction component); exact contact: the constraint (linear) with the matrix-only
        regularisation, and Coulomb's dependence on the multiplier."""
        from ngsolve import dx

        if self.tangent_points is not None:     # its coefficients at the points (prepare)
            self.tangent_points.attach(self.material, self.m_material, w, self.consistency)
            vol = self.tangent_points.tangent(u, p, v, q, self._dual_cf)
        else:
            vol = norton_hoff_tangent(self.material, self.m_material, w, u, p, v, q,
                                      K=self.consistency)
        out = (vol * dx(intrules=self.dual.intrules)
               + self.friction_tangent(w, u, v, lam, lam_w) * self.friction_measure()
               + self.boundary(w, w, v, friction=False).Diff(w, u))
        if self.exact:
            out = out + self.constraint(u, v, lam, xi, regularise=MATRIX_REGULARISATION,
                                        u_w=w, lam_w=lam_w)
        return out

    def boundary(self, u, w, v, friction: bool = True, lam=None):
        """Friction law, penalty terms (3.2), (3.3) and tensions on the boundary, coefficients at w
        (without the friction law if not ``friction``); ``lam`` the multiplier at w (exact
        contact: Coulomb's pressure)."""
        from ngsolve import IfPos, ds, specialcf, x

        rp, pen = self.rp, self.penalties
        n, t = self.roll_frame()
        gam_s = pen.surface(x, rp.soft_zone)
        chi = self.chi

        friction_term = (chi * self.friction_coefficient(w, lam=lam) * self.slip(u)
                         * self.tangential(v) if friction else None)
        # the penalty contact; exact contact: the constraint (``constraint``) instead
        contact = 0.0 if self.exact else gam_s * (u * n) * (v * n)

        inlet = self.inlet_penalty(u, w) * v[0]
        outlet = self.outlet_penalty(u, w) * v[0]
        free = IfPos(x - self.x_split, outlet, inlet)
        if self.free_surface == "constrained":
            free = free + gam_s * self.free_normal(u) * self.free_normal(v)

        nh = specialcf.normal(self.dim)
        rest = ((chi * contact + (1.0 - chi) * free) * ds(TOP)
                + (inlet - self.tension_back * (v * nh)) * ds("in")
                + (outlet + gam_s * u[1] * v[1] - self.tension_front * (v * nh)) * ds("out"))
        return friction_term * self.friction_measure() + rest if friction else rest
