"""Known-answer problems for the finite-element core (Taylor-Hood + Norton-Hoff + Picard/Newton).

Both problems go through the code paths of the rolling problem: ``taylor_hood`` spaces,
``norton_hoff_volume`` inside an ``integrand(u, p, w, v, q)``, a ``NonlinearProblem``, and the
solvers ``picard``/``newton`` with ``m`` an ``ngsolve.Parameter`` (one Picard step at m = 1, then
the target m). Unlike ``RollingForm`` the forms keep the physical K (not divided by K), so the
unit-independence checks exercise the solvers with stresses of order K.

For a shear flow u = (u(y), 0): sqrt3 edot = |u'| and s_xy = K |u'|^(m-1) u'; for the uniform
compression v = r (x, -y): eps_dot = diag(r, -r) and sqrt3 edot = 2r.

1. ``poiseuille``: power-law flow in the half channel [0, L] x [0, H], driven by the pressure
   drop G L (normal traction G L at the inlet, zero at the outlet). Equilibrium gives
   s_xy = -G y, hence u(y) = m/(m+1) (G/K)^(1/m) (H^((m+1)/m) - y^((m+1)/m)), p = G (L - x),
   half-channel flow rate Q = m/(2m+1) (G/K)^(1/m) H^((2m+1)/m).
2. ``compression``: frictionless plane-strain compression of [0, a] x [0, b] at rate r:
   v = r (x, -y), s = K (2r)^m diag(1, -1), free right face sigma_xx = 0 gives p = K (2r)^m,
   platen stress sigma_yy = -2K (2r)^m. The P2 velocity space contains the exact field.
"""
from __future__ import annotations

import numpy as np

from hotroll.fem.forms import NonlinearProblem, norton_hoff_volume, strain_rate
from hotroll.fem.nonlinear import SolveStats, newton, picard
from hotroll.fem.reproducible import find_points, integrate
from hotroll.fem.spaces import taylor_hood
from hotroll.model.material import NortonHoff, edot_squared


def rectangle(width: float, height: float, nx: int, ny: int, names: tuple[str, str, str, str]):
    """Structured triangular mesh of [0, width] x [0, height]; names of (bottom, right, top, left)."""
    from ngsolve import Mesh
    from ngsolve.meshes import MakeStructured2DMesh

    mesh = MakeStructured2DMesh(quads=False, nx=nx, ny=ny,
                                mapping=lambda s, t: (width * s, height * t))
    for i, name in enumerate(names):
        mesh.ngmesh.SetBCName(i, name)
    return Mesh(mesh.ngmesh)


def solve_with_continuation(problem: NonlinearProblem, m_param, m: float, method: str,
                            tol: float, max_it: int) -> tuple[SolveStats, list[float]]:
    """One Picard step at m = 1 (linear), then ``method`` at the target m, one step per call.

    Both solvers keep no state besides ``problem.gf``, so calling them with max_it = 1 in a loop
    is the same iteration; it records the velocity update of every step (contraction check).
    """
    m_param.Set(1.0)
    picard(problem, tol, 1)
    m_param.Set(m)
    step = newton if method == "newton" else picard
    total, updates = SolveStats(), []
    for _ in range(max_it):
        stats = step(problem, tol, 1)
        updates.append(stats.update)
        total.iterations += 1
        total.update, total.residual = stats.update, stats.residual
        total.time_assembly += stats.time_assembly
        total.time_linear += stats.time_linear
        if stats.converged:
            total.converged = True
            break
    return total, updates


def _l2(cf, mesh, order=10) -> float:
    from ngsolve import InnerProduct

    return float(np.sqrt(integrate(InnerProduct(cf, cf), mesh, order=order)))


