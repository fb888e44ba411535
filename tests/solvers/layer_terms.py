"""Checks of the elastic layer's terms in the contact's constraint (docs/theory.md 1e and 4l,
``RollingForm.constraint``, ``RollingForm3D.layer_flux_rate``, ``layer_ends``) on a solved 3D
strip: the arc's net flux, the layer's terms tested with xi = 1, and the layer's Jacobian
against central differences of its residual."""
from __future__ import annotations

import numpy as np


def arc_flux(form) -> tuple[float, float]:
    """(int u.n dA over the arc, the inflow int -u.n over ``in``): n the roll's normal on the
    arc (the constraint's), the mesh's outward normal on the inlet."""
    import ngsolve as ng

    from hotroll.fem.reproducible import integrate

    mesh, u = form.mesh, form.nonlinear.velocity
    n, _ = form.roll_frame()
    arc = integrate(u * n, mesh, ng.BND, definedon=mesh.Boundaries(form.MULTIPLIER_ON))
    inflow = -integrate(u * ng.specialcf.normal(form.dim), mesh, ng.BND,
                        definedon=mesh.Boundaries("in"))
    return float(arc), float(inflow)


def width_flux_divergence(form) -> float:
    """int d(c_e p u_z)/dz dA over a 3D arc (a volume flux, as int u.n dA), written out here:
    c_e p = compliance min(y, depth) s lambda~ (p reduced, c_e per unit reduced pressure),
    the derivatives the surface gradients' z parts (c_e does not vary along z). Its size is
    what the arc passed without the layer's flux across the width."""
    import ngsolve as ng

    from hotroll.fem.reproducible import integrate

    mesh, u, lam = form.mesh, form.nonlinear.velocity, form.multiplier
    depth = ng.y if form.strip_depth is None else ng.IfPos(ng.y - form.strip_depth,
                                                           form.strip_depth, ng.y)
    e_z = ng.CF((0.0, 0.0, 1.0))
    rate = form.compliance * depth * (u[2] * (ng.grad(lam) * e_z)
                                      + lam * (ng.grad(u) * e_z)[2])
    return float(form.lam_scale * integrate(rate, mesh, ng.BND,
                                            definedon=mesh.Boundaries("arc")))


def edge_flux(form) -> float:
    """int c_e p u_z dl along the contact's lateral edge ``arc_edge`` (a volume flux: the
    layer's flux out through the edge with nu = e_z, written out here; the edge runs along
    t within the spread's slope)."""
    import ngsolve as ng

    from hotroll.fem.reproducible import integrate

    mesh, u, lam = form.mesh, form.nonlinear.velocity, form.multiplier
    depth = ng.y if form.strip_depth is None else ng.IfPos(ng.y - form.strip_depth,
                                                           form.strip_depth, ng.y)
    return float(form.lam_scale * integrate(form.compliance * depth * lam * u[2], mesh,
                                            ng.BBND, definedon=mesh.BBoundaries("arc_edge")))


def _multiplier_rows(form, cf) -> float:
    """The sum over the multiplier's rows of the residual of the form ``cf`` (the constraint's
    layer terms) at the form's state: the terms tested with xi = 1 (P1: the multiplier's
    shape functions sum to 1), in the form's units (s^2 K^-1 per unit flux)."""
    import ngsolve as ng

    fes = form.fes
    residual = ng.BilinearForm(fes, nonassemble=True)
    residual += cf if isinstance(cf, ng.comp.SumOfIntegrals) else cf.MakeBFI()
    r = form.nonlinear.gf.vec.CreateVector()
    residual.Apply(form.nonlinear.gf.vec, r)
    m = fes.Range(2)
    return float(np.sum(r.FV().NumPy()[m.start:m.stop]))


def layer_terms(form) -> dict[str, float]:
    """The layer's terms in the constraint tested with xi = 1 at the form's state, as volume
    fluxes (m^3/s of the quarter, as int u.n dA): ``rate`` int div F dA (the upwinded test
    function is 1), ``start`` int F.nu over the start line, ``edge`` over ``arc_edge``."""
    import ngsolve as ng

    (u, _, lam), (_, _, xi) = form.fes.TnT()
    n, t = form.roll_frame()
    depth, slope = form.layer_depth()
    scale = form.lam_scale               # s^2 K^-1 F -> s F
    rate = form.elastic_rate(u, lam, xi, t, n, depth, slope) * ng.ds(
        form.MULTIPLIER_ON, bonus_intorder=2)
    out = {"rate": _multiplier_rows(form, rate) / scale}
    lines = form.layer_ends(u, lam, xi, t, depth)
    for part, name in zip(lines, ("start", "edge")):
        out[name] = _multiplier_rows(form, part) / scale
    return out


def layer_jacobian_error(form, seed: int = 0, eps: float = 1e-3, away: float = 0.1) -> float:
    """The largest difference, over the free rows, between the layer's Jacobian (``constraint``
    with ``u_w``, ``lam_w``: what Newton assembles, the rigid terms s (lambda v.n + xi u.n)
    taken off) applied to a random direction d and the central difference of the layer's
    residual along d, over the largest of that difference. The residual is quadratic in (u,
    lambda), so the central difference is its derivative to round-off for any eps. At the
    form's state moved ``away`` (velocity: of U; multiplier: of its largest) at random, so
    that every part is non-zero (a 3D state with u_z everywhere). The state is put back."""
    import ngsolve as ng

    fes, nl = form.fes, form.nonlinear
    keep = nl.gf.vec.CreateVector()
    keep.data = nl.gf.vec
    rng = np.random.default_rng(seed)
    free = np.array(list(fes.FreeDofs()), dtype=bool)
    p, m = fes.Range(1), fes.Range(2)
    moved = free.copy()
    moved[p.start:p.stop] = False           # the pressure is not in the constraint
    x = nl.gf.vec.FV().NumPy()
    scale = np.full(len(x), form.U.Get())
    scale[m.start:m.stop] = np.abs(x[m.start:m.stop]).max()
    x[:] += away * scale * rng.standard_normal(len(x)) * moved
    (u, _, lam), (v, _, xi) = fes.TnT()
    n, _ = form.roll_frame()
    rigid = form._lam * (lam * (v * n) + xi * (u * n)) * ng.ds(form.MULTIPLIER_ON,
                                                                bonus_intorder=2)
    residual = ng.BilinearForm(fes, nonassemble=True)
    residual += form.constraint(u, v, lam, xi) - rigid
    gu, _, gl = nl.gf.components
    jacobian = ng.BilinearForm(fes)
    jacobian += form.constraint(u, v, lam, xi, u_w=gu, lam_w=gl) - rigid
    jacobian.Assemble()
    d = nl.gf.vec.CreateVector()
    d.FV().NumPy()[:] = scale * rng.standard_normal(len(x)) * moved
    plus, minus, r_plus, r_minus, jd = (d.CreateVector() for _ in range(5))
    plus.data = nl.gf.vec + eps * d
    minus.data = nl.gf.vec - eps * d
    residual.Apply(plus, r_plus)
    residual.Apply(minus, r_minus)
    jd.data = jacobian.mat * d
    nl.gf.vec.data = keep
    fd = (r_plus.FV().NumPy() - r_minus.FV().NumPy())[free] / (2.0 * eps)
    return float(np.abs(jd.FV().NumPy()[free] - fd).max() / np.abs(fd).max())
