"""Engineering quantities from a solved configuration: tractions, forces, powers, fluxes.

Contact tractions are the consistent ones of the penalised form (seed-reading notes): the normal
stress is the penalty reaction sigma_n = -K gamma_vC (v.n), the shear the friction law (2.29a).
Everything is computed in reduced units (K = 1) and multiplied by K here.
"""
from __future__ import annotations

import math

import numpy as np

from hotroll.fem.forms import strain_rate
from hotroll.fem.reproducible import fe_space, integrate, parallel
from hotroll.fem.rolling_form import TOP, RollingForm
from hotroll.fem.top_boundary import TopBoundary
from hotroll.model.contact_figures import (  # noqa: F401 (re-exported)
    STICKING_FLOOR,
    contact_loss,
    exit_corrected,
    flux_neutral_angle,
    neutral_index,
    neutral_point,
    slip_sign_changes,
    smoothed,
    sticking_zone,
)
from hotroll.model.material import edot_squared


# --- nodal values on the top boundary ------------------------------------------------------
def top_nodes(form: RollingForm, top: TopBoundary, disp: np.ndarray, contact_only: bool):
    """(xy, velocity) at the top-boundary P2 nodes (vertices, then edge midpoints)."""
    verts = top.verts[top.vertex_contact] if contact_only else top.verts
    rows = np.nonzero(top.edge_contact)[0] if contact_only else np.arange(len(top.edge))
    vel = form.nonlinear.gf.vec.FV().NumPy()
    xy = np.vstack([top.vertex_positions(disp, verts), top.midpoint_positions(disp, rows)])
    return xy, np.vstack([top.vertex_values(vel, verts), top.midpoint_values(vel, rows)])


def contact_profile(form: RollingForm, top: TopBoundary, disp: np.ndarray, K: float,
                    vertex_values: dict[str, np.ndarray] | None = None) -> dict:
    """Slip, normal and shear stress at the contact nodes, sorted from entry to exit;
    ``vertex_values``: more columns from fields given at the mesh vertices (e.g. the
    temperature), read as ``at_top_nodes`` reads them."""
    rp, pen = form.rp, form.penalties
    extra = vertex_values or {}
    xy, vel = top_nodes(form, top, disp, contact_only=True)
    if len(xy) == 0:
        return {k: np.zeros(0) for k in ("x", "y", "angle", "v_slip", "normal_stress",
                                          "shear_stress", "vertex", *extra)}
    vertex = np.arange(len(xy)) < int(top.vertex_contact.sum())   # vertices come first
    ang = rp.angle(xy)
    order = np.argsort(-ang)
    xy, vel, ang, vertex = xy[order], vel[order], ang[order], vertex[order]
    n, t = rp.normal(xy), rp.tangent(xy)
    slip = np.sum(vel * t, -1) - rp.u_roll
    if form.exact:      # the multiplier's nodal traction (``nodal_traction``), a midpoint the
        # mean of its vertices
        multiplier = at_top_nodes(form.vertex_pressure(), top, contact_only=True)[order]
        pressure = nodal_traction(xy, multiplier, vertex)
    else:               # the penalty reaction
        pressure = pen.at_nodes(xy[:, 0], rp.soft_zone) * np.sum(vel * n, -1)
    k = _nodal_k(form, top, contact_only=True)
    k = None if k is None else k[order]
    # the friction law at the nodes as the form evaluates it: of the multiplier's own values
    shear = K * np.asarray(form.law.shear(slip, a_f=form.a_f.Get(), m=form.m.Get(),
                                               pressure=multiplier if form.exact else pressure,
                                               k=k))
    out = {"x": xy[:, 0], "y": xy[:, 1], "angle": ang, "v_slip": slip,
           "normal_stress": -K * pressure, "shear_stress": shear, "vertex": vertex.astype(int)}
    if form.exact:      # the multiplier's own nodal values (the FE function the form integrates)
        out["normal_stress_multiplier"] = -K * multiplier
    if k is not None:
        out["shear_flow_stress"] = K * k
    for name, values in extra.items():
        out[name] = at_top_nodes(values, top, contact_only=True)[order]
    return out


