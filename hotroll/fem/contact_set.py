"""Unilateral roll contact: the primal-dual active set on the arc's P1 multiplier nodes.

The strip may leave the roll where holding it would need a tensile contact stress. With the
multiplier lambda (the pressure, >= 0) and the weighted normal velocity g_j = int phi_j u.n ds
(u.n > 0 into the roll), the Signorini conditions g_j <= 0, lambda_j >= 0, lambda_j g_j = 0 are
the root of the complementarity function lambda_j - max(0, lambda_j + c g_j / m_j) (m_j =
int phi_j ds, c > 0 any constant). Newton on it is the primal-dual active set strategy
(Hintermueller, Ito & Kunisch 2002; Hueeber, Stadler & Wohlmuth 2008 for contact): a node is
active where lambda_j + c g_j / m_j > 0, and then its constraint g_j = 0 holds; elsewhere
lambda_j = 0 and the strip there is a free surface (no constraint, no friction). The set is
updated between Newton steps until it no longer changes; a_f and the free tops are updated
with it (``solvers/steady.py``). docs/theory.md 1e.

In the form's scaled multiplier (lambda~ = p / s, a velocity), c / s = c0 l_c / h with c0 = 1:
the rule has no units.
"""
from __future__ import annotations

import numpy as np


class ActiveSet:
    """The contact's active multiplier nodes and their update."""

    def __init__(self, form, c0: float = 1.0, max_changes: int = 40):
        self.form = form
        verts, dofs = form.multiplier_vertices()
        self.vertices = verts                                  # mesh vertex numbers
        self.dofs = form.nonlinear.multiplier_range().start + dofs   # in the product vector
        self.active = np.ones(len(dofs), dtype=bool)
        self.c = c0 * form.rp.contact_length / form.penalties.h
        self.changes = 0
        self.max_changes = max_changes      # beyond: the set is frozen, reported
        self.seen: set[bytes] = set()
        self.cycled = False

    @property
    def frozen(self) -> bool:
        return self.cycled or self.changes >= self.max_changes

    def reset(self) -> None:
        """All nodes active (the bilateral start)."""
        self._apply(np.ones(len(self.dofs), dtype=bool))
        self.changes, self.cycled = 0, False
        self.seen = {self.active.tobytes()}

    def weights(self) -> np.ndarray:
        """m_j = int phi_j ds over the arc (current geometry)."""
        from ngsolve import LinearForm, ds

        L = self.form.fes.components[2]
        xi = L.TestFunction()
        f = LinearForm(L)
        f += xi * ds("arc")
        f.Assemble()
        _, local = self.form.multiplier_vertices()
        return f.vec.FV().NumPy()[local].copy()

    def normal_velocity(self) -> np.ndarray:
        """g_j / m_j: the weighted normal velocity at each node (m/s, > 0 into the roll), read
        from the constraint rows of the residual (s int phi_j u.n)."""
        problem = self.form.nonlinear
        r = problem.gf.vec.CreateVector()
        problem.a_newton.Apply(problem.gf.vec, r)
        g = r.FV().NumPy()[self.dofs] / self.form.lam_scale
        return g / self.weights()

    def update(self) -> bool:
        """One active-set update at the current iterate; True if the set changed."""
        if self.frozen:
            return False
        lam = self.form.nonlinear.gf.vec.FV().NumPy()[self.dofs]
        new = lam + self.c * self.normal_velocity() > 0.0
        if not new.any():        # no contact at all is not a rolling pass: keep the old set
            return False
        if np.array_equal(new, self.active):
            return False
        if new.tobytes() in self.seen:
            # a cycle: the contact's end lies between two nodes that take turns. Keep the
            # intersection of the two sets (the shorter contact: no tensile pressure, the end
            # within one node of the exact one) and stop updating
            self.cycled = True
            new = new & self.active
            if np.array_equal(new, self.active):
                return False
        self.seen.add(new.tobytes())
        self.changes += 1
        self._apply(new)
        return True

    def _apply(self, active: np.ndarray) -> None:
        problem = self.form.nonlinear
        vec = problem.gf.vec.FV().NumPy()
        vec[self.dofs[~active]] = 0.0
        problem.set_free(self.dofs[active], True)
        problem.set_free(self.dofs[~active], False)
        self.active = active.copy()

    def active_vertices(self) -> np.ndarray:
        return self.vertices[self.active]
