"""The temperature's own mesh of the steady strip: structured, graded towards the top (issue 16).

The roll chills a layer of thickness delta ~ sqrt(alpha l_c / U) (alpha = k / rho c, l_c the
contact length, U the roll speed): about 1 mm in a roughing pass, 0.1 mm in a fast finishing
pass, far below the mechanics' contact size (l_c / 12). Refining the mechanics mesh to it costs
8x the isothermal solve (measured, docs/studies/thermal_mesh.md); a scalar P1 field on a mesh of
its own costs little. This mesh is logical in (X, eta): X the reference abscissa of the
mechanics mesh, eta = Y / H_ref(X) in [0, 1] with H_ref the reference mesh's top (straight
between its vertices: the P2 displacement bends those chords onto the roll arc). Its rows
are thin at the top (first cell delta / 8, growing by 1.2) and its columns fine over the
contact, a quarter contact length either side (l_c / 40; growing by 1.3 outside: a fine zone
reaching one contact length past the gap cost 30 % more strip DOFs and moved the heat to the
air by 0.16 %, the rest by less than 1e-6). It is placed on the strip by the mechanics'
displacement (``place``), so it follows the traced free surface; a point of the mechanics mesh
is found in it by its logical coordinates (``logical``), with no search in deformed
coordinates. Boundaries: ``bottom`` (symmetry line), ``left`` (inlet), ``right`` (outlet),
``top``.

The full strip between two rolls (``full=True``, issue 52): eta in [-1, 1], its rows thin at
both surfaces and mirror images of each other about eta = 0 (the mesh too: ``mirrored``);
``bottom`` is then the lower roll's surface.
"""
from __future__ import annotations

import math

import numpy as np

from hotroll.fem.mesh import structured_triangle_mesh
from hotroll.fem.reproducible import fe_space

FIRST_CELL = 1.0 / 8.0     # first row at the top, in layer thicknesses delta
ROW_GROWTH = 1.2           # row-to-row growth away from the top
COLUMN_GROWTH = 1.3        # column growth outside the fine zone
COLUMNS_PER_CONTACT = 40   # columns over one contact length in the fine zone


def graded_axis(a: float, b: float, breaks: list[float], fine: float, coarse: float,
                growth: float = COLUMN_GROWTH) -> np.ndarray:
    """Nodes from a to b: spacing at most ``fine`` between the first and last of ``breaks``
    (each break a node), growing by ``growth`` per node up to ``coarse`` outside."""
    lo, hi = max(a, min(breaks)), min(b, max(breaks))
    pts = sorted({lo, hi, *[p for p in breaks if lo <= p <= hi]})
    nodes = [lo]
    for p, q in zip(pts[:-1], pts[1:]):
        n = max(1, math.ceil((q - p) / fine - 1e-9))
        nodes.extend(np.linspace(p, q, n + 1)[1:])

    def outward(start, end, sign):
        out, x, s = [], start, fine
        while sign * (end - (x + sign * s)) > 0.5 * s:
            x += sign * s
            out.append(x)
            s = min(s * growth, coarse)
        return out

    left = outward(lo, a, -1.0)[::-1]
    right = outward(hi, b, 1.0)
    return np.array(([a] if lo > a else []) + left + nodes + right + ([b] if hi < b else []))


def top_rows(first: float, largest: float, growth: float = ROW_GROWTH) -> np.ndarray:
    """eta nodes from 0 to 1: the top row ``first`` thick, growing by ``growth`` towards the
    symmetry line up to ``largest`` (all in units of the half-thickness)."""
    if not 0.0 < first <= largest:
        raise ValueError(f"rows: need 0 < first ({first}) <= largest ({largest})")
    etas, s = [1.0], first
    while etas[-1] - s > 0.5 * s:
        etas.append(etas[-1] - s)
        s = min(s * growth, largest)
    etas.append(0.0)
    return np.array(etas[::-1])


def layer_thickness(rp, alpha: float) -> float:
    """delta = sqrt(alpha l_c / U) (m): the depth heat diffuses in the contact time."""
    return math.sqrt(alpha * rp.contact_length / rp.u_roll)


