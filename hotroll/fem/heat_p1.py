"""The steady heat equation's P1 pieces in numpy, for a velocity constant on each triangle and
constant properties (the thermal coupling's strip: its velocity is curl psi of a P1 stream
function): SUPG's tau, the plastic heat's load, and the volume part of the residual and of its
Jacobian (``SteadyP1Operator``), each what NGSolve's assembly gives, to rounding (tests).

On a triangle of area A with barycentric gradients g_i, v.grad N_i = b_i, tau constant:

    r_i = A [k g_i.grad T - rho c (Tbar - T_entry) b_i + rho c (v.grad T) tau b_i]
    J_ij = A [k g_i.g_j - rho c b_i / 3 + rho c tau b_i b_j]

(Tbar the mean of the vertex values: the enthalpy rho c (T - T_entry) of the advection term is
linear, its integral against the constant b_i exact). The boundary terms (the outlet's advection,
the top's fluxes) stay NGSolve's forms.
"""
from __future__ import annotations

import numpy as np


def p1_gradients(points: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The gradients of the barycentric coordinates of each triangle (ne, 3, 2) and the
    Jacobian determinant of its map from the reference triangle (ne; twice the signed area)."""
    p0, p1, p2 = (points[triangles[:, i]] for i in range(3))
    a11, a21 = p0[:, 0] - p2[:, 0], p0[:, 1] - p2[:, 1]      # J = [p0 - p2, p1 - p2]
    a12, a22 = p1[:, 0] - p2[:, 0], p1[:, 1] - p2[:, 1]
    det = a11 * a22 - a12 * a21
    g0 = np.stack([a22, -a12], -1) / det[:, None]           # rows of J^-1
    g1 = np.stack([-a21, a11], -1) / det[:, None]
    return np.stack([g0, g1, -(g0 + g1)], 1), det


def p1_supg_tau(grads: np.ndarray, det: np.ndarray, velocity: np.ndarray, rho_c: float,
                k: float, supg: float = 1.0) -> np.ndarray:
    """``TemperatureField._tau`` per P1 triangle (s) for a velocity constant on each (ne, 2)
    and constant properties: h_v = 2 |v| / sum_i |v.grad N_i| (the mesh size sqrt|det J|
    where v = 0), Pe = |v| h_v rho c / (2 k), tau = supg h_v / (2 |v|) (coth Pe - 1/Pe), its
    series below Pe = 1e-2; ``grads, det`` of ``p1_gradients``."""
    b = np.einsum("eij,ej->ei", grads, velocity)            # v.grad N_i
    total = np.abs(b).sum(axis=1)
    speed = np.sqrt(np.einsum("ej,ej->e", velocity, velocity) + 1e-300)
    moving = total - 1e-300 > 0.0
    h = np.where(moving, 2.0 * speed / np.where(moving, total, 1.0), np.sqrt(np.abs(det)))
    pe = speed * h * rho_c / (2.0 * k)
    big = np.where(pe - 1e-2 > 0.0, pe, 1e-2)
    e = np.exp(-2.0 * big)
    xi = np.where(pe - 1e-2 > 0.0, (1.0 + e) / (1.0 - e) - 1.0 / big, pe / 3.0 - pe ** 3 / 45.0)
    return supg * h / (2.0 * speed) * xi


def p1_supg_load(triangles: np.ndarray, grads: np.ndarray, det: np.ndarray,
                 velocity: np.ndarray, tau: np.ndarray, q: np.ndarray, ndof: int) -> np.ndarray:
    """int q (w + tau v.grad w) dx for each P1 hat function w (ndof, the vertices), q P1
    (vertex values), v and tau constant per triangle: on a triangle of area A, int q N_i =
    A (q_i + sum q) / 12 and int q tau v.grad N_i = tau (v.grad N_i) A sum q / 3 (what the
    order-2 rule integrates exactly); ``grads, det`` of ``p1_gradients``."""
    qv = q[triangles]
    total = qv.sum(axis=1)
    b = np.einsum("eij,ej->ei", grads, velocity)            # v.grad N_i
    area = 0.5 * np.abs(det)
    local = area[:, None] * ((qv + total[:, None]) / 12.0 + (tau * total / 3.0)[:, None] * b)
    return np.bincount(triangles.ravel(), local.ravel(), minlength=ndof)



class SteadyP1Operator:
    """The steady residual a(T; w) as NGSolve's forms have it (``Apply``,
    ``AssembleLinearization``, ``mat``): the boundary terms' form ``boundary`` plus the volume
    terms in numpy (module docstring), on the matrix of ``pattern`` (a form on the same space
    whose sparsity holds every triangle's couplings, assembled once).

    ``flow()``: (triangles (ne, 3), barycentric gradients, Jacobian determinants, velocity per
    triangle) at the current placement; ``tau()``: SUPG's tau per triangle as the field holds
    it; ``k``, ``rho_c``: the constant properties; ``reference``: the enthalpy's zero (K)."""

    def __init__(self, boundary, pattern, flow, tau, k: float, rho_c: float, reference: float):
        self.boundary, self.pattern = boundary, pattern
        self.flow, self.tau = flow, tau
        self.k, self.rho_c, self.reference = float(k), float(rho_c), float(reference)
        self._where = None       # (volume entries' positions, boundary entries' positions)

    @property
    def mat(self):
        return self.pattern.mat

    def _parts(self):
        """(triangles, barycentric gradients, areas, v.grad N_i) at the current placement."""
        tris, grads, det, v = self.flow()
        area = 0.5 * np.abs(det)
        b = np.einsum("eij,ej->ei", grads, v)                  # v.grad N_i
        return tris, grads, area, b

    def Apply(self, vec, out) -> None:                  # noqa: N802 - NGSolve's form interface
        self.boundary.Apply(vec, out)
        T = vec.FV().NumPy()
        tris, grads, area, b = self._parts()
        Te = T[tris]
        grad_T = np.einsum("eij,ei->ej", grads, Te)
        vgT = np.einsum("ei,ei->e", b, Te)
        rc, tau = self.rho_c, self.tau()
        local = area[:, None] * (self.k * np.einsum("eij,ej->ei", grads, grad_T)
                                 - rc * (Te.mean(axis=1) - self.reference)[:, None] * b
                                 + (rc * vgT * tau)[:, None] * b)
        out.FV().NumPy()[:] += np.bincount(tris.ravel(), local.ravel(), minlength=len(T))

    def AssembleLinearization(self, vec) -> None:       # noqa: N802
        self.boundary.AssembleLinearization(vec)
        tris, grads, area, b = self._parts()
        if self._where is None:
            self._where = self._positions(tris)
        rc, tau = self.rho_c, self.tau()
        local = area[:, None, None] * (self.k * np.einsum("eik,ejk->eij", grads, grads)
                                       - (rc / 3.0) * b[:, :, None]
                                       + (rc * tau)[:, None, None] * b[:, :, None]
                                       * b[:, None, :])
        vol_pos, bnd_pos = self._where
        vals = self.pattern.mat.AsVector().FV().NumPy()
        vals[:] = np.bincount(vol_pos, local.ravel(), minlength=len(vals))
        vals[bnd_pos] += self.boundary.mat.AsVector().FV().NumPy()

    def _positions(self, tris: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Where each triangle's 3 x 3 entries and the boundary matrix's entries sit in the
        pattern's values (its CSR order)."""
        self.pattern.Assemble()
        keys = _keys(self.pattern.mat)
        n = self.pattern.mat.width
        tris = np.asarray(tris, dtype=np.int64)
        rows = np.repeat(tris, 3, axis=1).ravel()
        cols = np.tile(tris, (1, 3)).ravel()
        vol_keys, bnd_keys = rows * n + cols, _keys(self.boundary.mat)
        vol, bnd = np.searchsorted(keys, vol_keys), np.searchsorted(keys, bnd_keys)
        for pos, want in ((vol, vol_keys), (bnd, bnd_keys)):
            if np.any(pos >= len(keys)) or np.any(keys[np.minimum(pos, len(keys) - 1)] != want):
                raise RuntimeError("the pattern form's matrix lacks a coupling of the heat form")
        return vol, bnd


def _keys(mat) -> np.ndarray:
    """row * width + column of each stored entry of an NGSolve sparse matrix, in its order."""
    _, cols, ptr = mat.CSR()
    ptr = np.asarray(ptr, dtype=np.int64)
    rows = np.repeat(np.arange(len(ptr) - 1, dtype=np.int64), np.diff(ptr))
    return rows * mat.width + np.asarray(cols, dtype=np.int64)
