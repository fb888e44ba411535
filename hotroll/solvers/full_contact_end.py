"""The contact ends of the full strip between two rolls (issue 52): each side's end searched
by its own ``ContactEndSearch`` on its own roll, with the strip's elasticity past its gap
through that roll's Winkler layer (docs/theory.md 1e), the multiplier carried with each end's
moves; the half model's ``ContactEndMixin`` (solvers/contact_end.py) per side. A mixin of
``FullSteadyRun`` (solvers/full_steady.py), which holds the rolls, shapes, tops, map and
form these methods use."""
from __future__ import annotations

import numpy as np

from hotroll.solvers.contact_end import PAST_GAP, carried_pressure, move_end, surface_overlap, winkler_end
from hotroll.solvers.couplings import ContactEnd

#: the traced free surface after a contact's end may lie inside its roll by this many of the
#: traced tops' tolerance (surface_tol h) before the end moves on to where it leaves the roll:
#: a few times the surface's own noise, not a margin (at 10, asymmetric_plate at a speed
#: ratio of 1.1 on the mesh refined at the contact's start settled 24.95 um, 0.998 of the
#: threshold, inside its slower roll without the wrap, its force 7 % below the wrapped
#: state's; at 3 it wraps cold and warm on both meshes; r = 1.05 ends 2 um inside, unwrapped)
OVERLAP_TOL = 3.0
#: how far past its gap a strip that curls onto a roll may follow it, in contact lengths: the
#: mesh's exit zone is at least one contact length, and the strip must leave the roll well
#: before the outlet (at most a quarter of the exit zone: ``StripMap.end_bounds``;
#: docs/theory.md 1e, "wrap")
PAST_GAP_WRAP = 0.5


class FullContactEndMixin:
    """The two contact ends of ``FullSteadyRun``."""

    def side_end_bounds(self, side: int) -> tuple[float, float]:
        """The contact end's range on ``side`` (``ContactEndMixin.end_bounds``: past the gap
        for an elastic strip)."""
        past = (PAST_GAP_WRAP if side in self.wraps else
                PAST_GAP if self.form.compliance else 0.0)
        return self.map.end_bounds(side, past)

    def side_overlap(self, side: int) -> tuple[float, float | None]:
        """``overlap_after`` of the free surface after the contact's end on ``side``."""
        rp = self.rolls[side]
        return surface_overlap(self.tops[side], self.d, rp, self.shapes[side].end(rp),
                               OVERLAP_TOL * self.s.surface_tol * self.problem.h)

    def _predict_ends(self) -> None:
        """An elastic strip's contact ends to start from, each where its Winkler layer at 2k
        meets its roll (``ContactEndMixin._predict_end``)."""
        if not (self.unilateral and self.form.compliance):
            return
        pb = self.problem
        for s, rp in self.rolls.items():
            lo, hi = self.side_end_bounds(s)
            layer = self._layer(s)
            self._set_side_end(s, float(np.clip(
                winkler_end(rp, layer, rp.axis_x, pb.mean_two_k / pb.material.K), lo, hi)))

    def _layer(self, side: int):
        """The elastic layer's c_e(y) in the contact of the roll on ``side``."""
        return lambda y: self.form.layer_compliance(y, side)

    def _set_side_end(self, side: int, new: float) -> None:
        """The contact's end on ``side`` at ``new`` (``move_end``), the mesh mapped onto it."""
        move_end(self.shapes[side], self.rolls[side], new)
        self._set_shape()

    def end_tolerance(self, side: int) -> float:
        """The contact end's tolerance on ``side`` (m): 1e-2 h where its pressure falls
        smoothly to zero at the end (an elastic strip, or one that curls onto the roll past
        its gap: ``ContactEnd.TOLERANCE_ELASTIC``), else 1e-3 h."""
        smooth = self.form.compliance or side in self.wraps
        return ((ContactEnd.TOLERANCE_ELASTIC if smooth else ContactEnd.TOLERANCE)
                * self.s.surface_tol * self.problem.h)

    def move_contact_end(self) -> float:
        """Each side's contact end by its own search (``ContactEndMixin.move_contact_end``:
        with the strip's elasticity past the gap, seen through its Winkler layer, the
        multiplier carried with the end's moves); a strip that curls onto its roll followed
        past the gap (``overlap_after``). The larger of the two ends' residual or move, each
        in units of its own ``end_tolerance``."""
        out = 0.0
        f = self.form
        for s, top in self.tops.items():
            verts = top.verts[top.vertex_contact]
            x = top.vertex_positions(self.d, verts)[:, 0]
            order = np.argsort(x)
            p = f.vertex_pressure()[verts]
            rp, sh = self.rolls[s], self.shapes[s]
            old = sh.end(rp)
            winkler = ((lambda x_ref, p_ref, rp=rp, s=s: winkler_end(rp, self._layer(s), x_ref,
                                                                     p_ref, exit_zone=True))
                       if f.compliance and s not in self.wraps else None)
            new, residual = self.end_searches[s].step(x[order], p[order],
                                                      self.side_end_bounds(s), winkler)
            _, leaves = self.side_overlap(s)
            if leaves is not None and p[order][-1] >= 0.0 and leaves > new:
                # the strip curls onto the roll past its end, still pressing on it there: the
                # contact goes on to where the traced surface leaves the roll (past the gap
                # by PAST_GAP_WRAP at most; asymmetric_radii's slower roll: 9.2 mm)
                self.wraps.add(s)
                new = float(np.clip(leaves, *self.side_end_bounds(s)))
            elif new < rp.axis_x:
                self.wraps.discard(s)        # back before the gap: no longer curled onto it
            self._set_side_end(s, new)
            x_new = top.vertex_positions(self.d, verts)[:, 0]
            p_new = carried_pressure(x_new, x[order], p[order], rp,
                                     self._layer(s) if f.compliance else None)
            mv, dofs = f.multiplier_vertices()
            vec = f.multiplier.vec.FV().NumPy()
            vec[dofs[np.searchsorted(mv, verts)]] = p_new / f.lam_scale
            out = max(out, max(residual, abs(new - old)) / self.end_tolerance(s))
        return out
