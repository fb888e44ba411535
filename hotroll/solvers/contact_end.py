"""The unilateral contact's end on the steady strip (docs/theory.md 1e): the search's steps
(``fem/free_surface.py: ContactEndSearch``) applied to the strip map, its range, and an elastic
strip's exit zone (a Winkler layer on the roll's shape: the end predicted, the multiplier
carried with the end's moves). A mixin of ``SteadyRun`` (``solvers/steady.py``), which holds the
strip map, the shape, the form and the problem these methods use."""
from __future__ import annotations

import numpy as np

#: how far past the gap an elastic strip's contact may reach, in contact lengths (its elastic
#: exit zone is sqrt(2 R c_e p), a few percent of the contact length: docs/theory.md 1e)
PAST_GAP = 0.25


def winkler_end(rp, layer_compliance, x_ref: float, p_ref: float,
                exit_zone: bool = False) -> float | None:
    """An elastic strip's contact end on the roll ``rp`` seen from a point of its elastic exit
    zone (x_ref, m; reduced pressure p_ref): where the roll has risen by the strip's elastic
    recovery there, y_roll(x) = y_roll(x_ref) + c_e p_ref (a Winkler layer on the roll's shape,
    docs/theory.md 1e; c_e = ``layer_compliance(y)``, the form's); the first such x within a
    contact length. ``exit_zone``: None where the roll still descends after x_ref (before the
    gap the strip is plastic, not the elastic layer the rule models: from an end 8.6 mm
    before the gap it sent the roughing pass's 3D ends to the point as far past it, a
    tensile 12 MPa there, issue 53)."""
    y0 = float(rp.height(x_ref))
    rise = layer_compliance(y0) * p_ref
    xs = np.linspace(x_ref, x_ref + rp.contact_length, 257)
    if exit_zone and float(rp.height(xs[1])) < y0:
        return None
    g = rp.height(xs) - y0 - rise
    up = np.flatnonzero(g >= 0.0)
    if not len(up):
        return float(xs[-1])
    i = int(up[0])
    if i == 0:
        return x_ref
    return float(xs[i - 1] - g[i - 1] * (xs[i] - xs[i - 1]) / (g[i] - g[i - 1]))


def overlap_after(xy: np.ndarray, rp, x_e: float, tol: float) -> tuple[float, float | None]:
    """The free surface after a contact's end inside its roll (docs/theory.md 1e): from the
    surface's points ``xy`` (its own frame, y towards the roll ``rp``), (the deepest point
    inside the roll after ``x_e``, m; where the stretch inside by more than ``tol`` that starts
    at the end leaves the roll, m, or None when the surface leaves at the end). A strip that
    curls towards a roll follows it past the end found from the pressure (asymmetric_radii's
    lower roll, rigid-plastic: 51 um inside over 15 mm past the gap)."""
    xy = xy[np.argsort(xy[:, 0], kind="stable")]
    x, y = xy[:, 0], xy[:, 1]
    after = x > x_e
    if not np.any(after):
        return 0.0, None
    x, inside = x[after], y[after] - rp.height(x[after])
    depth = max(float(inside.max()), 0.0)
    deep = np.flatnonzero(inside > tol)
    # a stretch inside the roll that starts at the end: the surface does not leave the roll
    # (by more than tol) before it goes in
    if not len(deep) or np.any(inside[:deep[0]] < -tol):
        return depth, None
    out = np.flatnonzero(inside[deep[0]:] <= 0.0)
    if not len(out):
        return depth, float(x[-1])
    i = int(deep[0] + out[0])
    return depth, float(x[i - 1] + inside[i - 1] * (x[i] - x[i - 1]) / (inside[i - 1] - inside[i]))


def surface_overlap(top, d, rp, x_e: float, tol: float) -> tuple[float, float | None]:
    """``overlap_after`` of the free surface ``top`` (its vertices and edge midpoints at the
    displacement ``d``, in its roll's frame) against the roll ``rp`` after the end ``x_e``."""
    xy = np.vstack([top.vertex_positions(d), top.midpoint_positions(d)])
    return overlap_after(xy, rp, x_e, tol)


