"""Starting a steady pass from a solved, similar pass on another mesh (issue 17: schedules).

The passes of a schedule differ in size, speed and temperature but look alike in the roll
gap's own coordinates: xi along the strip through the knots (inlet, touching point, roll gap,
outlet) and eta = y / (top height). ``SimilarPass.apply`` maps the solved pass onto the new
pass in those coordinates:

- a flattening roll's surface at the same fraction of the bite angle;
- the strip shape: the contact start by the knot map, the free tops' sag scaled with the
  thickness (the entry top still ends on the roll);
- the velocity at every P2 node of the new mesh: the solved velocity at the same (xi, eta),
  v_x times U_new/U_old, v_y times (U alpha)_new / (U alpha)_old (alpha the bite angle: v_y
  follows the top's slope);
- the (reduced, p/K) pressure at the vertices times the rate factor
  (edot_new^m_new / edot_old^m_old), edot = U/l_c 2/sqrt3 ln(h0/h1).

It is only Newton's starting point: the converged pass is the new pass's own (the result does
not depend on where Newton started, to the solver's tolerance; a start that fails to converge
is solved again from cold, ``SteadyRun.solve``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hotroll.fem.free_surface import StripShape, roll_height
from hotroll.fem.point_search import mesh_points


def _knots(run) -> np.ndarray:
    """The strip's knots in x: inlet, touching point, roll gap, outlet (the inlet and outlet
    of the reference mesh: a flattened roll touches the strip further upstream than the roll
    the mesh was made for)."""
    rp = run.problem.rp
    x = run.top.X0[run.top.verts][:, 0]
    return np.array([float(np.min(x)), rp.x_touch, rp.axis_x, float(np.max(x))])


def knot_map(x, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Piecewise-linear map of x taking the knots ``a`` to ``b``, linear beyond the ends."""
    x = np.asarray(x, dtype=float)
    i = np.clip(np.searchsorted(a, x) - 1, 0, len(a) - 2)
    t = (x - a[i]) / (a[i + 1] - a[i])
    return b[i] + t * (b[i + 1] - b[i])


def _top(run):
    """(x, y) of the reference mesh's top vertices, increasing x (undeformed coordinates)."""
    P = run.top.X0[run.top.verts]
    order = np.argsort(P[:, 0])
    return P[order, 0], P[order, 1]


def _mean_rate(rp) -> float:
    return rp.u_roll / rp.contact_length * 2.0 / math.sqrt(3.0) * math.log(
        rp.half_entry / rp.half_exit)


