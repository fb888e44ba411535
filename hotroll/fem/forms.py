"""Generic weak-form machinery shared by the rolling problem and the analytic checks.

A problem is written once as ``integrand(u, p, w, v, q)``: ``u, p`` the trial velocity and
pressure, ``w`` the velocity at which nonlinear coefficients are evaluated, ``v, q`` the tests.
A space with a third component (the contact multiplier on the roll arc) passes its trial and test
functions as two more arguments, ``integrand(u, p, w, v, q, lam, xi)`` (Newton only).
Newton uses w = u (exact linearisation by NGSolve); Picard (3.8) uses w = the previous iterate, so
the Picard matrix J(U^i) is the linearisation of the frozen form and the Picard step is
U^{i+1} = U^i - J(U^i)^{-1} r(U^i). One code path, two algorithms.

Newton's Jacobian is also kept as a form of its own, linear in the trial functions with its
coefficients at the iterate, so that it assembles as a plain bilinear form: by default the
residual integrand at the iterate differentiated symbolically (``CoefficientFunction.Diff``), or
a hand-written tangent (``norton_hoff_tangent`` for the volume term: 0.036 s against 0.063 s with
``AssembleLinearization`` per assembly on Example 1, C2). Both are the same matrix as
``AssembleLinearization`` to rounding (tested).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Callable

from hotroll.fem.spaces import P2Nodes
from hotroll.model.material import NortonHoff, edot_squared


def strain_rate(u):
    """eps_dot(u) = sym grad u, (2.4)."""
    from ngsolve import Grad, Sym

    return Sym(Grad(u))


def one_sided(f_u, f_w):
    """[f]_+ with the active set taken at w (Picard) or at u itself (Newton: f_w is f_u)."""
    from ngsolve import IfPos

    return IfPos(f_w, f_u, 0.0)


def norton_hoff_volume(material: NortonHoff, m, u, p, w, v, q, K=1.0):
    """Volume part of (2.24)/(3.6): int s(u):eps(v) - p div v - q div u."""
    from ngsolve import InnerProduct, div

    mu = material.viscosity(edot_squared(strain_rate(w)), m=m, K=K)
    return mu * InnerProduct(strain_rate(u), strain_rate(v)) - p * div(v) - q * div(u)


def norton_hoff_tangent(material: NortonHoff, m, w, u, p, v, q, K=1.0):
    """Newton's Jacobian of ``norton_hoff_volume`` at w along (u, p): with mu(edot^2) of (2.21),
    mu [eps(u):eps(v) + (m-1) (2/3) (eps(w):eps(u)) (eps(w):eps(v)) / (eps0^2 + edot(w)^2)]
    - p div v - q div u (the primal tangent; the primal-dual one, with nu in one factor of
    the rank-one term, is ``fem/primal_dual.py: TangentPoints.tangent``)."""
    from ngsolve import InnerProduct, div

    ew, eu, ev = strain_rate(w), strain_rate(u), strain_rate(v)
    e2 = edot_squared(ew)
    mu = material.viscosity(e2, m=m, K=K)
    rank = InnerProduct(ew, eu) * InnerProduct(ew, ev) / (material.eps0**2 + e2)
    return (mu * (InnerProduct(eu, ev) + (m - 1.0) * (2.0 / 3.0) * rank)
            - p * div(v) - q * div(u))


# The Newton and Picard matrices are symmetric (every term derives from a convex potential), so
# NGSolve's sparse LDL^T ("sparsecholesky", no pivoting) factorises the saddle-point system;
# measured 16x faster than UMFPACK here, whose pivoting slows down on the wide viscosity range,
# and faster than MKL PARDISO (present only with ``pip install mkl``; 25k DOFs, 2 threads:
# refactorisation 0.13 s vs 0.18 s, UMFPACK 0.8 s). The next solver is the fallback when one
# is missing, fails, or its solution is inaccurate. The factorisation is kept between
# iterations and steps: the sparsity pattern never changes, so ``Update()`` refactorises the
# new values with the old ordering.
# Where the Jacobian is not symmetric (Coulomb's pressure dependence, the one-sided boundary
# terms) LDL^T alone misses the accuracy test: it is GMRES's preconditioner (fem/krylov.py: 11
# against 24 ms for UMFPACK on a thermal finishing pass; on a symmetric Jacobian GMRES stops
# after one iteration). First, so that a non-symmetric pass factorises once: finishing_mill
# 0.2 s faster than with the plain LDL^T tried first, Example 1 the same within the noise.
# Issue 50: UMFPACK first, the only one whose factors are the same in every run and at any
# thread count: NGSolve's LDL^T merges its blocks under locks in the order the threads reach
# them, and with no task manager it starts one of its own with every core (a Taylor-Hood Stokes
# matrix: 8 distinct solutions of 8 factorisations with 2 threads or none, 1 of 8 in a 1-thread
# task manager); their noise made the ten stands' F10 take 15 or 17 Newton steps. UMFPACK's
# refactorisation and solve there: 22 ms against LDL^T's 6 ms (2 threads); kept as GMRES's
# preconditioner across Newton steps instead, its factors took 4-12 iterations of 2.8 ms (its
# solve) on 22 of 42 changed Jacobians and missed 12 on the other 20: slower than factorising.
# Whole passes: docs/validation/speed.md "Issue 50". The other remains a fallback (a run that
# needs it is not reproducible to the bit). MKL PARDISO is not in the list (issue 53): only
# there with ``pip install mkl``, 1.13x UMFPACK on the 3D roughing pass held to one thread,
# and NGSolve 6.2.2608's wrapper crashes when it refactorises with fewer MKL threads than it
# analysed with, which the parallel regions' per-step thread count allows
# (docs/validation/spread_3d.md, "The roughing pass").
LINEAR_SOLVERS = ("umfpack", "sparsecholesky+gmres")


@dataclass
class NonlinearProblem:
    """A mixed velocity-pressure problem with its Newton and Picard forms.

    ``integrand(u, p, w, v, q)`` returns an NGSolve SumOfIntegrals. ``velocity_scale`` makes the
    stopping test ``max|du| <= tol * velocity_scale`` independent of units; |du| is taken at
    the velocity nodes (vertices and edge midpoints for P2), not over the coefficients. ``jacobian(w, u, p,
    v, q)`` (optional) returns Newton's Jacobian at the velocity w, linear in (u, p); without it
    the residual integrand is differentiated symbolically.
    """

    fes: object
    integrand: Callable
    velocity_scale: float = 1.0
    jacobian: Callable | None = None
    #: the multiplier's stopping test: max |d lambda| <= multiplier_tol * velocity_scale (the
    #: rolling form scales lambda so that the reference stress is the roll speed)
    multiplier_tol: float = 1e-4
    #: weight of the pressure rows in the residual norm (a viscosity; ``nonlinear._Workspace``)
    pressure_row_scale: float = 1.0
    #: the largest forcing term of the inexact Newton (``fem/nonlinear.py``): a direction's
    #: relative residual
    linear_rtol: float = 1e-2
    #: GMRES iterations a Newton direction may take on the kept factors of an earlier
    #: Jacobian before they are refactorised (``fem/nonlinear.py``; 0: refactorised every step)
    reuse_steps: int = 0
    #: the velocity's place in the unknowns (``amg.VelocityLayout``), for the AMG solver
    layout: object = None
    gf: object = field(init=False)
    gf_w: object = field(init=False)
    a_newton: object = field(init=False)
    a_picard: object = field(init=False)
    a_jacobian: object = field(init=False)
    inverses: dict = field(init=False, default_factory=dict, repr=False)  # kept factorisations
    linear_solvers: tuple = field(init=False, default=LINEAR_SOLVERS, repr=False)

    def __post_init__(self):
        from ngsolve import BilinearForm, GridFunction

        self.gf = GridFunction(self.fes)
        self.gf_w = GridFunction(self.fes)
        trial, test = self.fes.TnT()
        (u, p, *lam), (v, q, *xi) = trial, test
        w_frozen = self.gf_w.components[0]
        self.a_newton = BilinearForm(self.fes)
        self.a_newton += self.integrand(u, p, u, v, q, *lam, *xi).Compile()
        self.a_picard = None
        if not lam:      # Picard freezes the velocity; a multiplier problem is Newton only
            self.a_picard = BilinearForm(self.fes)
            self.a_picard += self.integrand(u, p, w_frozen, v, q).Compile()
        # Newton's Jacobian at gf along (u, p[, lam])
        gu, gp, *glam = self.gf.components
        if self.jacobian is not None:
            extra = dict(lam_w=glam[0]) if glam else {}   # the multiplier at the iterate
            tangent = self.jacobian(gu, u, p, v, q, *lam, *xi, **extra)
        else:
            residual = self.integrand(gu, gp, gu, v, q, *glam, *xi)
            tangent = residual.Diff(gu, u) + residual.Diff(gp, p)
            for g, t in zip(glam, lam):
                tangent = tangent + residual.Diff(g, t)
        self.a_jacobian = BilinearForm(self.fes)
        self.a_jacobian += tangent.Compile()
        self._freedofs = self.fes.FreeDofs()

    @property
    def freedofs(self):
        return self._freedofs

    def set_free(self, dofs, free: bool) -> bool:
        """Free or fix (value kept by the caller) the DOFs ``dofs`` (an active set: fixed
        multipliers are 0); True if that changed the free set. The kept factorisations then
        cover another matrix and are dropped."""
        from ngsolve import BitArray

        changed = [int(d) for d in dofs if self._freedofs[int(d)] != free]
        if not changed:
            return False
        fd = BitArray(self._freedofs)
        for d in changed:
            fd[d] = free
        self._freedofs = fd
        self.inverses.clear()
        self.__dict__.pop("free_mask", None)
        self.__dict__.pop("free_velocity_mask", None)
        return True

    def fix_dirichlet(self) -> None:
        """The velocity's Dirichlet DOFs (v_y = 0 on the symmetry line, the full strip's
        inlet) set to their value 0: Newton keeps them as they are, and a start interpolated
        by ``Set`` (an element-wise projection) carries its error there (2e-4 U on Case R's
        symmetry line, which then held the half strip off its symmetry: 6e-5 in its force)."""
        n = self.n_velocity_dofs()
        vec = self.gf.vec.FV().NumPy()
        vec[:n][~self.free_mask[:n]] = 0.0

    @property
    def has_multiplier(self) -> bool:
        return len(self.fes.components) > 2

    def multiplier_range(self) -> slice:
        """The multiplier's DOFs in the product vector (empty without one)."""
        if not self.has_multiplier:
            n = self.fes.ndof
            return slice(n, n)
        r = self.fes.Range(2)
        return slice(r.start, r.stop)

    def pressure_range(self) -> slice:
        r = self.fes.Range(1)
        return slice(r.start, r.stop)

    @property
    def velocity(self):
        return self.gf.components[0]

    @property
    def pressure(self):
        return self.gf.components[1]

    def n_velocity_dofs(self) -> int:
        return self.fes.components[0].ndof

    @cached_property
    def free_mask(self):
        """Boolean numpy mask of the free DOFs (Dirichlet rows excluded)."""
        import numpy as np

        return np.array(list(self.freedofs), dtype=bool)

    def max_nodal_velocity(self, vec) -> float:
        """max |v| over the velocity nodes of the coefficient vector ``vec`` (free DOFs only)."""
        import numpy as np

        a = np.where(self.free_velocity_mask, vec.FV().NumPy(), 0.0)
        nodes = self._velocity_nodes
        vals = nodes.values(a) if nodes is not None else a[: self.n_velocity_dofs()]
        return float(np.max(np.abs(vals))) if vals.size else 0.0

    def max_multiplier(self, vec) -> float:
        """max |lambda| over the free multiplier DOFs of ``vec`` (0 without a multiplier); the
        problems that have one scale it to a velocity (``RollingForm``)."""
        import numpy as np

        r = self.multiplier_range()
        lam = vec.FV().NumPy()[r][self.free_mask[r]]
        return float(np.max(np.abs(lam))) if lam.size else 0.0

    @property
    def p2_nodes(self) -> P2Nodes:
        """The velocity's P2 nodes (vertices, edge midpoints) and nodal values."""
        if self._velocity_nodes is None:
            raise ValueError("the velocity space is not P2")
        return self._velocity_nodes

    @cached_property
    def _velocity_nodes(self):
        try:
            return P2Nodes(self.fes.mesh, self.n_velocity_dofs() // 2)
        except ValueError:     # not P2: the coefficients are the nodal values (P1)
            return None

    @cached_property
    def free_velocity_mask(self):
        mask = self.free_mask.copy()
        mask[self.n_velocity_dofs():] = False
        return mask
