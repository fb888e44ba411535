"""The figures of a full-thickness solve, per roll (issue 52): forces, torques, powers, the
neutral points and forward slips, the entry guide's reaction, the exit's rotation and
curvature, and the balances (identities of any converged solve: labelled so).

Signs: a roll's force is the strip's push on it along its own axis direction (both positive
in rolling); its torque and power are what its drive supplies (negative: the strip drives the
roll). Curvature kappa > 0: the strip curls up (towards the upper roll), from the exit's rigid
rotation Omega (counter-clockwise > 0) over its centreline speed (../shared/notes/
asymmetric-rolling.md 4.4).
"""
from __future__ import annotations

import math

import numpy as np

from hotroll.fem import quantities as Q
from hotroll.fem.gap_form import ARCS, SURFACES
from hotroll.fem.reproducible import integrate
from hotroll.model.contact_figures import neutral_point
from hotroll.model.material import edot_squared

NAMES = {1: "upper", -1: "lower"}


def strip_force(run, side: int, K: float) -> list[float]:
    """(x, y) of the force (N/m) the roll on ``side`` exerts on the strip: the pressure's -p n
    and the friction's shear over its contact."""
    from ngsolve import BND, CF, IfPos, y

    form, mesh = run.form, run.mesh
    u = form.nonlinear.velocity
    n, t = form.roll_frame()
    on = IfPos(side * y, 1.0, 0.0)
    kf_s_t = form.friction_coefficient(u) * form.slip(u) * t
    return [-K * integrate(CF(on * form.pressure(u) * n[i]).Compile(), mesh, BND,
                           definedon=mesh.Boundaries(ARCS))
            - K * form.integrate_friction(on * form.chi * kf_s_t[i]) for i in range(2)]


def gap_measure(run, K: float) -> dict:
    """One history row of ``FullSteadyRun`` (SI; stresses times K)."""
    from ngsolve import BND, CF, VOL, IfPos, InnerProduct, specialcf, sqrt, x, y

    form, mesh = run.form, run.mesh
    u = form.nonlinear.velocity
    chi = form.chi
    n, t = form.roll_frame()
    s = form.slip(u)
    kf = form.friction_coefficient(u)
    nh = specialcf.normal(2)

    def bnd(cf, region):
        return integrate(CF(cf).Compile(), mesh, BND, definedon=mesh.Boundaries(region))

    out = {}
    sec_in, sec_out = Q.face_flow(form, "in"), Q.face_flow(form, "out")
    for side, name in NAMES.items():
        rp = run.rolls[side]
        on = IfPos(side * y, 1.0, 0.0)
        cx, cy = rp.centre
        cy = side * cy
        r = sqrt((x - cx) ** 2 + (y - cy) ** 2)
        f_strip = strip_force(run, side, K)
        prof = run.side_profile(side, K)
        (xn, _), angle = neutral_point(prof, rp)
        # the shear's power at the rim's speed and the torque that supplies it, power / omega
        # (the half model's, quantities.measure): r = R on the circle, R (1 + e_tt) on a
        # flattening roll's rim
        speed, arm = form.U_side[side], r
        if rp.shape is not None:
            speed = form.roll_speed()
            arm = speed / rp.omega
        out.update({
            f"{name}_roll_force": -side * f_strip[1],
            f"{name}_horizontal_force": f_strip[0],
            f"{name}_roll_torque": K * form.integrate_friction(on * chi * (-kf * s) * arm),
            f"{name}_roll_power": K * form.integrate_friction(on * chi * (-kf * s) * speed),
            f"{name}_contact_length": bnd(on * chi, ARCS),
            f"{name}_neutral_angle": angle,
            f"{name}_neutral_x": xn,
            f"{name}_contact_start": run.shapes[side].x_c,
            f"{name}_contact_end": run.shapes[side].end(rp),
            f"{name}_min_contact_pressure": float(np.min(-prof["normal_stress"]))
            if len(prof["normal_stress"]) else math.nan,
        })
    eps = strain_rate_of(u)
    e2 = edot_squared(eps)
    mu = form.material.viscosity(e2, m=form.m_material, K=form.consistency)
    out["plastic_power"] = K * integrate((mu * InnerProduct(eps, eps)).Compile(), mesh, VOL)
    out["friction_power"] = K * form.integrate_friction(chi * kf * s * s)
    out["tension_power"] = K * (bnd(form.tension_back * (u * nh), "in")
                                + bnd(form.tension_front * (u * nh), "out"))
    inlet = form.inlet_penalty(u, u) * u[0]
    outlet = form.outlet_penalty(u, u) * u[0]
    out["penalty_power"] = K * (bnd((1 - chi) * IfPos(x - form.x_split, outlet, inlet), SURFACES)
                                + bnd(inlet, "in") + bnd(outlet, "out"))
    supplied = out["upper_roll_power"] + out["lower_roll_power"] + out["tension_power"]
    spent = out["plastic_power"] + out["friction_power"] + out["penalty_power"]
    out["power_balance_error"] = abs(supplied - spent) / max(abs(supplied), 1e-300)
    # the entry guide's vertical force on the strip: the inlet's Dirichlet rows v_y = 0
    out["entry_guide_force_y"] = Q.dirichlet_reaction_y(form, K)
    out["vertical_balance_error"] = abs(
        -out["upper_roll_force"] + out["lower_roll_force"] + out["entry_guide_force_y"]) / max(
        out["upper_roll_force"], 1e-300)
    out["roll_force"] = 0.5 * (out["upper_roll_force"] + out["lower_roll_force"])
    # the cross-shear zone: between the two rolls' neutral points (m; 0 for equal rolls)
    out["cross_shear_length"] = abs(out["upper_neutral_x"] - out["lower_neutral_x"])
    out.update(exit_rotation(run))
    out["exit_surface_curvature"] = exit_surface_curvature(run)
    out.update(exit_shear(run))
    # a curling strip crosses the vertical outlet inclined by theta: its thickness there is
    # the projected height times cos theta, its centreline speed the flux over that
    # (face_flow's flux / height is the speed times cos theta)
    cos_out = math.cos(out["outlet_angle"])
    h_exit = sec_out["thickness"] * cos_out
    v_exit = sec_out["flux"] / h_exit if h_exit > 0 else math.nan
    out.update({"entry_velocity": sec_in["velocity"], "exit_velocity": v_exit,
                "mass_flux_in": sec_in["flux"], "mass_flux_out": sec_out["flux"],
                "exit_thickness_measured": h_exit})
    for side, name in NAMES.items():
        out[f"{name}_forward_slip"] = v_exit / run.rolls[side].u_roll - 1.0
    return out


