"""Free surfaces of the steady strip as streamlines (steady counterpart of (3.7) + (3.9)).

In a steady flow the free top is a streamline: dy/dx = v_y / v_x. After a steady solve the top is
traced from the inlet corner (x_in, entry half-thickness) along the top nodes; where the traced
line reaches the roll the contact begins (3.9) and the top follows the arc; after the roll gap the
line is traced again from the last contact point. The mesh follows by scaling every P2 node
vertically, y' = y Y(x) / Y_ref(x), with Y the new and Y_ref the reference top height, so the
arc part and the symmetry line stay where they are.
"""
from __future__ import annotations

import numpy as np

from ..discretisation.spaces import P2Nodes
from .geometry import RollPass


class StripShape:
    """All P2 geometry nodes of a mesh and their vertical scaling through the displacement."""

    def __init__(self, mesh, n_scalar: int):
        self.nodes = P2Nodes(mesh, n_scalar)

    def scale(self, d_ref: np.ndarray, height_ref, height_new) -> np.ndarray:
        """Displacement that maps the shape of ``d_ref`` to the new top height (callables of x)."""
        nodes = self.nodes
        P = nodes.X0 + nodes.values(d_ref).T          # node positions of the d_ref shape
        Pn = P.copy()
        Pn[:, 1] *= height_new(P[:, 0]) / height_ref(P[:, 0])
        return nodes.coefficients((Pn - nodes.X0).T)


def trace_top(rp: RollPass, xs: np.ndarray, vx: np.ndarray, vy: np.ndarray, y_in: float,
              contact_end: float) -> tuple[np.ndarray, float]:
    """Streamline heights at the sorted top abscissae ``xs`` and the first contact abscissa.

    From ``y_in`` at xs[0] by the trapezoidal rule on v_y/v_x until the line reaches the roll;
    on the roll up to ``contact_end``; after it traced again from the roll surface there.
    The first contact abscissa is nan when the line never reaches the roll.
    """
    cx, cy = rp.centre
    roll = cy - np.sqrt(np.maximum(rp.radius**2 - (xs - cx) ** 2, 0.0))
    slope = vy / np.where(np.abs(vx) > 1e-300, vx, 1e-300)
    y = np.empty_like(xs)
    y[0], start, state = y_in, float("nan"), "free"
    for i in range(1, len(xs)):
        step = 0.5 * (slope[i - 1] + slope[i]) * (xs[i] - xs[i - 1])
        if state == "free":
            y[i] = y[i - 1] + step
            if xs[i] <= contact_end and y[i] >= roll[i]:
                state, start, y[i] = "roll", float(xs[i]), roll[i]
        elif state == "roll" and xs[i] <= contact_end:
            y[i] = roll[i]
        elif state == "roll":
            y_end = cy - np.sqrt(max(rp.radius**2 - (contact_end - cx) ** 2, 0.0))
            state, y[i] = "exit", y_end + slope[i] * (xs[i] - contact_end)
        else:
            y[i] = y[i - 1] + step
    return y, start


def top_height_function(xs: np.ndarray, ys: np.ndarray):
    """Piecewise-linear top height through the traced nodes (constant beyond the ends)."""
    return lambda x: np.interp(x, xs, ys)
