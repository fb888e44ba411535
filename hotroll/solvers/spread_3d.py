"""A steady 3D pass with spread from a solved 2D pass (issue 53).

The quarter strip (mid-thickness and mid-width symmetry) is the solved 2D pass's mesh extruded
across the stock's half width b0 (``fem/extruded_mesh.py``), its form the 2D one in 3D
(``fem/rolling_form_3d.py``), its start the 2D solution in every layer. Its free surfaces are
stream surfaces of the 3D flow: the lateral face z = B(x, y) (``fem/lateral_face.py``) and the
top, traced per width level with the contact's start x_c(z) (``solvers/spread_tops.py``; with
``tops=False`` the 2D pass's in every level), and with unilateral contact each level's own
contact end (``solvers/spread_ends.py``). The friction parameter and the tensions stay as the
2D pass left them; the temperature a flow stress takes is the 2D pass's plus the entry's
difference across the width where one is given, and a strain-dependent flow stress's strain
is carried through the 3D flow (``solvers/spread_fields.py``). The surfaces' update, the
ends' search and the carried fields' transport are Newton's coupling, as the 2D pass's are
its own (``solvers/steady_solve.py``): a round after each Newton step once the step is below
the 2D pass's ``couple_below`` U, until they settle (the surfaces' largest move below
``surface_tol`` h, the 2D pass's tolerance of its traced tops; the ends' below the 2D pass's;
the carried fields' change below ``strain_rtol``); Newton then converges the flow of the
settled shape to ``tol`` (its own flow, which the figures
read). With ``edge_held`` the face is held (u_z = 0): plane strain, the 2D answer.
"""
from __future__ import annotations

import math
import time

import numpy as np

from hotroll.fem import amg
from hotroll.fem.extruded_mesh import LayerCopy, extrude, width_axis
from hotroll.fem.forms import LINEAR_SOLVERS
from hotroll.fem.lateral_face import LateralFace
from hotroll.fem.nonlinear import LinearSolveError, newton
from hotroll.fem.penalties import PenaltyTable
from hotroll.fem.reproducible import integrate
from hotroll.fem.rolling_form_3d import RollingForm3D
from hotroll.fem.strain import CarriedField
from hotroll.model.material import NortonHoff
from hotroll.solvers import spread_checks
from hotroll.solvers.spread_ends import LevelEnds
from hotroll.solvers.spread_fields import cooled_flow_stress, frozen_flow_stress, strain_3d
from hotroll.solvers.spread_tops import LevelTops
from hotroll.solvers.steady_solve import COUPLE_BELOW_ELASTIC
from hotroll.solvers.threads import solver_threads

#: how the 3D strip takes the strain of a strain-dependent flow stress: carried through its
#: own flow (the edge's hardening) or the 2D pass's in every layer
STRAIN_MODES = ("transported", "frozen")

#: GMRES iterations (NGSolve's count) a Newton direction may take on the kept factors of an
#: earlier Jacobian before they are refactorised (``fem/nonlinear.py``), where the 3D strip
#: has at least ``REUSE_FROM`` unknowns. A direction on kept factors costs a solve with them
#: an iteration; it pays where a refactorisation costs many solves, as on large 3D meshes:
#: the roughing pass (113k unknowns) 12.7 s against 0.65 s, 735.6 -> 490.4 s for its 3D
#: solve; Case R's bar (36k) 0.67 s against 0.095 s, 14.0 -> 17.6 s (slower: none there)
REUSE_STEPS = 12
REUSE_FROM = 60_000

#: the 3D strip's linear solvers: the 2D pass's, and GMRES with smoothed-aggregation AMG
#: (``fem/amg.py``: no factorisation of the whole Jacobian, for meshes whose factors do not
#: fit; slower where they do)
LINEAR_SOLVERS_3D = LINEAR_SOLVERS + (amg.NAME,)