def strain_rate_of(u):
    from hotroll.fem.forms import strain_rate

    return strain_rate(u)


def exit_rotation(run) -> dict:
    """The exit's rigid motion v = V0 + Omega e_z x (x - x0), fitted by least squares to the
    velocity at the P2 nodes of the strip's last half downstream of the gap: Omega (1/s),
    kappa = Omega / |V| (1/m), the exit direction (rad, > 0 upwards) and the fit's residual
    over |Omega| h (a rigid exit: small)."""
    nodes = run.map.nodes
    pos = nodes.X0 + nodes.values(run.d).T
    vel = nodes.values(run.form.nonlinear.gf.vec.FV().NumPy()).T
    axis = run.problem.rp.axis_x
    x_out = float(pos[:, 0].max())
    on = pos[:, 0] > axis + 0.5 * (x_out - axis)
    X, Y = pos[on, 0], pos[on, 1]
    n = int(on.sum())
    # unknowns (a, b, Omega): v_x = a - Omega y, v_y = b + Omega x
    A = np.zeros((2 * n, 3))
    A[:n, 0], A[:n, 2] = 1.0, -Y
    A[n:, 1], A[n:, 2] = 1.0, X
    rhs = np.concatenate([vel[on, 0], vel[on, 1]])
    sol, *_ = np.linalg.lstsq(A, rhs, rcond=None)
    a, b, omega = sol
    xm, ym = float(X.mean()), float(Y.mean())
    vx, vy = a - omega * ym, b + omega * xm
    speed = math.hypot(vx, vy)
    resid = float(np.sqrt(np.mean((A @ sol - rhs) ** 2)))
    h1 = 2.0 * run.rolls[1].half_exit
    # the direction at the outlet face's centre: the strip crosses it inclined
    out = pos[:, 0] >= x_out - 1e-12 * max(1.0, abs(x_out))
    y_out = 0.5 * (float(pos[out, 1].min()) + float(pos[out, 1].max()))
    return {"exit_rotation_rate": float(omega), "exit_curvature": float(omega) / speed,
            "exit_angle": math.atan2(vy, vx),
            "outlet_angle": math.atan2(b + omega * x_out, a - omega * y_out),
            "exit_rotation_fit_residual": resid / max(abs(omega) * h1, 1e-300)}


def exit_surface_curvature(run) -> float:
    """The exit's curvature from its shape, not its velocity (note 4.4's cross-check): the
    centreline between the two traced free surfaces, y_c = (y_upper + y_lower)/2, over the
    last half of the exit strip, fitted by a parabola; kappa = y_c'' / (1 + y_c'^2)^(3/2) at
    the zone's middle (1/m, > 0 curls up)."""
    nodes = run.map.nodes
    X = nodes.X0[:, 0] + nodes.values(run.d)[0]
    axis = run.problem.rp.axis_x
    x_out = float(X.max())
    xs = np.linspace(axis + 0.5 * (x_out - axis), x_out, 41)
    ys = []
    for side in (1, -1):
        sh = run.shapes[side]
        ys.append(side * np.interp(xs, sh.exit_x, sh.exit_y))
    yc = 0.5 * (ys[0] + ys[1])
    a, b, _ = np.polyfit(xs - xs.mean(), yc, 2)
    return float(2.0 * a / (1.0 + b * b) ** 1.5)


def exit_shear(run) -> dict:
    """The through-thickness shear the pass leaves in the strip: the engineering shear strain
    gamma_xy carried along the streamlines (``fem/strain.py: ShearStrainField``) at the outlet,
    at its upper and lower surfaces and at mid-thickness (linear between the outlet's
    vertices), and its thickness mean (-)."""
    from hotroll.fem.strain import ShearStrainField

    field = getattr(run, "_shear_field", None)
    if field is None:
        field = run._shear_field = ShearStrainField(run.mesh)
    field.transport(run.form.nonlinear.velocity)
    nv = run.mesh.nv
    n = run.map.nodes.n
    y_now = run.map.nodes.X0[:nv, 1] + run.d[n:n + nv]
    y, gamma = field.on_boundary("out", y_now)
    mid = 0.5 * (y[0] + y[-1])
    mean = float(np.trapezoid(gamma, y) / (y[-1] - y[0])) if len(y) > 1 else math.nan
    return {"exit_shear_strain_upper": float(gamma[-1]),
            "exit_shear_strain_lower": float(gamma[0]),
            "exit_shear_strain_mid": float(np.interp(mid, y, gamma)),
            "exit_shear_strain_mean": mean}
