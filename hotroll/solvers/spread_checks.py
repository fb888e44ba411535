"""Checks of a solved 3D pass (issue 53, ``solvers/spread_3d.Spread3D``): the power balance of
its form and how far its mid-width plane is from the 2D pass (the plane-strain limit)."""
from __future__ import annotations

import numpy as np

from hotroll.fem.reproducible import fe_space, integrate
from hotroll.solvers.spread_contact import level_contact, plane_contact, read_at


def power_balance(s3, torque: float) -> dict:
    """The power balance of (3.6) of the solved ``Spread3D`` ``s3``, tested with the velocity
    itself, of the quarter (W): the roll's power, the quarter's torque ``torque`` (N m)
    times omega (the shear's power at the rim's speed), and the tensions' on the cut faces against the plastic power
    int mu eps:eps dV, the friction's int k_f |v_s|^2 dA and the contact pressure's
    int p u.n dA; the error |roll + tension - plastic - friction - contact| / roll (the
    penalties, inactive in a pass the roll drives, left out)."""
    import ngsolve as ng

    from hotroll.fem.forms import strain_rate
    from hotroll.model.material import edot_squared

    f, mesh, K = s3.form, s3.mesh, s3.problem.material.K
    u = f.nonlinear.velocity
    eps = strain_rate(u)
    mu = f.material.viscosity(edot_squared(eps), m=f.m_material, K=f.consistency)
    s, kf = f.slip(u), f.friction_coefficient(u)
    nn = ng.specialcf.normal(3)
    plastic = K * integrate(mu * ng.InnerProduct(eps, eps), mesh, ng.VOL)
    friction = K * f.integrate_friction(f.chi * kf * (s * s))
    # the contact pressure's power on the strip, p u.n: zero to round-off on a rigid-plastic
    # strip (the constraint u.n = 0 against every P1 function), the elastic surface's rate
    # with the strip's elasticity (fem/quantities.integrals, 2D, the same)
    n, _ = f.roll_frame()
    contact = K * integrate(f.pressure(u) * (u * n), mesh, ng.BND,
                            definedon=mesh.Boundaries("arc"))
    roll = torque * s3.problem.rp.omega
    tension = K * (integrate(f.tension_back * (u * nn), mesh, ng.BND,
                             definedon=mesh.Boundaries("in"))
                   + integrate(f.tension_front * (u * nn), mesh, ng.BND,
                               definedon=mesh.Boundaries("out")))
    return {"plastic_power": plastic, "friction_power": friction, "roll_power": roll,
            "tension_power": tension, "contact_power": contact, "power_balance_error":
                abs(roll + tension - plastic - friction - contact) / max(abs(roll), 1e-300)}

def midplane_deviation(s3) -> dict:
    """How far the mid-width plane (z = 0) of ``s3`` is from the 2D pass: the largest difference of
    the pressure at its vertices over the 2D pass's largest |p|, its root mean square over
    the 2D pressure's (the whole plane: ahead of the bite and after it too), the same two
    of the contact pressure at the arc's vertices (the bite), and the largest difference
    of the velocity at its P2 nodes over the roll speed (all 0 with the edge held; the
    plane-strain limit of a wide strip)."""
    f2, f3 = s3.run2d.form, s3.form
    g2, g3 = f2.nonlinear.gf, f3.nonlinear.gf
    out = {}
    P2, P3 = g2.components[1], g3.components[1]
    mid = np.zeros_like(P2.vec.FV().NumPy())
    s3.copy.take(0, P3.space, P3.vec.FV().NumPy(), P2.space, mid)
    p2 = P2.vec.FV().NumPy()
    out["midplane_pressure_deviation"] = float(np.abs(mid - p2).max() / np.abs(p2).max())
    # ... and its root mean square over the vertices, over the 2D pressure's (the largest
    # sits where the pressure peaks at the contact's start)
    out["midplane_pressure_rms_deviation"] = float(np.sqrt(np.mean((mid - p2) ** 2))
                                                   / np.sqrt(np.mean(p2 ** 2)))
    # the contact pressure on the arc at mid-width (level 0, as the 2D pass reads its own:
    # solvers/spread_contact.py) against the 2D pass's at the same x: what the roll feels,
    # the bite only. The level's own contact start and end move its vertices along the
    # arc, so the 3D pressure is read at the 2D vertices' x (``spread_contact.read_at``)
    two, lev = plane_contact(s3.run2d), level_contact(s3)
    c2 = two["traction"]
    c3 = read_at(two["x"], lev["x"][0], lev["traction"][0],
                 s3.run2d.s.surface_tol * s3.problem.h)
    out["midplane_contact_pressure_deviation"] = float(np.abs(c3 - c2).max()
                                                       / np.abs(c2).max())
    out["midplane_contact_pressure_rms_deviation"] = float(
        np.sqrt(np.mean((c3 - c2) ** 2)) / np.sqrt(np.mean(c2 ** 2)))
    # ... and in L2 along the arc (trapezoid over the 2D vertices' x): the vertex RMS
    # weighs each vertex alike, so a mesh refined at the contact's start weighs its
    # singular corner more; the L2 norm is the mesh's limit
    x = np.asarray(two["x"], dtype=float)
    out["midplane_contact_pressure_l2_deviation"] = float(
        np.sqrt(np.trapezoid((c3 - c2) ** 2, x) / np.trapezoid(c2 ** 2, x)))
    V2 = g2.components[0]
    u2 = V2.vec.FV().NumPy()
    mid = np.zeros_like(u2)
    s3.copy.take_vector(0, g3.components[0], V2.space.components[0], mid, 2)
    out["midplane_velocity_deviation"] = (float(np.abs(mid - u2).max())
                                          / s3.problem.rp.u_roll)
    out.update(midplane_stress_deviation(s3))
    return out