def nodal_traction(xy: np.ndarray, pressure: np.ndarray, vertex: np.ndarray) -> np.ndarray:
    """The contact pressure as the multiplier's nodal forces over their lengths, p_i =
    int lambda phi_i ds / int phi_i ds (phi_i the P1 hat functions of the arc's vertices; the
    nodal value of the dual, biorthogonal multiplier basis, Wohlmuth 2000), at nodes ordered
    along the arc (vertices and edge midpoints alternating, ``vertex`` marking the vertices);
    the two end vertices keep the multiplier's values (the complementarity's pressure at the
    contact's end); a midpoint the mean of its vertices. The multiplier's own nodal values carry the P1 mass
    matrix's ringing (a ratio of -(2 - sqrt3) = -0.27 per vertex) where the traction changes
    abruptly (the entry corner); the interior forces are the same."""
    iv = np.flatnonzero(vertex)
    if len(iv) < 2:
        return pressure
    p = pressure[iv]
    L = np.hypot(*np.diff(xy[iv], axis=0).T)
    force = np.zeros_like(p)
    force[:-1] += L * (p[:-1] / 3.0 + p[1:] / 6.0)
    force[1:] += L * (p[1:] / 3.0 + p[:-1] / 6.0)
    length = np.zeros_like(p)
    length[:-1] += 0.5 * L
    length[1:] += 0.5 * L
    out = pressure.copy()
    # the arc's two end vertices keep the multiplier's value: a half hat's mean leans to the
    # inside (an end where the pressure falls to zero would read a third of its neighbour)
    out[iv[1:-1]] = (force / length)[1:-1]
    mids = np.flatnonzero(~vertex.astype(bool))
    below = np.searchsorted(iv, mids) - 1
    ok = (below >= 0) & (below + 1 < len(iv))
    out[mids[ok]] = 0.5 * (out[iv[below[ok]]] + out[iv[below[ok] + 1]])
    return out


def at_top_nodes(values: np.ndarray, top: TopBoundary, contact_only: bool) -> np.ndarray:
    """A field given at the mesh vertices, at the top nodes as ``top_nodes`` orders them: the
    vertices' values, then each edge midpoint's as the mean of its two vertices (exact for a P1
    field)."""
    verts = top.verts[top.vertex_contact] if contact_only else top.verts
    rows = np.nonzero(top.edge_contact)[0] if contact_only else np.arange(len(top.edge))
    return np.concatenate([values[verts], 0.5 * (values[top.ea[rows]] + values[top.eb[rows]])])


def _nodal_k(form: RollingForm, top: TopBoundary, contact_only: bool):
    """The friction law's shear flow stress k (reduced) at the top nodes as ``top_nodes`` orders
    them, from its P1 projection (vertices, then edge midpoints: the mean of the two vertices);
    the form evaluates k at its quadrature points."""
    if not form.friction.uses_k:
        return None
    from ngsolve import GridFunction

    k = GridFunction(p1_space(form.mesh))
    k.Set(form.shear_flow_stress(form.nonlinear.velocity))
    return at_top_nodes(k.vec.FV().NumPy(), top, contact_only)


#: The last mesh given to ``p1_space`` and its space (the mesh held: identity stays valid).
_P1: list = [None, None]


def p1_space(mesh):
    """The P1 space (H1, order 1) of ``mesh``, made once for the last mesh asked for: every
    contact profile (each roll update's loads, the measures, the results) made its own before,
    NGSolve's parallel set-up each time (86 in the ten-stand schedule; 35 ms each when another
    process shares the cores). A GridFunction set on it is the same as on a new space."""
    if _P1[0] is not mesh:
        from ngsolve import H1

        _P1[:] = [mesh, fe_space(H1, mesh, order=1)]
    return _P1[1]