class ThermalStrip:
    """The structured P1 mesh of the steady strip for the temperature (module docstring)."""

    def __init__(self, rp, top_ref: np.ndarray, h: float, delta: float, refine: float = 1.0,
                 full: bool = False, breaks=()):
        """``top_ref``: the reference top vertices of the mechanics mesh (N, 2), inlet to
        outlet; ``h`` its contact size; ``delta`` the layer thickness (``layer_thickness``);
        ``full``: the whole thickness between two surfaces at +-H_ref (module docstring);
        ``breaks``: more x (m) inside the fine columns (another roll's contact start)."""
        from ngsolve import CF, H1, GridFunction, VectorH1, grad

        if not refine > 0.0:
            raise ValueError(f"refine = {refine!r}: must be > 0")
        order = np.argsort(top_ref[:, 0])
        self._top_x, self._top_y = top_ref[order, 0], top_ref[order, 1]
        self.rp, self.x_in, self.x_out = rp, float(self._top_x[0]), float(self._top_x[-1])
        self.delta = float(delta)
        lc, h1 = rp.contact_length, rp.half_exit
        fine = min(lc / COLUMNS_PER_CONTACT, h / 2.0) / refine
        coarse = max(fine, min(rp.half_entry / 2.0, 8.0 * h) / refine)
        self.X = graded_axis(self.x_in, self.x_out,
                             [rp.x_touch - 0.25 * lc, rp.x_touch, rp.axis_x, rp.axis_x + 0.25 * lc,
                              *(z for b in breaks for z in (b - 0.25 * lc, b))],
                             fine, coarse)
        largest = min(h / 2.0, h1 / 8.0) / refine / h1
        first = min(FIRST_CELL * self.delta / refine / h1, largest)
        self.eta = top_rows(first, largest)
        self.full = bool(full)
        if self.full:
            self.eta = np.concatenate([-self.eta[:0:-1], self.eta])
        X, eta = self.X, self.eta
        nx, ny = len(X) - 1, len(eta) - 1
        self.mesh = structured_triangle_mesh(X, eta, mirrored=self.full)
        # vertex i + j (nx + 1): column i, row j
        self.shape = (ny + 1, nx + 1)
        Xg, Eg = np.meshgrid(X, eta)
        self.logical_points = np.stack([Xg.ravel(), Eg.ravel()], -1)
        self.reference = np.stack([Xg.ravel(), Eg.ravel() * self.top_height(Xg.ravel())], -1)
        self.disp = GridFunction(fe_space(VectorH1, self.mesh, order=1))
        self.psi = GridFunction(fe_space(H1, self.mesh, order=1))
        g = grad(self.psi)
        self._velocity = CF((g[1], -g[0]))
        self.physical = self.reference.copy()
        self.i_exit = int(np.argmin(np.abs(X - rp.axis_x)))   # the roll gap's column

    def top_height(self, X: np.ndarray) -> np.ndarray:
        """H_ref(X): the reference top, straight between the mechanics mesh's top vertices."""
        return np.interp(X, self._top_x, self._top_y)

    @property
    def nv(self) -> int:
        return self.mesh.nv

    def logical(self, ref: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Logical (X, eta) of reference points (N, 2) of the mechanics mesh, clipped into
        the strip."""
        X = np.clip(ref[:, 0], self.x_in, self.x_out)
        eta = np.clip(ref[:, 1] / self.top_height(X), -1.0 if self.full else 0.0, 1.0)
        return X, eta

    def place(self, physical: np.ndarray) -> None:
        """Deform the logical mesh onto the strip: ``physical`` (N, 2) are the current
        positions of ``reference`` (the mechanics' displacement added)."""
        self.physical = np.asarray(physical, dtype=float)
        n = self.nv
        d = self.disp.vec.FV().NumPy()
        d[:n] = self.physical[:, 0] - self.logical_points[:, 0]
        d[n:2 * n] = self.physical[:, 1] - self.logical_points[:, 1]
        self.mesh.SetDeformation(self.disp)

    def set_stream_function(self, flux: np.ndarray, total: float) -> None:
        """psi at the vertices from the flux below each vertex along its column (``flux``,
        (ny+1, nx+1), 0 on the symmetry line, or the lower surface): rescaled per column to
        ``total`` at the top, so that the velocity curl psi is divergence-free, the top and the
        bottom are streamlines and every section carries ``total`` (m^2/s)."""
        flux = np.asarray(flux, dtype=float).reshape(self.shape)
        top = flux[-1]
        if np.any(top <= 0.0):
            raise ValueError("the strip's flux through a section is not positive")
        self.psi.vec.FV().NumPy()[:] = (total * flux / top).ravel()

    def velocity(self):
        """curl psi = (d psi/dy, -d psi/dx), constant on each triangle (m/s); one CF object
        (the field's forms are built once for it)."""
        return self._velocity

    def element_flow(self, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """numpy twin of ``velocity()`` on the placed strip: per triangle (``triangles``, the
        mesh's, in element order) the gradients of its barycentric coordinates (ne, 3, 2), its
        Jacobian determinant (ne) and curl psi (ne, 2). The vertices as the deformed mesh has
        them (logical + displacement: the thin top rows make the Jacobian sensitive to the
        last digit of the positions), grad psi from the differences to the third vertex (psi
        is large, its steps small)."""
        from hotroll.fem.heat_p1 import p1_gradients

        n, d = self.nv, self.disp.vec.FV().NumPy()
        grads, det = p1_gradients(self.logical_points + np.stack([d[:n], d[n:2 * n]], -1),
                                  triangles)
        psi = self.psi.vec.FV().NumPy()[triangles]
        g = ((psi[:, 0] - psi[:, 2])[:, None] * grads[:, 0]
             + (psi[:, 1] - psi[:, 2])[:, None] * grads[:, 1])
        return grads, det, np.stack([g[:, 1], -g[:, 0]], -1)
