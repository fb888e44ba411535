"""Classical (slab) rolling theory: a numerical von Karman / Orowan solver and closed forms.

Per unit width, SI units.  numpy + scipy only.

* :func:`solve_pass` -- slab equation with exact circular-arc geometry (or von Karman's
  small-angle form), Coulomb / Tresca / sticking friction, strain-, rate- and
  temperature-dependent flow stress, tensions; force, torque, neutral point, forward slip.
* :func:`sims` -- Sims (1954) closed form for sticking friction.
* :func:`ford_alexander` -- Ford & Alexander (1963/64) simplified load formula.
* :func:`profile_slip_offset`, :func:`slip_error_bound` -- slab theory's forward-slip error in
  the thin-gap limit, to leading order.
"""

from hotroll.theory.ford_alexander import FordAlexanderResult, ford_alexander, ford_alexander_factor
from hotroll.theory.sims import SimsResult, sims, sims_force_factor, sims_neutral_angle
from hotroll.theory.slab import (
    Coulomb,
    NoNeutralPointError,
    SlabResult,
    Sticking,
    Tresca,
    constant_flow_stress,
    solve_pass,
)
from hotroll.theory.thin_gap import profile_slip_offset, slip_error_bound

__all__ = [
    "Coulomb", "Tresca", "Sticking", "constant_flow_stress", "solve_pass", "SlabResult",
    "NoNeutralPointError", "sims", "SimsResult", "sims_force_factor", "sims_neutral_angle",
    "ford_alexander", "FordAlexanderResult", "ford_alexander_factor", "profile_slip_offset",
    "slip_error_bound",
]
