"""The weak form (3.6) on the full-thickness strip between two rolls (issue 52).

The half model's form (``rolling_form.RollingForm``) with the symmetry plane taken out and a
second contact: every term that belongs to a roll (its normal and tangent, surface speed,
friction law with its own parameters and a_f) is the upper roll's on y > 0 and the lower
roll's on y < 0 (the strip's mid-plane y = 0 separates the two surfaces: each contact lies on
its own side). One continuous P1 multiplier lives on both arcs, the contact pressure of each.
What changes against the half model (../shared/notes/asymmetric-rolling.md 4.3):

- no ``sym`` condition: the vertical rigid motion is fixed by v_y = 0 on the inlet face (the
  entry guide; its reaction is reported), nothing else holds the exit, which may leave
  inclined and curved;
- no T* (gamma v_y phi_y) on the outlet face, no flat-exit normal: both would clamp the curl;
- the inlet and outlet bounds (3.2a,b) use the slower roll's speed on both sides: the entry is
  slower and the exit faster than it whenever that roll has both slip zones (above the
  saturation ratio the exit is slower than the fast roll).

A flattening roll (its ``RollPass`` with a ``shape``) turns its frame by its surface's tilt and
moves its surface at omega R (1 + e_tt), as the half model's (``RollingForm.roll_frame``): one
P1 tilt and one hoop strain field carry each roll's values on its side's vertices
(``set_roll_shape``), in that roll's own frame (the lower's mirrored), where the formulas are
the half model's.
"""
from __future__ import annotations

from dataclasses import replace

from hotroll.fem.penalties import ScaledPenalties, _elements_on, reference_viscosity
from hotroll.fem.reproducible import fe_space
from hotroll.fem.rolling_form import RollingForm
from hotroll.fem.spaces import taylor_hood
from hotroll.model.friction import FrictionLaw
from hotroll.model.geometry import RollPass
from hotroll.model.material import NortonHoff

#: the boundaries of the full strip (fem/full_strip.py)
ARCS = "arc|arcl"
SURFACES = "top|arc|exit|topl|arcl|exitl"
#: where v_y = 0 holds: the inlet face (the entry guide; free, the strip drifts across the gap:
#: the traced surfaces' fixed point does not hold its height, measured on Example 1)
INLET_GUIDE = "in"


def by_side(upper, lower):
    """The upper roll's value on y > 0, the lower's on y < 0 (CFs or numbers; vectors
    component by component)."""
    from ngsolve import CF, IfPos, y

    dims = getattr(upper, "dim", 1)
    if dims > 1:
        return CF(tuple(IfPos(y, upper[i], lower[i]) for i in range(dims)))
    return IfPos(y, upper, lower)


class SidedFriction:
    """Two friction laws, one per roll, as one law of the form's interface (``FrictionLaw``):
    the coefficient and its partials of each side's law with that side's a_f."""

    def __init__(self, upper: FrictionLaw, lower: FrictionLaw, a_f: dict):
        self.laws = {1: upper, -1: lower}
        self.a_f = a_f
        self.uses_k = upper.uses_k or lower.uses_k
        self.uses_pressure = upper.uses_pressure or lower.uses_pressure
        self.uses_a_f = upper.uses_a_f or lower.uses_a_f

    def _kw(self, side, kw):
        law = self.laws[side]
        return dict(kw, a_f=self.a_f[side], pressure=kw.get("pressure") if law.uses_pressure
                    else None, k=kw.get("k") if law.uses_k else None)

    def coefficient(self, slip2, **kw):
        return by_side(*(self.laws[s].coefficient(slip2, **self._kw(s, kw)) for s in (1, -1)))

    def coefficient_partials(self, slip2, **kw):
        up, lo = (self.laws[s].coefficient_partials(slip2, **self._kw(s, kw)) for s in (1, -1))
        return tuple(by_side(a, b) for a, b in zip(up, lo))


