"""The primal-dual Newton tangent of the Norton-Hoff law (Chan, Golub & Mulet 1999, their
method for total variation, the m -> 0 limit of this law; docs/theory.md 3.2b).

The law s = mu(E) eps, E^2 = eps0^2 + 2/3 eps:eps, mu ~ E^(m-1) (2.21), is written with its
dual nu = eps / E ((2/3) nu:nu < 1) as s = mu E nu and nu E - eps = 0. Newton on the pair,
nu eliminated, has the primal residual and the primal tangent with one factor eps/E of its
rank-one term replaced by nu (``forms.norton_hoff_tangent``, symmetrised so that the LDL^T
factorisation stays usable):

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
"""
from __future__ import annotations

#: order of the ``IntegrationRuleSpace``: its rule (6 points on a triangle, exact to order 4)
#: is the one NGSolve picks by default for the P2-P1 forms (P2 trial x P2 test), so the
#: residual is the same as with plain ``dx`` (tests/fem/test_primal_dual.py)
ORDER = 2


class NortonHoffDual:
    """nu at the quadrature points of ``mesh``; ``prepare(iteration)`` is the flow's Newton
    hook (``nonlinear.newton``): nu = eps/E at the first iterate, then the update above."""

    def __init__(self, mesh, eps0: float):
        from ngsolve import CF, GridFunction
        from ngsolve.comp import IntegrationRuleSpace

        space = IntegrationRuleSpace(mesh, order=ORDER)
        self.intrules = space.GetIntegrationRules()
        self.eps0 = eps0
        self.gf, self._next = GridFunction(space**3), GridFunction(space**3)
        g = self.gf
        #: nu as a 2x2 tensor (symmetric: xx, xy, yy stored)
        self.cf = CF((g[0], g[1], g[1], g[2]), dims=(2, 2))
        self.velocity = self._previous = self._primal = self._step = None

    def attach(self, velocity) -> None:
        """The iterate's velocity (a GridFunction component) whose steps nu follows."""
        from ngsolve import CF, GridFunction, IfPos, InnerProduct, sqrt

        from hotroll.fem.forms import strain_rate
        from hotroll.model.material import edot_squared

        def stored(t):
            norm = sqrt(2.0 / 3.0 * InnerProduct(t, t))
            t = t / IfPos(norm - 1.0, norm, 1.0)        # held inside (2/3) nu:nu <= 1
            return CF((t[0, 0], t[0, 1], t[1, 1])).Compile()

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