def top_profile(form: RollingForm, top: TopBoundary, disp: np.ndarray,
                vertex_values: dict[str, np.ndarray] | None = None) -> dict:
    """Position and velocity of every top node, sorted by x (and the ``vertex_values``
    fields there, as in ``contact_profile``)."""
    xy, vel = top_nodes(form, top, disp, contact_only=False)
    o = np.argsort(xy[:, 0])
    out = {"x": xy[o, 0], "y": xy[o, 1], "v1": vel[o, 0], "v2": vel[o, 1]}
    for name, values in (vertex_values or {}).items():
        out[name] = at_top_nodes(values, top, contact_only=False)[o]
    return out


def measure(form: RollingForm, top: TopBoundary, disp: np.ndarray, K: float, h: float,
            head_x: float) -> dict:
    """The per-configuration figures (SI, stresses times K) recorded by both solvers."""
    rp = form.rp
    prof = contact_profile(form, top, disp, K)
    (xn, yn), ang = neutral_point(prof, rp)
    # any cross-section carries the same flux (incompressible, v.n = 0 on the free top); the
    # tail and head faces are cross-sections the strip crosses rigidly, where the flux integral
    # is exact. The head counts once it is past the bite by l_c/4 (before that: nan).
    sec_in = face_flow(form, "in")
    sec_out = (face_flow(form, "out") if head_x > rp.axis_x + 0.25 * rp.contact_length + 2 * h
               else {"velocity": math.nan, "flux": math.nan, "thickness": math.nan})
    row = {
        "a_f": form.a_f.Get(), "neutral_x": xn, "neutral_y": yn, "neutral_angle": ang,
        "entry_velocity": sec_in["velocity"], "exit_velocity": sec_out["velocity"],
        "mass_flux_in": sec_in["flux"], "mass_flux_out": sec_out["flux"],
        "exit_thickness_measured": 2.0 * sec_out["thickness"],
        "forward_slip": sec_out["velocity"] / rp.u_roll - 1.0, "head_x": head_x,
    }
    row.update(integrals(form, K))
    return row


# --- integrals -------------------------------------------------------------------------------
def integrals(form: RollingForm, K: float) -> dict:
    """Forces, torque and the power balance of (3.6) tested with v itself (all per unit width)."""
    from ngsolve import BND, CF, VOL, IfPos, InnerProduct, specialcf, sqrt, x, y

    mesh, rp, pen, m = form.mesh, form.rp, form.penalties, form.m
    u = form.nonlinear.velocity
    top = mesh.Boundaries(TOP)
    chi = form.chi
    n, t = form.roll_frame()
    s = form.slip(u)
    kf = form.friction_coefficient(u)
    gam = pen.surface(x, rp.soft_zone)
    eps = strain_rate(u)
    e2 = edot_squared(eps)
    mu = form.material.viscosity(e2, m=form.m_material, K=form.consistency)
    cx, cy = rp.centre
    r = sqrt((x - cx) ** 2 + (y - cy) ** 2)

    def bnd(cf, region=top):
        return integrate(CF(cf).Compile(), mesh, BND, definedon=region)

    inlet = form.inlet_penalty(u, u) * u[0]
    outlet = form.outlet_penalty(u, u) * u[0]
    top_pen = gam * form.free_normal(u) ** 2 if form.free_surface == "constrained" else 0.0
    free_pen = bnd((1 - chi) * (top_pen + IfPos(x - form.x_split, outlet, inlet)))
    face_pen = bnd(inlet, mesh.Boundaries("in")) + bnd(outlet + gam * u[1] ** 2,
                                                      mesh.Boundaries("out"))
    # the contact's power on the strip: the penalty's gamma (u.n)^2; with exact contact the
    # multiplier's s lambda~ u.n, zero to round-off (the constraint holds against every P1
    # function, and lambda~ is one)
    contact_pen = (bnd(form.pressure(u) * (u * n), mesh.Boundaries("arc")) if form.exact
                   else bnd(chi * gam * (u * n) ** 2))
    outlet_pen = bnd((1 - chi) * IfPos(x - form.x_split, outlet, 0.0)) + bnd(
        outlet, mesh.Boundaries("out"))
    p = m.Get() + 1.0
    nh = specialcf.normal(2)
    out = {
        "plastic_power": K * integrate((mu * InnerProduct(eps, eps)).Compile(), mesh, VOL),
        "friction_power": K * form.integrate_friction(chi * kf * s * s),
        "penalty_power": K * (free_pen + face_pen + contact_pen),
        "contact_penalty_power": K * contact_pen,
        "outlet_penalty_power": K * outlet_pen,
        # the shear's power at the rim's speed (the pressure does no work on the turning roll)
        # and the torque that supplies it, power / omega: r = R on the circle; R (1 + e_tt)
        # on a flattened roll (its rim keeps its centre distance ~R and its hoop strain)
        "roll_power": K * form.integrate_friction(chi * (-kf * s) * form.roll_speed()),
        "roll_torque": K * form.integrate_friction(
            chi * (-kf * s) * (r if form.roll_hoop is None else form.roll_speed() / rp.omega)),
        # power of the tensions' traction sigma n on the plate (back: < 0, front: > 0)
        "tension_power": K * (bnd(form.tension_back * (u * nh), mesh.Boundaries("in"))
                              + bnd(form.tension_front * (u * nh), mesh.Boundaries("out"))),
        "contact_length": bnd(chi),
        "slip_measure": bnd(chi * IfPos(s * s, (s * s) ** (p / 2), 0.0)),
        "strain_rate_measure": integrate((3.0 * e2 + 1e-300) ** (p / 2), mesh, VOL),
    }
    out.update(force_balance(form, K))
    # the roll's force on the plate, pressing down: the roll force is its vertical part
    out["roll_force"], out["horizontal_force"] = -out["roll_force_y"], out["roll_force_x"]
    out["volume_v_p"], out["backward_length"] = a_f_inputs(form)
    bal = out["plastic_power"] + out["friction_power"] + out["penalty_power"]
    supplied = out["roll_power"] + out["tension_power"]
    out["power_balance_error"] = abs(supplied - bal) / max(abs(out["roll_power"]), 1e-300)
    out["penalty_share"] = out["penalty_power"] / max(abs(out["roll_power"]), 1e-300)
    return out