class Spread3D:
    """The 3D quarter strip of the solved 2D ``SteadyRun`` ``run`` for a stock of half width
    ``half_width`` (m): width layers ``edge`` thick at the free edge (default the 2D contact
    mesh size), growing by ``growth`` inwards up to ``largest`` (default 4 edge layers).
    ``zone`` (m): the edge-zone model of a wide strip, only the outer ``zone`` of the half
    width graded, the interior inside its cut at half_width - zone one layer in generalized
    plane strain (``fem/rolling_form_3d.py``), tied to the zone by the flow itself (None:
    the whole half width graded).
    ``entry_temperature``: the entry temperature across the width (K, a function of z / half
    width, its value at 0 the 2D pass's) or over the cross-section (``model/section.py``, its
    mid-width column the 2D pass's entry profile), its differences from mid-width's at the
    same height carried through the bite into the flow stress (None: the 2D pass's
    temperature at every width).
    ``ends``: with unilateral contact and the tops per level, each width level's contact end
    found from its own pressure (``solvers/spread_ends.py``; False, or ``tops=False``: the 2D
    pass's end in every level).
    ``linear_solver``: Newton's first linear solver (``LINEAR_SOLVERS_3D``; the 2D pass's
    after it where it fails). ``strain``: a strain-dependent flow stress's strain carried
    through the 3D flow ("transported", with a free edge) or the 2D pass's ("frozen").
    ``reuse_steps``: GMRES iterations a Newton direction may take on the kept factors of an
    earlier Jacobian (0: fresh factors every step; default ``REUSE_STEPS`` from
    ``REUSE_FROM`` unknowns). ``interior_layers``: an edge zone's interior in this many equal
    layers, all tied (for measuring; one layer holds generalized plane strain exactly).
    ``comm``: an mpi4py communicator of several ranks (``fem/mirror.world``): every rank
    builds this strip, and its flow's Newton systems are assembled and solved on its mesh
    distributed over them (``solvers/spread_mpi.py``); None: serial."""

    def __init__(self, run, half_width: float, edge: float | None = None, growth: float = 1.2,
                 largest: float | None = None, edge_held: bool = False, tops: bool = True,
                 zone: float | None = None, linear_solver: str = "umfpack",
                 strain: str = "transported", ends: bool = True, entry_temperature=None,
                 reuse_steps: int | None = None, interior_layers: int = 1, comm=None):
        import ngsolve as ng

        t0 = time.perf_counter()
        if not half_width > 0.0:
            raise ValueError(f"half_width = {half_width!r} m: must be > 0")
        if linear_solver not in LINEAR_SOLVERS_3D:
            raise ValueError(f"linear_solver = {linear_solver!r}: one of {LINEAR_SOLVERS_3D}")
        if strain not in STRAIN_MODES:
            raise ValueError(f"strain = {strain!r}: one of {STRAIN_MODES}")
        problem, f2 = run.problem, run.form
        missing = [what for what, on in (
            ("a flattening roll (roll.model)", problem.rp.shape is not None),
            ("the constrained free surface (plate.free_surface)",
             run.s.free_surface != "traced"),
            ("the penalty contact (contact.method)", not f2.exact)) if on]
        if missing:
            raise ValueError("the 3D strip does not yet carry: " + "; ".join(missing))
        self.run2d, self.problem = run, problem
        h = problem.h
        if not int(interior_layers) >= 1:
            raise ValueError(f"interior_layers = {interior_layers!r}: must be >= 1")
        if zone is not None and not 0.0 < zone <= half_width:
            raise ValueError(f"zone = {zone!r} m: must be in (0, half width = {half_width} m]")
        modelled = half_width if zone is None else zone
        edge = min(h, modelled) if edge is None else edge
        # the width levels, from the mid-width plane to the edge; an edge zone's graded from
        # its cut, one layer in generalized plane strain inside it (RollingForm3D)
        self.cut = half_width - modelled
        self.z = self.cut + width_axis(modelled, edge, growth,
                                       4.0 * edge if largest is None else largest)
        #: the levels inside an edge zone's cut, mid-width's first (the cut is level
        #: ``interior``; 0 without a zone)
        self.interior = int(interior_layers) if self.cut > 0.0 else 0
        if self.interior:
            self.z = np.concatenate([np.linspace(0.0, self.cut, self.interior + 1)[:-1],
                                     self.z])
        self.z[-1] = half_width
        ref2 = ng.Mesh(run.mesh.ngmesh.Copy())          # the 2D reference (undeformed)
        self.mesh = extrude(ref2, self.z)
        copy = self.copy = LayerCopy(ref2, self.mesh)
        # the strain: carried through the 3D flow with a free edge; with the edge held the
        # strip is in plane strain and the 2D pass's is its answer
        self.strain = (strain_3d(run, copy, self.mesh)
                       if strain == "transported" and not edge_held else None)
        #: the entry temperature's difference across the width from mid-width's, carried
        #: through the bite (fem/strain.CarriedField), or None
        self.cooling = (None if entry_temperature is None else
                        CarriedField(self.mesh, _offset(entry_temperature, half_width)))
        self.edge_held = edge_held
        self.form = self.make_form(self.mesh, copy, self.strain, self.cooling)
        f3 = self.form
        # the chosen solver first, the others after it where it fails (fem/nonlinear.py)
        f3.nonlinear.linear_solvers = (linear_solver,) + tuple(
            n for n in LINEAR_SOLVERS if n != linear_solver)
        if linear_solver == amg.NAME:
            f3.nonlinear.layout = amg.VelocityLayout(
                f3.fes.components[0].ndof, np.array([v.point for v in self.mesh.vertices]))
        if reuse_steps is None:
            reuse_steps = REUSE_STEPS if f3.fes.ndof >= REUSE_FROM else 0
        f3.nonlinear.reuse_steps = reuse_steps
        self.disp = ng.GridFunction(f3.fes.components[0])
        copy.vector(run.disp, self.disp)
        self.mesh.SetDeformation(self.disp)
        for name in f3.PARAMETERS:
            getattr(f3, name).Set(getattr(f2, name).Get())
        copy.facets(f2.chi.space, f2.chi.vec.FV().NumPy(), f3.chi.space,
                    f3.chi.vec.FV().NumPy())
        g2, g3 = f2.nonlinear.gf, f3.nonlinear.gf
        copy.vector(g2.components[0], g3.components[0])
        for c in range(1, len(g2.components)):
            copy.copy(g2.components[c].space, g2.components[c].vec.FV().NumPy(),
                      g3.components[c].space, g3.components[c].vec.FV().NumPy())
        if self.cooling is not None:     # carried along the start's flow (the 2D pass's)
            self.cooling.transport(f3.nonlinear.velocity)
        self.face = None if edge_held else LateralFace(ref2, run.disp.vec.FV().NumPy(),
                                                       self.z, copy)
        #: the top per width level (solvers/spread_tops.py), or None: the 2D pass's
        self.tops = LevelTops(self) if tops and not edge_held else None
        #: the contact's end per width level (solvers/spread_ends.py), or None: the 2D pass's
        self.ends = (LevelEnds(self, self.tops) if ends and self.tops is not None
                     and run.unilateral else None)
        self.rounds, self.iterations, self.settled, self.failure = 0, 0, False, ""
        self.factorisations, self.reused = 0, 0
        #: the flow solve over MPI ranks (solvers/spread_mpi.py), or None
        self.mpi = None
        if comm is not None:
            from hotroll.solvers.spread_mpi import DistributedFlow

            self.mpi = DistributedFlow(self, comm)
        self.setup_time, self.solve_time = time.perf_counter() - t0, 0.0

    def make_form(self, mesh, copy, strain, cooling) -> RollingForm3D:
        """The pass's 3D form on ``mesh`` (this strip's, or its distributed copy:
        ``solvers/spread_mpi.py``), its flow stress from ``copy`` (a ``LayerCopy`` or its
        mirror), the carried ``strain`` and ``cooling`` (or None)."""
        run, problem = self.run2d, self.problem
        f2, mat = run.form, problem.material
        if cooling is None:
            consistency, rate_offset = frozen_flow_stress(run, copy, strain)
        else:
            consistency, rate_offset = cooled_flow_stress(run, copy, cooling, strain)
        return RollingForm3D(mesh, problem.rp, NortonHoff(1.0, mat.m, mat.eps0),
                             problem.friction, PenaltyTable(problem.h),
                             tensions=problem.reduced_tensions, edge_held=self.edge_held,
                             consistency=consistency, rate_offset=rate_offset,
                             strip_compliance=f2.compliance, strip_depth=f2.strip_depth,
                             interior_cut=self.cut if self.cut > 0.0 else None)

    def solve(self, max_rounds: int = 30, progress=None) -> bool:
        """Newton with the surfaces' update (with the ends' search and the carried fields'
        transport) as its coupling, as the 2D pass couples its own (``solvers/steady_solve``):
        a round each Newton step once the update is below the 2D pass's ``couple_below`` U,
        until the surfaces moved less than surface_tol h, the ends less than their tolerance
        and the carried fields changed less than strain_rtol; then Newton converges the flow
        of that settled shape to ``tol`` (the figures read it, as the 2D pass returns the flow
        of its final shape). True if settled. ``progress``: called with a report (its words
        in ``message``) after each round. Its threads as the 2D pass's solve
        (``solvers/threads.solver_threads``: an outer call's, else "auto"; BLAS 1 thread;
        over MPI ranks one each)."""
        with solver_threads(1 if self.mpi is not None else None):
            return self._solve(max_rounds, progress)

    def _solve(self, max_rounds: int, progress) -> bool:
        t0 = time.perf_counter()
        s = self.run2d.s
        system = self.form.nonlinear if self.mpi is None else self.mpi.system
        try:
            if self.face is None:
                st = newton(system, s.tol, s.max_it)
                self.settled = st.converged
            else:
                state = {"settled": False}

                def couple(update: float) -> bool:
                    if state["settled"] or self.rounds >= max_rounds:
                        return False
                    state["settled"] = self._round(update, progress)
                    if self.form.friction_dual is not None:   # the form's data moved
                        self.form.friction_dual.restart()
                    if self.mpi is not None:
                        self.mpi.sync()
                        self.mpi.restart()
                    return True

                st = newton(system, s.tol, s.max_it + 3 * max_rounds,
                            couple=couple, couple_below=s.couple_below, full_step=True)
                self.settled = st.converged and state["settled"]
            self.iterations += st.iterations
            self.factorisations += st.factorisations
            self.reused += st.reused
        except LinearSolveError as e:         # the pass's record says why (settled False)
            self.settled, self.failure = False, f"a linear solve failed: {e}"
        self.solve_time += time.perf_counter() - t0
        return self.settled

    def _round(self, update: float, progress=None) -> bool:
        """One update of the surfaces, the ends and the carried fields on the flow whose last
        Newton update was ``update`` (over U); True when all moved within their tolerances.
        With the strip's compliance the ends, which read the contact pressure, wait for a flow
        converged to ``COUPLE_BELOW_ELASTIC`` (the 2D pass's rule)."""
        s = self.run2d.s
        tol_face = s.surface_tol * self.problem.h
        self.rounds += 1
        change, ended = 0.0, 0.0
        if self.ends is not None:     # each level's contact end, then its tops
            tight = self.form.compliance and update > COUPLE_BELOW_ELASTIC
            ended = math.inf if tight else self.ends.update()
        if self.tops is not None:     # the tops first: the face is solved on them
            change = self.tops.update()
            self.tops.displace(self.disp)
            self.face.set_shape(self.tops.d2[-1])
        change = max(change, self.face.update(self.form.nonlinear.velocity))
        self.face.displace(self.disp)
        self.mesh.SetDeformation(self.disp)
        # the strain along the new flow on the new shape (its change over the largest)
        strained = max(0.0 if field is None
                       else field.transport(self.form.nonlinear.velocity)
                       for field in (self.strain, self.cooling))
        if progress is not None:
            progress({"stage": "spread", "spread_round": self.rounds, "message": (
                f"3D pass round {self.rounds} ({self.form.fes.ndof} unknowns) at a Newton "
                f"update of {update:.3g} of the roll speed: the free surfaces moved "
                f"{change / self.problem.h:.3g} h (tolerance {s.surface_tol:g} h)"
                + ("" if self.ends is None else
                   ", the contact's ends wait for a tighter flow" if math.isinf(ended)
                   else f", the contact's ends moved {ended / self.problem.h:.3g} h "
                   f"(tolerance {self.ends.tol / self.problem.h:.3g} h)")
                + ("" if self.strain is None and self.cooling is None else
                   f", the carried fields changed {strained:.3g} (tolerance "
                   f"{s.strain_rtol:g})"))})
        return (change <= tol_face and strained <= s.strain_rtol
                and (self.ends is None or ended <= self.ends.tol))

    def figures(self) -> dict:
        """The pass's figures (SI, per roll and the whole strip; ``zone_cut``: an edge zone's
        cut, m from mid-width, or 0): roll force (N) and per
        width (N/m of the stock's width), roll torque (N m), the exit's mean half width and
        the spread (m), the exit half width over the thickness (m, at 40 equal steps of
        y / exit half thickness from the mid-plane), the mass fluxes through the cut faces and
        the lateral face (m^3/s of the quarter), the mean exit speed (m/s: the outlet's flux
        over its area) and the forward slip from it, Newton iterations, rounds, DOFs, wall
        time (s)."""
        import ngsolve as ng

        f, mesh, K = self.form, self.mesh, self.problem.material.K
        u = f.nonlinear.velocity
        n, t = f.roll_frame()
        s = f.slip(u)
        kf = f.friction_coefficient(u)
        arc = mesh.Boundaries("arc")
        force_y = (integrate(f.pressure(u) * n[1], mesh, ng.BND, definedon=arc)
                   + f.integrate_friction(f.chi * kf * s[1]))
        cx, cy = f.rp.centre
        r = ng.sqrt((ng.x - cx) ** 2 + (ng.y - cy) ** 2)
        torque = f.integrate_friction(f.chi * (-kf * (s * t)) * r)
        nn = ng.specialcf.normal(3)
        flux = {b: float(integrate(u * nn, mesh, ng.BND, definedon=mesh.Boundaries(b)))
                for b in ("in", "out", "edge")}
        b0 = float(self.z[-1])
        out = {"roll_force": 2.0 * K * force_y, "roll_torque": 2.0 * K * torque,
               "stock_half_width": b0, "zone_cut": float(self.cut),
               "flux_in": -flux["in"], "flux_out": flux["out"], "flux_edge": flux["edge"],
               "rounds": self.rounds,
               "newton_iterations": self.iterations, "dofs": f.fes.ndof,
               "factorisations": self.factorisations, "reused": self.reused,
               "wall_time": self.setup_time + self.solve_time, "settled": self.settled,
               "failure": self.failure}
        out["roll_force_per_width"] = out["roll_force"] / (2.0 * b0)
        # the mean exit speed: the outlet's flux over its area projected on x (the 2D pass's
        # face_flow across the width), the forward slip of the whole strip from it
        area = float(integrate(nn[0], mesh, ng.BND, definedon=mesh.Boundaries("out")))
        out["exit_velocity"] = out["flux_out"] / area
        out["forward_slip"] = out["exit_velocity"] / self.problem.rp.u_roll - 1.0
        out.update(self.power_balance(K * torque))
        out.update(self.midplane_deviation())
        if self.face is not None:
            # at the outlet, over the reference cross-section's heights: the strip there is
            # flat and x stays (the strip map moves neither past its exit anchor), its
            # heights the reference's times one factor, so the mean is the physical one
            x_out = max(v.point[0] for v in mesh.vertices)
            y = np.linspace(0.0, self.problem.rp.half_exit, 41)[:-1] + 0.5 * (
                self.problem.rp.half_exit / 40.0)
            half = self.face.half_width(x_out - 1e-9 * abs(x_out) - 1e-12, y)
            out["exit_half_width"] = float(np.mean(half))
            out["exit_half_width_profile"] = half.tolist()
            out["spread"] = 2.0 * (out["exit_half_width"] - b0)
        return out

    def power_balance(self, torque: float) -> dict:
        """``solvers/spread_checks.power_balance`` of this pass (the quarter's ``torque``, N m)."""
        return spread_checks.power_balance(self, torque)

    def midplane_deviation(self) -> dict:
        """``solvers/spread_checks.midplane_deviation`` of this pass."""
        return spread_checks.midplane_deviation(self)


def _offset(entry_temperature, half_width: float):
    """theta(x, y, z) at the inlet's vertices (K): the entry temperature less mid-width's at
    the same height, from a ``SectionProfile`` (eta = y / the inlet's half thickness) or a
    profile across the width alone (a function of zeta)."""
    if hasattr(entry_temperature, "offset"):
        return lambda x, y, z: entry_temperature.offset(y / y.max(), z / half_width)
    mid = float(entry_temperature(0.0))
    return lambda x, y, z: entry_temperature(z / half_width) - mid
