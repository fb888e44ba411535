"""The contact's end per width level of the 3D strip (issue 53; unilateral contact as in 2D,
issue 50).

Each width level z_k carries its own contact end x_e(z_k) (its ``StripShape.x_e`` in
``solvers/spread_tops.LevelTops``), found as the 2D pass finds its own
(``fem/free_surface.ContactEndSearch``, ``solvers/contact_end.py``): a root of the contact
pressure at the level's last arc vertex, p_end >= 0, X_roll - x_e >= 0, p_end (X_roll - x_e)
= 0, one step per round from the first round the surfaces are within 10 of their tolerances
(the 2D pass's rule), each level with its own search from scratch (trust length, sign changes), its bounds
the 2D pass's (up to the gap for a rigid-plastic strip, past it for an elastic one), an
elastic strip's first steps predicted by its Winkler layer. After a level's end moved its arc
vertices slide along the roll and the multiplier is carried with the position
(``contact_end.carried_pressure``). With the end the 2D pass's in every level, the bundled
narrow bar's 3D multiplier pulled at mid-width (-41 MPa at the end vertex) and pushed at the
edge (+142 MPa): where the strip leaves the roll depends on the width position.
"""
from __future__ import annotations

import numpy as np

from hotroll.fem.free_surface import ContactEndSearch
from hotroll.solvers.contact_end import carried_pressure, move_end
from hotroll.solvers.couplings import ContactEnd


class LevelEnds:
    """The contact's end per width level of the ``Spread3D`` ``s3`` (its ``LevelTops``
    ``tops`` holds the levels' shapes), for a 2D pass with unilateral contact."""

    def __init__(self, s3, tops):
        self.s3, self.tops, run = s3, tops, s3.run2d
        # each level its own search from scratch (the 2D pass's last pair, sign changes and
        # trust are its own level's history, not these)
        self.searches = [ContactEndSearch() for _ in range(len(s3.z))]
        #: the tolerance of an end's move (m): the 2D pass's (``couplings.ContactEnd``)
        scale = ContactEnd.TOLERANCE_ELASTIC if run.form.compliance else ContactEnd.TOLERANCE
        self.tol = scale * run.s.surface_tol * run.problem.h

    def ends(self) -> np.ndarray:
        """x_e of every level (m, the solver's frame)."""
        rp = self.s3.run2d.problem.rp
        return np.array([shape.end(rp) for shape in self.tops.shapes])

    def update(self) -> float:
        """One step of every level's end search from the 3D multiplier at the level's arc
        vertices; the levels' meshes mapped onto the new ends and the multiplier carried; the
        largest residual or move (m)."""
        s3, tops, run = self.s3, self.tops, self.s3.run2d
        rp, f3, top = run.problem.rp, s3.form, run.top
        nv = run.mesh.nv
        verts = top.verts[top.vertex_contact]
        winkler = run._winkler if run.form.compliance else None
        bounds = run.end_bounds()
        lam = f3.multiplier.vec.FV().NumPy()
        mv, dofs = f3.multiplier_vertices()
        p_all = f3.vertex_pressure()
        largest, tied = 0.0, tops.tied
        # an edge zone's interior levels (below ``tied``) take the cut's end (LevelTops.tied)
        for k in list(range(tied, len(self.searches))) + list(range(tied)):
            x = top.vertex_positions(tops.d2[k], verts)[:, 0]
            order = np.argsort(x)
            p = p_all[k * nv + verts]
            old = tops.shapes[k].end(rp)
            if k < tied:
                new, residual = tops.shapes[tied].end(rp), 0.0
            else:
                new, residual = self.searches[k].step(x[order], p[order], bounds, winkler)
            move_end(tops.shapes[k], rp, new)
            tops.d2[k] = run.map.displacement(tops.shapes[k])
            x_new = top.vertex_positions(tops.d2[k], verts)[:, 0]
            p_new = carried_pressure(x_new, x[order], p[order], rp,
                                     run.form.layer_compliance if run.form.compliance else None)
            lam[dofs[np.searchsorted(mv, k * nv + verts)]] = p_new / f3.lam_scale
            largest = max(largest, residual, abs(new - old))
        return largest