def move_end(shape, rp, new: float) -> None:
    """The contact's end of ``shape`` on the roll ``rp`` at ``new`` (m): the exit top moves
    with its start, which stays on the roll."""
    old = shape.end(rp)
    shape.exit_x = shape.exit_x + (new - old)
    shape.exit_y = shape.exit_y + float(rp.height(new) - rp.height(old))
    shape.x_e = new


def carried_pressure(x_new, xs, ps, rp, layer_compliance=None) -> np.ndarray:
    """The contact pressure (reduced) at the arc's vertices' new x ``x_new`` after the contact's
    end moved: the old profile (``xs`` increasing, ``ps``) interpolated at the new positions;
    past the old end an elastic strip's (``layer_compliance``: its c_e(y)) continued by its
    Winkler layer, p = p_end - (y_roll - y_roll(x_end)) / c_e (docs/theory.md 1e), a
    rigid-plastic one's held at its end value."""
    p_new = np.interp(x_new, xs, ps)
    ahead = x_new > xs[-1]
    if np.any(ahead) and layer_compliance is not None:
        y = rp.height(x_new[ahead])
        p_new[ahead] = np.maximum(ps[-1] - (y - float(rp.height(xs[-1]))) / layer_compliance(y),
                                  0.0)
    return p_new


class ContactEndMixin:
    """The contact's end x_e of ``SteadyRun``."""

    def end_bounds(self) -> tuple[float, float]:
        """The contact end's range (``StripMap.end_bounds``): up to the gap for a rigid-plastic
        strip; past it (``PAST_GAP``) for an elastic one, which follows the rising roll while
        its pressure falls."""
        return self.map.end_bounds(PAST_GAP if self.form.compliance else 0.0)

    def move_contact_end(self) -> float:
        """Unilateral contact: move the contact's end by ``ContactEndSearch``'s step from the
        pressure at the arc's vertices and remap the mesh; its residual or move (m), the
        larger."""
        top = self.top
        verts = top.verts[top.vertex_contact]
        x = top.vertex_positions(self.d, verts)[:, 0]
        order = np.argsort(x)
        p = self.form.vertex_pressure()[verts]
        old = self.shape.end(self.problem.rp)
        new, residual = self.end_search.step(x[order], p[order], self.end_bounds(),
                                             self._winkler if self.form.compliance else None)
        self._set_end(new)
        self._carry_multiplier(verts, x, p, order)
        return max(residual, abs(new - old))

    def _predict_end(self) -> None:
        """An elastic strip's contact end to start from: where its layer, at 2k at the gap,
        meets the roll (``_winkler``; hot_strip_finishing: 15 Newton iterations, as many as the
        rigid-plastic strip's, against 23 from the gap)."""
        if self.unilateral and self.form.compliance:
            pb = self.problem
            lo, hi = self.end_bounds()
            self._set_end(float(np.clip(self._winkler(pb.rp.axis_x,
                                                      pb.mean_two_k / pb.material.K, False),
                                        lo, hi)))

    def _set_end(self, new: float) -> None:
        """The contact's end at ``new`` (``move_end``), the mesh mapped onto it."""
        move_end(self.shape, self.problem.rp, new)
        self._set_shape()

    def _winkler(self, x_ref: float, p_ref: float, exit_zone: bool = True) -> float | None:
        """``winkler_end`` on the pass's roll (None before the gap, ``exit_zone``)."""
        return winkler_end(self.problem.rp, self.form.layer_compliance, x_ref, p_ref,
                           exit_zone)

    def _carry_multiplier(self, verts, x_old, p_old, order) -> None:
        """After the contact's end moved, the arc's vertices slid along it: the multiplier
        carried with the position (interpolated at the new vertices), not with the vertex; past
        the old end, an elastic strip's pressure continued by its Winkler layer
        (p = p_end - (y_roll - y_roll(x_end)) / c_e, docs/theory.md 1e), a rigid-plastic one's
        held at its end value."""
        f, rp = self.form, self.problem.rp
        x_new = self.top.vertex_positions(self.d, verts)[:, 0]
        p_new = carried_pressure(x_new, x_old[order], p_old[order], rp,
                                 f.layer_compliance if f.compliance else None)
        mv, dofs = f.multiplier_vertices()           # sorted vertex numbers and their DOFs
        vec = f.multiplier.vec.FV().NumPy()
        vec[dofs[np.searchsorted(mv, verts)]] = p_new / f.lam_scale