@dataclass
class SimilarPass:
    """A solved ``SteadyRun`` to start another pass from (module docstring)."""

    run: object
    name: str = ""

    @property
    def free_surface(self) -> str:
        return self.run.s.free_surface

    def shape_for(self, dst) -> StripShape:
        """The solved strip shape carried onto ``dst``'s pass."""
        src, rs, rd = self.run, self.run.problem.rp, dst.problem.rp
        a, b = _knots(src), _knots(dst)
        sh = src.shape
        x_c = float(np.clip(knot_map(sh.x_c, a, b), *dst.map.x_bounds()))
        sag_src = sh.entry_y[-1] - rs.half_entry
        sag_dst = float(roll_height(rd, x_c)) - rd.half_entry
        scale = sag_dst / sag_src if abs(sag_src) > 1e-12 * rs.half_entry else 0.0
        entry_x = knot_map(sh.entry_x, a, b)
        entry_x[-1] = x_c
        entry_y = rd.half_entry + (sh.entry_y - rs.half_entry) * scale
        exit_y = rd.half_exit + (sh.exit_y - rs.half_exit) * (rd.half_exit / rs.half_exit)
        exit_x = knot_map(sh.exit_x, a, b)
        if sh.x_e is None:
            return StripShape(x_c, entry_x, entry_y, exit_x, exit_y)
        # the contact's end: before the gap by the knot map; past it (an elastic strip's exit
        # zone, sqrt(2 R c_e p) with c_e ~ h) by sqrt(R h)
        past = sh.x_e - rs.axis_x
        x_e = (float(knot_map(sh.x_e, a, b)) if past <= 0.0 else
               rd.axis_x + past * math.sqrt(rd.radius * rd.half_exit / (rs.radius * rs.half_exit)))
        x_e = float(np.clip(x_e, *dst.end_bounds()))
        exit_x = exit_x + (x_e - exit_x[0])
        exit_y = exit_y + (float(roll_height(rd, x_e)) - exit_y[0])
        return StripShape(x_c, entry_x, entry_y, exit_x, exit_y, x_e)

    def apply(self, dst, vec: np.ndarray) -> None:
        """Set ``dst``'s shape and its velocity-pressure vector ``vec`` from the solved pass."""
        src, rs, rd = self.run, self.run.problem.rp, dst.problem.rp
        if src.problem.roll is not None and dst.problem.roll is not None:
            dst.problem.roll.carry(src.problem.roll)      # before the shape: it lies on the roll
        dst.shape = self.shape_for(dst)
        dst._set_shape()
        nodes = dst.map.nodes
        X = nodes.X0                                   # P2 nodes, undeformed coordinates
        xd, yd = _top(dst)
        xs_top, ys_top = _top(src)
        eta = np.clip(X[:, 1] / np.interp(X[:, 0], xd, yd), 0.0, 1.0) * (1.0 - 1e-9)
        a, b = _knots(dst), _knots(src)
        span = b[-1] - b[0]
        xs = np.clip(knot_map(X[:, 0], a, b), b[0] + 1e-9 * span, b[-1] - 1e-9 * span)
        ys = eta * np.interp(xs, xs_top, ys_top)
        pts = self._find(xs, ys)
        u, p = src.form.nonlinear.gf.components[:2]
        vel = np.asarray(u(pts), dtype=float).reshape(len(xs), 2)
        # by the roll speeds (scaling by the fluxes over the local heights, closer by mass
        # conservation, took more Newton iterations on the finishing mill: 159 against 120)
        ratio = rd.u_roll / rs.u_roll
        vel[:, 0] *= ratio
        vel[:, 1] *= ratio * rd.bite_angle / rs.bite_angle
        coeff = nodes.coefficients(vel.T)
        n = len(coeff)
        vec[:n] = coeff
        nv = dst.mesh.nv
        m_s, m_d = src.problem.material.m, dst.problem.material.m
        factor = _mean_rate(rd) ** m_d / _mean_rate(rs) ** m_s
        press = np.asarray(p(pts), dtype=float).reshape(-1)[:nv]
        vec[n:n + nv] = factor * press
        lr = dst.form.nonlinear.multiplier_range()
        vec[lr] = 0.0
        if dst.form.exact and src.form.exact:
            # the contact pressure at the same point of the arc, times the rate factor (from
            # zero, Coulomb's friction is nil in Newton's first residual)
            vs, _ = src.form.multiplier_vertices()
            xs_arc = src.top.vertex_positions(src.d, vs)[:, 0]
            order = np.argsort(xs_arc)
            p_src = src.form.vertex_pressure()[vs][order]
            vd, dofs = dst.form.multiplier_vertices()
            x_dst = knot_map(dst.top.vertex_positions(dst.d, vd)[:, 0], a, b)
            p_dst = factor * np.interp(x_dst, xs_arc[order], p_src, left=0.0, right=0.0)
            vec[lr.start + dofs] = p_dst / dst.form.lam_scale

    def _find(self, xs: np.ndarray, ys: np.ndarray):
        """Mesh points of the solved pass's mesh (searched undeformed, evaluated deformed)."""
        pts = mesh_points(self.run.mesh, xs, ys, self.run.disp)     # fem/point_search.py
        missing = int(np.sum(np.asarray(pts["nr"]) < 0))
        if missing:
            raise ValueError(f"similar-pass start: {missing} nodes outside the solved mesh")
        return pts
