"""The forward slip in the thin-gap limit: slab theory's error, to leading order.

Limit: l/h -> infinity at a fixed reduction (l = sqrt(R dh)), Coulomb mu (or a Tresca
factor) proportional to h/l, so that the friction hill stays O(1) while the shear stays small
against k.  With delta = h/l the slab equation is the leading order of the plane-strain
equations; what it drops is O(delta^2): the shear in the yield condition ((tau/k)^2), the
variation of the vertical stress over the section and the tilt of the roll's normal (both
(h/l) tau/k or alpha^2), and the velocity profile over the section.  The last one moves the
forward slip directly, so it is computed here (docs/testing.md, "The forward slip against the
thin-gap limit").

Velocity profile at the neutral section.  Half thickness a(x), flux Q = u_mean a.  To leading
order the vertical velocity is the homogeneous one, v = u y a'/a, and the shear stress
vanishes at the neutral section (the surface shear changes sign there and sigma_xy ~ tau y/a),
so du/dy = -dv/dx = -y Q (a''/a^2 - 2 a'^2/a^3) and

    (u_mean - u_surface) / u_surface = a a''/3 - (2/3) a'^2
                                     = h_n / (6 R cos^3 phi_n) - (2/3) tan^2 phi_n

(a' = tan phi, a'' = 1/(R cos^3 phi) on the arc).  The surface moves with the roll there,
u_surface = U cos phi_n, which is the slab's section velocity; so the true flux exceeds the
slab's by that factor and

    f_true - f_slab = (1 + f_slab) (h_n / (6 R cos^3 phi_n) - (2/3) tan^2 phi_n) + s,

s the slip change from the neutral point's own O(delta^2) shift (the dropped stress terms),
not computed here.  Both terms are O(delta^2): h_n/R = (h_n/l)^2 dh/h_n and phi_n < alpha ~
dh/l.
"""
from __future__ import annotations

import math


def profile_slip_offset(roll_radius: float, neutral_thickness: float, neutral_angle: float,
                        forward_slip: float) -> float:
    """(1 + f) (h_n / (6 R cos^3 phi_n) - (2/3) tan^2 phi_n): the forward slip the velocity
    profile over the neutral section adds to the slab's (module docstring)."""
    c = math.cos(neutral_angle)
    return (1.0 + forward_slip) * (neutral_thickness / (6.0 * roll_radius * c ** 3)
                                   - 2.0 / 3.0 * math.tan(neutral_angle) ** 2)


def slip_error_bound(roll_radius: float, neutral_thickness: float, neutral_angle: float,
                     forward_slip: float) -> float:
    """A bound on |f_FE - f_slab| in the thin-gap limit: twice the profile term with both its
    parts counted positive, the factor 2 an allowance for the uncomputed neutral-point shift
    of the same order."""
    c = math.cos(neutral_angle)
    return 2.0 * (1.0 + abs(forward_slip)) * (neutral_thickness / (6.0 * roll_radius * c ** 3)
                                              + 2.0 / 3.0 * math.tan(neutral_angle) ** 2)