def poiseuille(h: float, m: float, K: float = 1.0, G: float = 1.0, H: float = 1.0,
               L: float = 2.0, eps0: float = 1e-6, method: str = "newton",
               tol: float = 1e-10, max_it: int = 60) -> dict:
    """Power-law Poiseuille flow on a structured mesh of size h; errors relative to the exact."""
    from ngsolve import CF, Parameter, ds, dx, x, y

    mesh = rectangle(L, H, round(L / h), round(H / h), ("sym", "out", "wall", "in"))
    fes = taylor_hood(mesh, dirichletx="wall", dirichlety="sym|wall|in|out")
    material = NortonHoff(K=K, m=m, eps0=eps0)
    m_param = Parameter(1.0)

    def integrand(u, p, w, v, q):
        vol = norton_hoff_volume(material, m_param, u, p, w, v, q, K=K)
        return vol * dx - G * L * v[0] * ds("in")

    u_max = m / (m + 1.0) * (G / K) ** (1.0 / m) * H ** ((m + 1.0) / m)
    problem = NonlinearProblem(fes, integrand, velocity_scale=u_max)
    stats, updates = solve_with_continuation(problem, m_param, m, method, tol, max_it)

    u_exact = CF((m / (m + 1.0) * (G / K) ** (1.0 / m)
                  * (H ** ((m + 1.0) / m) - y ** ((m + 1.0) / m)), 0.0))
    p_exact = G * (L - x)
    q_exact = m / (2.0 * m + 1.0) * (G / K) ** (1.0 / m) * H ** ((2.0 * m + 1.0) / m)
    u_h, p_h = problem.velocity, problem.pressure
    q_h = integrate(u_h[0], mesh, order=6) / L          # mean over x of the flow rate
    return {
        "u_error": _l2(u_h - u_exact, mesh) / _l2(u_exact, mesh),
        "flux": q_h,
        "flux_exact": q_exact,
        "flux_error": abs(q_h - q_exact) / q_exact,
        "p_error": _l2(p_h - p_exact, mesh) / _l2(p_exact, mesh),
        "iterations": stats.iterations,
        "converged": stats.converged,
        "updates": updates,
        "dofs": fes.ndof,
        "velocity": u_h,
        "mesh": mesh,
    }


def compression(h: float, m: float, K: float = 1.0, r: float = 1.0, a: float = 1.0,
                b: float = 1.0, method: str = "newton", eps0: float = 1e-6,
                tol: float = 1e-10, max_it: int = 30) -> dict:
    """Frictionless plane-strain compression; the exact solution is in the discrete space."""
    from ngsolve import BND, BoundaryFromVolumeCF, Parameter, dx

    mesh = rectangle(a, b, max(1, round(a / h)), max(1, round(b / h)),
                     ("bottom", "right", "top", "left"))
    fes = taylor_hood(mesh, dirichletx="left", dirichlety="bottom|top")
    material = NortonHoff(K=K, m=m, eps0=eps0)
    m_param = Parameter(1.0)

    def integrand(u, p, w, v, q):
        return norton_hoff_volume(material, m_param, u, p, w, v, q, K=K) * dx

    problem = NonlinearProblem(fes, integrand, velocity_scale=r * max(a, b))
    # Dirichlet value v_y = -r b on the platen (free DOFs only are changed by the solvers)
    problem.gf.components[0].components[1].Set(-r * b, BND, definedon=mesh.Boundaries("top"))
    stats, updates = solve_with_continuation(problem, m_param, m, method, tol, max_it)

    u_h, p_h = problem.velocity, problem.pressure
    xs, ys = np.meshgrid(np.linspace(0, a, 21), np.linspace(0, b, 21))
    vals = u_h(find_points(mesh, xs.ravel(), ys.ravel()))
    exact = r * np.column_stack([xs.ravel(), -ys.ravel()])
    eps = strain_rate(u_h)
    s_yy = material.viscosity(edot_squared(eps), m=m, K=K) * eps[1, 1]
    # on boundary elements Grad gives the surface gradient only (d/dy of v_y lost on the top):
    # evaluate sigma_yy from the adjacent volume element
    force = integrate(BoundaryFromVolumeCF(s_yy - p_h), mesh, BND,
                      definedon=mesh.Boundaries("top"), order=6)
    p_mean = integrate(p_h, mesh, order=4) / (a * b)
    return {
        "u_error": float(np.max(np.abs(vals - exact))) / (r * a),
        "force": force,
        "force_exact": -2.0 * K * (2.0 * r) ** m * a,
        "pressure": p_mean,
        "pressure_exact": K * (2.0 * r) ** m,
        "iterations": stats.iterations,
        "converged": stats.converged,
        "updates": updates,
        "dofs": fes.ndof,
    }
