"""The primal-dual Newton tangents of the Norton-Hoff law and of the friction laws (Chan, Golub
& Mulet 1999, their method for total variation, the m -> 0 limit of these laws; docs/theory.md
3.2b).

The law s = mu(E) eps, E^2 = eps0^2 + 2/3 eps:eps, mu ~ E^(m-1) (2.21), is written with its
dual nu = eps / E ((2/3) nu:nu < 1) as s = mu E nu and nu E - eps = 0. Newton on the pair,
nu eliminated, has the primal residual and the primal tangent with one factor eps/E of its
rank-one term replaced by nu (``TangentPoints.tangent``; the primal one is
``forms.norton_hoff_tangent``), symmetrised so that the LDL^T factorisation stays usable:

    mu [eps(du):eps(v) + (m-1) (2/3) ((eps:eps(du)) (nu:eps(v)) + (nu:eps(du)) (eps:eps(v))) / (2E)]

and nu moves by the linearised nu E - eps = 0 along each step du taken,

    nu+ = (eps + eps(du)) / E - nu (2/3) (eps:eps(du)) / E^2,

held inside (2/3) nu:nu <= 1. Only the Jacobian reads nu: the residual, and so every converged
solution, is the primal one. At a converged iterate nu = eps/E and the tangent is Newton's.
Where the strain rate passes through eps0 (the near-rigid zones at the bite's entry and exit,
eps0 = 1e-4 1/s against 1-100 1/s in the bite) the primal tangent's stiffness changes by a
factor 1/m within a step and its full steps overshoot; nu keeps the last step's memory there
(docs/validation/speed.md, issue 34 session 5).

nu lives at the quadrature points of the volume integrals (an ``IntegrationRuleSpace``): the
residual's and the Jacobian's volume terms are integrated on the same points (``intrules``).

The friction laws are the same power law in the slip s (a scalar along the roll's tangent),
T = -k_f(s^2) s with k_f ~ S^(q-1), S^2 = s^2 + v_reg^2 (q = m viscoplastic, q = 0 Coulomb and
Tresca: ``model/friction/base.py``). Where the slip passes through v_reg (the neutral point,
which moves from one iterate to the next) Newton's tangent k_f (1 + (q-1) s^2/S^2) changes by
1/q within a step. ``FrictionDual`` keeps z ~ s/S (|z| <= 1) with the same update,

    z+ = (s + ds) / S - z s ds / S^2,

and the tangent k_f (1 + (q-1) z s / S) (its other terms, the pressure's and k's, as
Newton's). z is stored as its departure d = z - s/S from the primal value, a P2 field on the
top (a projection; z itself has a kink at the neutral point that a P2 field would round): d
is the linearisation's error, of the order of the step squared, so it vanishes as Newton
converges and the tangent becomes Newton's: the last steps converge quadratically (a stored z
projected onto P2 converged linearly: 24 against 10 iterations, docs/validation/speed.md,
issue 34 session 6).
"""
from __future__ import annotations

from hotroll.fem.reproducible import fe_space


def symmetric_components(dim: int) -> list[tuple[int, int]]:
    """The stored components (i, j), i <= j, of a symmetric dim x dim tensor: xx, xy, yy in
    2D; xx, xy, xz, yy, yz, zz in 3D."""
    return [(i, j) for i in range(dim) for j in range(i, dim)]


def symmetric_tensor(values, dim: int):
    """The dim x dim CF of the stored components ``values`` (``symmetric_components``)."""
    from ngsolve import CF

    index = {ij: k for k, ij in enumerate(symmetric_components(dim))}
    return CF(tuple(values[index[(min(i, j), max(i, j))]] for i in range(dim) for j in range(dim)),
              dims=(dim, dim))


#: order of the ``IntegrationRuleSpace``: its rule (6 points on a triangle, exact to order 4)
#: is the one NGSolve picks by default for the P2-P1 forms (P2 trial x P2 test), so the
#: residual is the same as with plain ``dx`` (tests/fem/test_primal_dual.py)
ORDER = 2