def force_balance(form: RollingForm, K: float) -> dict:
    """Forces on the plate (N/m, x and y) from each part of its boundary, and the closure error.

    Each is the boundary term of (3.6) tested with a constant vector e_x or e_y (its traction is
    minus the term's integrand): the roll contact (penalty + friction), the penalties on the free
    tops ((3.2d) in the constrained model, the one-sided (3.2a)/(3.2b)), and on the cut faces
    ((3.2a), (3.2b), T*). The symmetry line's reaction is the residual of (3.6) in its Dirichlet
    rows (v_y = 0), summed over its vertices: computed from the volume terms, not from the roll.
    The parts sum to the residual of the free rows, zero at a converged solve:
    ``balance_error`` = |sum| / roll force. ``tension``: the back and front tensions' force.
    ``free_top_force_share``: |free-top force| / roll force.
    """
    from ngsolve import BND, CF, Grad, IfPos, specialcf, x

    mesh, rp = form.mesh, form.rp
    u, chi = form.nonlinear.velocity, form.chi
    n, t = form.roll_frame()
    gam = form.penalties.surface(x, rp.soft_zone)
    s = form.slip(u)
    kf = form.friction_coefficient(u)
    ex = CF((1.0, 0.0))
    friction_term = kf * s * t
    top_term = IfPos(x - form.x_split, form.outlet_penalty(u, u), form.inlet_penalty(u, u)) * ex
    if form.free_surface == "constrained":
        nf = IfPos(x - rp.axis_x, CF((0.0, 1.0)), specialcf.normal(2))
        top_term = top_term + gam * form.free_normal(u) * nf
    faces = {"in": form.inlet_penalty(u, u) * ex,
             "out": form.outlet_penalty(u, u) * ex + gam * u[1] * CF((0.0, 1.0))}
    nh = specialcf.normal(2)

    def force(term, region):
        return [-K * integrate(term[i].Compile(), mesh, BND, definedon=mesh.Boundaries(region))
                for i in range(2)]

    normal = (force(form.pressure(u) * n, "arc") if form.exact
              else force(chi * gam * (u * n) * n, TOP))
    roll = np.add(normal,
                  [-K * form.integrate_friction(chi * friction_term[i]) for i in range(2)])
    tops = force((1 - chi) * top_term, TOP)
    face = np.add(force(faces["in"], "in"), force(faces["out"], "out"))
    # the tensions' traction sigma n on the cut faces (the residual term is -sigma n . v)
    tension = np.add(force(-form.tension_back * nh, "in"), force(-form.tension_front * nh, "out"))
    # symmetry reaction: the residual of (3.6) in the Dirichlet rows v_y = 0, at the vertices
    # (the constant e_y has coefficient 1 there and 0 on the edge bubbles)
    problem = form.nonlinear
    sym_y = dirichlet_reaction_y(form, K)
    # the same reaction from the stress itself: -int sigma_yy dx over the symmetry line. On
    # y = 0 only the tangential derivative is at hand (a boundary integral sees the surface
    # gradient); symmetry (u_y = 0, du_x/dy = 0) and incompressibility give eps_yy = -eps_xx,
    # eps_xy = 0, so sigma_yy = -mu(4/3 eps_xx^2) eps_xx - p: an approximation that converges
    # with h, independent of the residual
    exx = Grad(u)[0, 0]
    mu = form.material.viscosity(4.0 / 3.0 * exx * exx, m=form.m_material, K=form.consistency)
    sigma_yy = -mu * exx - problem.pressure
    sym_stress = -K * integrate(sigma_yy, mesh, BND, definedon=mesh.Boundaries("sym"))
    total = np.add(np.add(roll, tops), np.add(np.add(face, tension), [0.0, sym_y]))
    scale = max(abs(roll[1]), 1e-300)
    out = {"balance_error": float(np.hypot(*total)) / scale, "symmetry_stress_force_y": sym_stress,
           "free_top_force_share": float(np.hypot(*tops)) / scale, "symmetry_force_y": sym_y}
    for name, f in (("roll", roll), ("free_top", tops), ("face", face), ("tension", tension)):
        out[f"{name}_force_x"], out[f"{name}_force_y"] = float(f[0]), float(f[1])
    return out