class GapForm(RollingForm):
    """Spaces, parameters and forms of (3.6) on the full strip: ``rolls`` {+1: upper, -1:
    lower} each a ``RollPass`` in its own frame (centre above), ``frictions`` the same."""

    MULTIPLIER_ON = ARCS
    START = "start|startl"

    def __init__(self, mesh, rolls: dict[int, RollPass], material: NortonHoff,
                 frictions: dict[int, FrictionLaw], h: float, tensions: tuple = (0.0, 0.0),
                 consistency=1.0, primal_dual: bool = True, rate_offset=None,
                 strip_compliance: float | None = None, strip_depth: dict | None = None):
        from ngsolve import FacetFESpace, GridFunction, Parameter

        self.mesh, self.rolls = mesh, rolls
        slow = min(rolls.values(), key=lambda r: r.u_roll)
        self.rp = slow                      # the scale of the penalties and the multiplier
        self.free_surface, self.contact = "traced", "multiplier"
        #: the strip's elastic compliance (``RollingForm``'s), or None: rigid-plastic; its
        #: layer's largest depth in each roll's contact ({side: m}: ``Problem.
        #: strip_layer_depth`` of that roll), or None
        self.compliance, self.strip_depth = strip_compliance, strip_depth
        self._mu = Parameter(reference_viscosity(material, slow))
        self.penalties = ScaledPenalties(h, self._mu)
        self._lam = Parameter(self.mu_ref / slow.contact_length)
        self.U_side = {s: Parameter(r.u_roll) for s, r in rolls.items()}
        self.U = Parameter(slow.u_roll)     # the inlet and outlet bounds' speed
        self.v_reg_side = {s: Parameter(f.v_reg) for s, f in frictions.items()}
        self.v_reg = by_side(self.v_reg_side[1], self.v_reg_side[-1])
        self.laws = frictions               # their floats (numpy evaluations)
        self.a_f_side = {s: Parameter(1.0) for s in rolls}
        self.a_f = self.a_f_side[1]          # the half model's name: the upper roll's
        self.friction = SidedFriction(*(replace(frictions[s], v_reg=self.v_reg_side[s])
                                        for s in (1, -1)), self.a_f_side)
        self.law = frictions[1]
        self.material = material
        self.consistency = consistency
        self.fes = taylor_hood(mesh, dirichlety=INLET_GUIDE, multiplier_on=ARCS)
        self.m = Parameter(material.m)
        # m(T) - m_ref where a temperature-dependent law's exponent varies (RollingForm's)
        self.m_material = self.m if rate_offset is None else self.m + rate_offset
        self.x_split_side = {s: Parameter(r.axis_x) for s, r in rolls.items()}
        self.x_split = by_side(self.x_split_side[1], self.x_split_side[-1])
        self.chi = GridFunction(fe_space(FacetFESpace, mesh, order=0))
        self.tension_back, self.tension_front = Parameter(tensions[0]), Parameter(tensions[1])
        self.top_elements = _elements_on(mesh, ARCS) if self.friction.uses_k else None
        self.contact_regions = ARCS
        self.roll_tilt = self.roll_hoop = None
        if any(r.shape is not None for r in rolls.values()):     # a flattening roll
            from ngsolve import H1

            P1 = fe_space(H1, mesh, order=1)
            self.roll_tilt, self.roll_hoop = GridFunction(P1), GridFunction(P1)
            self.roll_cx_side = {s: Parameter(r.centre[0]) for s, r in rolls.items()}
        self._newton_problem(material.eps0, ARCS, slow.u_roll, primal_dual)

    def layer_compliance(self, y, side: int = 1):
        """c_e per unit reduced pressure at half thicknesses ``y`` (m, numbers) in the contact
        of the roll on ``side``: compliance min(y, that roll's strip_depth)."""
        import numpy as np

        depth = y if self.strip_depth is None else np.minimum(y, self.strip_depth[side])
        return self.compliance * depth

    def set_roll_speed(self, rp, v_reg):
        raise NotImplementedError("the full strip's roll speeds are fixed (issue 52 stage 3)")

    def set_roll_shape(self, vertices) -> None:
        """Each flattening roll's tilt and hoop strain at the mesh vertices on its side
        (``vertices``: their current positions, m, full frame), in its own frame (y mirrored
        for the lower roll); a rigid roll's side 0."""
        import numpy as np

        tilt = self.roll_tilt.vec.FV().NumPy()
        hoop = self.roll_hoop.vec.FV().NumPy()
        tilt[:], hoop[:] = 0.0, 0.0
        pts = np.asarray(vertices, dtype=float)
        for side, rp in self.rolls.items():
            if rp.shape is None:
                continue
            self.roll_cx_side[side].Set(rp.centre[0])
            mine = pts[:, 1] * side >= 0.0
            own = pts[mine] * np.array([1.0, side])
            tilt[mine] = rp.tilt(own)
            hoop[mine] = rp.shape.strain(rp.angle(own))

    def roll_frame(self):
        """(n, t) of the roll on each side: n into the roll, t along its surface's motion
        (+x at the contact: the lower roll turns the other way)."""
        from ngsolve import CF, sqrt, x, y

        frames = []
        for side in (1, -1):
            rp = self.rolls[side]
            cx, cy = rp.centre
            cy = side * cy                              # the lower roll's centre below
            if rp.shape is not None:                    # moves with the lowest point
                cx = self.roll_cx_side[side]
            r = sqrt((x - cx) ** 2 + (y - cy) ** 2)
            n = CF(((cx - x) / r, (cy - y) / r))
            t = CF((-side * (y - cy) / r, side * (x - cx) / r))
            frames.append((n, t))
        (n1, t1), (n2, t2) = frames
        n, t = by_side(n1, n2), by_side(t1, t2)
        if self.roll_tilt is None:
            return n, t
        # the tilt in each roll's own frame turns (n, t) as the half model's; mirrored into the
        # full frame the same formula holds for the lower roll (its t keeps +x at the contact)
        from ngsolve import cos, sin

        b = self.roll_tilt
        return cos(b) * n - sin(b) * t, sin(b) * n + cos(b) * t

    def roll_speed(self):
        """|U| of each roll on its side, times (1 + e_tt) on a flattening roll's rim."""
        speed = by_side(self.U_side[1], self.U_side[-1])
        return speed if self.roll_hoop is None else speed * (1.0 + self.roll_hoop)

    def friction_arguments(self, w, k=None, lam=None) -> dict:
        law = self.friction
        if law.uses_k and k is None:
            k = self.shear_flow_stress(w)
        return dict(a_f=None, m=self.m,
                    pressure=self.pressure(w, lam) if law.uses_pressure else None,
                    k=k if law.uses_k else None)

    def layer_depth(self):
        """(c_e's depth, its gradient) on both arcs (``RollingForm.constraint``): c_e =
        compliance min(|y|, strip_depth of that roll): |y| the surface's distance from the exit
        mid-plane, the half thickness where the strip is centred between the rolls (the pass
        line puts it there; unequal radii shift the bite's middle by dh (R2 - R1) / (2 (R1 +
        R2)), 1 % of the half thickness at 360/400 mm and 25 -> 20 mm)."""
        from ngsolve import CF, IfPos, y

        half, slope = IfPos(y, y, -y), CF((0.0, 1.0)) * IfPos(y, 1.0, -1.0)
        if self.strip_depth is None:
            return half, slope
        cap = by_side(self.strip_depth[1], self.strip_depth[-1])
        return IfPos(half - cap, cap, half), IfPos(half - cap, 0.0, 1.0) * slope

    def centre_distance(self):
        """The distance from each roll's centre (``RollingForm.centre_distance``; the lower
        roll's centre below)."""
        from ngsolve import sqrt, x, y

        r = []
        for side in (1, -1):
            rp = self.rolls[side]
            cx, cy = rp.centre
            if rp.shape is not None:
                cx = self.roll_cx_side[side]
            r.append(sqrt((x - cx) ** 2 + (y - side * cy) ** 2))
        return by_side(*r)

    def boundary(self, u, w, v, friction: bool = True, lam=None):
        """Friction on both arcs, the bounds (3.2a,b) on the free surfaces and the cut faces,
        the tensions; no T* on the outlet."""
        from ngsolve import IfPos, ds, specialcf, x

        chi = self.chi
        n, t = self.roll_frame()
        friction_term = (chi * self.friction_coefficient(w, lam=lam) * self.slip(u) * (v * t)
                         if friction else None)
        inlet = self.inlet_penalty(u, w) * v[0]
        outlet = self.outlet_penalty(u, w) * v[0]
        free = IfPos(x - self.x_split, outlet, inlet)
        nh = specialcf.normal(2)
        rest = ((1.0 - chi) * free * ds(SURFACES)
                + (inlet - self.tension_back * (v * nh)) * ds("in")
                + (outlet - self.tension_front * (v * nh)) * ds("out"))
        return friction_term * self.friction_measure() + rest if friction else rest