class NortonHoffDual:
    """nu at the quadrature points of ``mesh``; ``prepare(iteration)`` is the flow's Newton
    hook (``nonlinear.newton``): nu = eps/E at the first iterate, then the update above."""

    def __init__(self, mesh, eps0: float):
        from ngsolve import GridFunction
        from ngsolve.comp import IntegrationRuleSpace

        self.space = space = fe_space(IntegrationRuleSpace, mesh, order=ORDER)
        self.intrules = space.GetIntegrationRules()
        self.eps0 = eps0
        self.dim = dim = mesh.dim
        n = len(symmetric_components(dim))
        self.gf, self._next = GridFunction(space**n), GridFunction(space**n)
        g = self.gf
        #: nu as a dim x dim tensor (symmetric: ``symmetric_components`` stored)
        self.cf = symmetric_tensor([g[k] for k in range(n)], dim)
        self.velocity = self._previous = self._primal = self._step = None

    def attach(self, velocity) -> None:
        """The iterate's velocity (a GridFunction component) whose steps nu follows."""
        from ngsolve import CF, GridFunction, IfPos, InnerProduct, sqrt

        from hotroll.fem.forms import strain_rate
        from hotroll.model.material import edot_squared

        def stored(t):
            norm = sqrt(2.0 / 3.0 * InnerProduct(t, t))
            t = t / IfPos(norm - 1.0, norm, 1.0)        # held inside (2/3) nu:nu <= 1
            return CF(tuple(t[i, j] for i, j in symmetric_components(self.dim))).Compile()

        self.velocity = velocity
        self._previous = GridFunction(velocity.space)
        e, ep = strain_rate(velocity), strain_rate(self._previous)
        eps0 = self.eps0
        E2p = eps0**2 + edot_squared(ep)
        self._primal = stored(e / sqrt(eps0**2 + edot_squared(e)))
        self._step = stored(e / sqrt(E2p) - self.cf * ((2.0 / 3.0) * InnerProduct(ep, e - ep)
                                                       / E2p))

    def prepare(self, iteration: int) -> bool:
        """nu for the Jacobian at the current iterate; False: the residual is unchanged."""
        self._next.Interpolate(self._primal if iteration == 1 else self._step)
        self.gf.vec.data = self._next.vec
        self._previous.vec.data = self.velocity.vec
        return False


class TangentPoints:
    """The Norton-Hoff tangent's coefficients at the quadrature points of the dual's rule:
    mu, mu (m - 1) 2/3 and a = eps(w)/E, interpolated once per Newton iteration (``prepare``).
    The Jacobian then reads five numbers a point (``tangent``) where the symbolic form
    evaluated the law (K(eps, T), m(T), E) for every pair of trial and test components: a
    thermo-mechanical pass's assembly 36 -> 9 ms on 2 threads, Example 1's 39 -> 17 ms, the
    matrix equal to rounding (4e-12; issue 34 session 7)."""

    def __init__(self, space, dim: int = 2):
        """``space``: the dual's ``IntegrationRuleSpace`` (its points are the integrals');
        ``dim``: the mesh's."""
        from ngsolve import GridFunction

        self.dim = dim
        self.gf = GridFunction(space**(2 + len(symmetric_components(dim))))
        self._cf = None

    def attach(self, material, m, velocity, K) -> None:
        """The law (reduced ``material``, rate exponent ``m``, consistency ``K``: numbers or
        CFs) at the iterate's ``velocity``."""
        from ngsolve import CF, sqrt

        from hotroll.fem.forms import strain_rate
        from hotroll.model.material import edot_squared

        ew = strain_rate(velocity)
        e2 = edot_squared(ew)
        mu = material.viscosity(e2, m=m, K=K)
        a = ew / sqrt(material.eps0**2 + e2)
        self._cf = CF((mu, mu * (m - 1.0) * (2.0 / 3.0),
                       *(a[i, j] for i, j in symmetric_components(self.dim)))).Compile()

    def prepare(self) -> None:
        self.gf.Interpolate(self._cf)

    def tangent(self, u, p, v, q, dual):
        """The primal-dual tangent (module docstring) at the interpolated coefficients (the
        dual's nu: ``dual``)."""
        from ngsolve import InnerProduct, div

        from hotroll.fem.forms import strain_rate

        g = self.gf
        a = symmetric_tensor([g[2 + k] for k in range(len(symmetric_components(self.dim)))],
                             self.dim)
        eu, ev = strain_rate(u), strain_rate(v)
        rank = 0.5 * (InnerProduct(a, eu) * InnerProduct(dual, ev)
                      + InnerProduct(dual, eu) * InnerProduct(a, ev))
        return g[0] * InnerProduct(eu, ev) + g[1] * rank - p * div(v) - q * div(u)