def dirichlet_reaction_y(form: RollingForm, K: float) -> float:
    """The vertical force (N/m) the Dirichlet rows v_y = 0 carry (the half strip's symmetry
    line, the full strip's inlet guide): the residual of (3.6) in those rows at the vertices,
    summed (the constant e_y has coefficient 1 there and 0 on the edge bubbles)."""
    problem = form.nonlinear
    r = problem.gf.vec.CreateVector()
    with parallel():
        problem.a_newton.Apply(problem.gf.vec, r)
    nv = problem.n_velocity_dofs() // 2
    rows = np.arange(nv, nv + form.mesh.nv)
    fixed = ~problem.free_mask[rows]
    return K * float(np.sum(r.FV().NumPy()[rows[fixed]]))


def a_f_inputs(form: RollingForm) -> tuple[float, float]:
    """The two integrals of (3.15): int_Omega |v|^p dx and the length of Gamma_C^-."""
    from ngsolve import BND, VOL, IfPos, Norm

    u, p = form.nonlinear.velocity, form.m.Get() + 1.0
    vol = integrate((Norm(u) ** 2 + 1e-300) ** (p / 2), form.mesh, VOL)
    back = integrate(form.chi * IfPos(-form.slip(u), 1.0, 0.0), form.mesh, BND,
                     definedon=form.mesh.Boundaries(TOP))
    return vol, back


def face_flow(form: RollingForm, face: str) -> dict:
    """Flux (m^2/s, half model), projected height and mean velocity through the face ``in``
    (tail / inlet) or ``out`` (head / outlet): flux = |int v.n ds|, exact for any face shape."""
    from ngsolve import BND, specialcf

    nh = specialcf.normal(2)
    region = form.mesh.Boundaries(face)
    q = abs(integrate(form.nonlinear.velocity * nh, form.mesh, BND, definedon=region))
    height = abs(integrate(nh[0], form.mesh, BND, definedon=region))
    return {"velocity": q / height if height > 0 else math.nan, "thickness": height, "flux": q}