def _stress(form, plane: bool) -> list:
    """The Cauchy stress (reduced) of ``form``'s solution, sigma = mu(edot) eps_dot - p I
    ((2.18), (2.21)): xx, yy, zz, xy; plane strain's sigma_zz = -p (eps_zz = 0)."""
    from hotroll.fem.forms import strain_rate
    from hotroll.model.material import edot_squared

    e = strain_rate(form.nonlinear.velocity)
    p = form.nonlinear.pressure
    mu = form.material.viscosity(edot_squared(e), m=form.m_material, K=form.consistency)
    zz = -p if plane else mu * e[2, 2] - p
    return [mu * e[0, 0] - p, mu * e[1, 1] - p, zz, mu * e[0, 1]]


#: the stress components ``_stress`` returns, and their weights in the Frobenius norm
STRESS_COMPONENTS = (("xx", 1.0), ("yy", 1.0), ("zz", 1.0), ("xy", 2.0))


def bite_regions(s3) -> dict:
    """Indicators (CoefficientFunctions of x on the 2D mesh) of the mid-width plane's parts:
    ``ahead`` of the 2D contact's start, the ``bite`` from its start to its end, ``after``."""
    import ngsolve as ng

    two = plane_contact(s3.run2d)
    xs, xe = float(np.min(two["x"])), float(np.max(two["x"]))
    return {"ahead": ng.IfPos(xs - ng.x, 1.0, 0.0),
            "bite": ng.IfPos(ng.x - xs, 1.0, 0.0) * ng.IfPos(xe - ng.x, 1.0, 0.0),
            "after": ng.IfPos(ng.x - xe, 1.0, 0.0)}


def midplane_stress_parts(s3, regions: dict, fields: dict | None = None) -> tuple[dict, dict]:
    """int chi w (sigma_3D - sigma_2D)^2 and int chi w sigma_2D^2 over the mid-width plane
    (reduced stresses) per region ``chi`` of ``regions`` and component (keys (region, name)):
    each component set into P2 on both meshes (the same ``Set``), the 3D one read in layer 0
    onto the 2D mesh. ``fields``: filled with each component's P2 vectors, 2D and 3D."""
    import ngsolve as ng

    mesh2 = s3.run2d.mesh
    V2 = fe_space(ng.H1, mesh2, order=2)
    V3 = fe_space(ng.H1, s3.mesh, order=2)
    g2, g3, mid = ng.GridFunction(V2), ng.GridFunction(V3), ng.GridFunction(V2)
    diff, norm = {}, {}
    for (name, w), c2, c3 in zip(STRESS_COMPONENTS, _stress(s3.run2d.form, True),
                                 _stress(s3.form, False)):
        g2.Set(c2)
        g3.Set(c3)
        mid.vec[:] = 0.0
        s3.copy.take(0, V3, g3.vec.FV().NumPy(), V2, mid.vec.FV().NumPy())
        for part, chi in regions.items():
            diff[part, name] = w * integrate(chi * (mid - g2) ** 2, mesh2, ng.VOL)
            norm[part, name] = w * integrate(chi * g2 ** 2, mesh2, ng.VOL)
        if fields is not None:
            fields[name] = (g2.vec.FV().NumPy().copy(), mid.vec.FV().NumPy().copy())
    return diff, norm


def midplane_stress_deviation(s3) -> dict:
    """The stress tensor on the mid-width plane (z = 0) of ``s3`` against the 2D pass's, in L2
    over the plane (Frobenius, sigma_xy twice; ``midplane_stress_parts``), over the 2D
    stress's norm, the whole plane and the bite (x from the 2D contact's start to its end:
    the deforming zone; ahead of it and after it a 3D strip's rigid zones carry a width-wise
    sigma_zz that balances the bite's across the mid-width plane, which plane strain cannot:
    docs/validation/spread_3d.md, "The mid-width stresses")."""
    diff, norm = midplane_stress_parts(s3, {"whole": 1.0, "bite": bite_regions(s3)["bite"]})

    def ratio(part):
        return float(np.sqrt(sum(v for (p, _), v in diff.items() if p == part)
                             / sum(v for (p, _), v in norm.items() if p == part)))

    return {"midplane_stress_l2_deviation": ratio("whole"),
            "midplane_bite_stress_l2_deviation": ratio("bite")}