class FrictionDual:
    """z = s/S + d of the friction's slip on the top boundaries ``region`` of ``mesh`` (module
    docstring); ``prepare(iteration)`` is the flow's Newton hook: d = 0 at the first iterate
    (z the primal value) and after a ``restart``, then the update above."""

    def __init__(self, mesh, region: str):
        from ngsolve import H1, GridFunction, VectorH1

        self.region = mesh.Boundaries(region)
        #: a 3D strip's slip is a vector in the roll's tangent plane, and so is z (issue 53)
        self.vector = mesh.dim == 3
        space = fe_space(VectorH1 if self.vector else H1, mesh, order=2)
        self.d, self._next = GridFunction(space), GridFunction(space)
        self.velocity = self._previous = self._step = None
        self._restart = False

    def restart(self) -> None:
        """The form's data changed (a coupling update: the mesh, the roll, the speed): the
        slip's change to the next iterate is not a Newton step to follow, and d starts again
        at 0 there (on finishing_mill's warm passes 51 Newton iterations against 55 without
        the restart and 53 with Newton's friction tangent; speed.md, session 6)."""
        self._restart = True

    def z(self, slip, v_reg):
        """z at the iterate whose slip is the CF ``slip``, held inside |z| <= 1."""
        from ngsolve import sqrt

        return self._capped(slip / sqrt(slip * slip + v_reg * v_reg) + self.d)

    def attach(self, velocity, slip, v_reg) -> None:
        """The iterate's velocity (a GridFunction component), the slip of a velocity
        (``slip(u)``, a CF) and v_reg (m/s, a Parameter or a number)."""
        from ngsolve import GridFunction, sqrt

        self.velocity = velocity
        self._previous = GridFunction(velocity.space)
        s, sp = slip(velocity), slip(self._previous)
        Sp2 = sp * sp + v_reg * v_reg
        if self.vector:        # z+ = (s + ds)/S - z (s.ds)/S^2, ds = s - sp
            z_next = s / sqrt(Sp2) - self.z(sp, v_reg) * ((sp * (s - sp)) / Sp2)
        else:
            z_next = (s / sqrt(Sp2) - self.z(sp, v_reg) * sp * (s - sp) / Sp2)
        self._step = (self._capped(z_next) - s / sqrt(s * s + v_reg * v_reg)).Compile()

    def _capped(self, z):
        from ngsolve import IfPos, sqrt

        size = sqrt(z * z) if self.vector else IfPos(z, z, -z)
        return z / IfPos(size - 1.0, size, 1.0)

    def prepare(self, iteration: int) -> bool:
        """d for the Jacobian at the current iterate; False: the residual is unchanged."""
        from ngsolve import BND

        if iteration == 1 or self._restart:
            self._restart = False
            self._next.vec[:] = 0.0
        else:
            self._next.Set(self._step, BND, definedon=self.region)
        self.d.vec.data = self._next.vec
        self._previous.vec.data = self.velocity.vec
        return False
