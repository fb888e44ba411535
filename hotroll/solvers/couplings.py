"""The couplings of a rolling solve: what the flow depends on besides the velocity and the
pressure, behind one interface that both solvers call (docs/theory.md 4b).

- the steady solver's fixed point (``SteadyRun``): ``update(result)`` once the Newton update is
  small, returning the change in units of the coupling's tolerance; the solve has settled when
  every change is at most 1;
- the report's scheme (``TransientRun``): ``advance(dt)`` carries the field with the material
  through one step.

A new coupling (the elastic roll, microstructure) is one class here and one line where the
solver builds its list (``SteadyRun.couplings``, ``TransientRun.couplings``).
"""
from __future__ import annotations

from dataclasses import replace
from typing import Callable

import numpy as np


class Coupling:
    """A field or parameter coupled to the flow; the default does nothing."""

    name = ""
    #: its change decides whether the steady fixed point has settled (the active set's does
    #: not: it is updated with the others but never keeps the iteration going on its own)
    in_fixed_point = True
    #: the couplings whose change it does not wait for (``after_others``)
    waits_not_on: tuple[str, ...] = ()
    #: it reads the contact pressure (with the strip's compliance it waits for a tight flow:
    #: ``steady.COUPLE_BELOW_ELASTIC``)
    reads_pressure = False

    def update(self, result) -> float:
        """Steady fixed point: one update; its change over its tolerance."""
        return 0.0

    def advance(self, dt: float) -> None:
        """The report's scheme: carry the field through one step of ``dt`` seconds."""


class StrainTransport(Coupling):
    """The strain carried with the material (``fem/strain.py``): steady, transported along the
    current flow; the report's scheme, eps += dt edot at the material nodes."""

    name = "strain"

    def __init__(self, field, velocity, rtol: float = 1.0):
        self.field, self.velocity, self.rtol = field, velocity, rtol

    def update(self, result) -> float:
        return self.field.transport(self.velocity) / self.rtol

    def advance(self, dt: float) -> None:
        self.field.integrate(self.velocity, dt)


class Temperature(Coupling):
    """The strip's temperature (``solvers/thermal_coupling.py``): steady, one Newton step of
    the heat equation on the current flow per update; the report's scheme, one implicit step."""

    name = "temperature"

    def __init__(self, thermal, rtol: float = 1.0):
        self.thermal, self.rtol = thermal, rtol

    def update(self, result) -> float:
        return self.thermal.update_steady(max_iter=1) / self.rtol

    def advance(self, dt: float) -> None:
        self.thermal.step(dt)


class AfEstimate(Coupling):
    """The friction coefficient a_f from (3.15) on the current flow (``form.a_f``)."""

    name = "a_f"

    def __init__(self, a_f, estimate: Callable[[], float], rtol: float):
        self.a_f, self.estimate, self.rtol = a_f, estimate, rtol

    def update(self, result) -> float:
        a_old, a_new = self.a_f.Get(), self.estimate()
        result.a_f_history.append(a_new)
        self.a_f.Set(a_new)
        return abs(a_new - a_old) / (self.rtol * a_new)


class FreeSurface(Coupling):
    """The traced free tops (``fem/free_surface.py``): moved onto the streamlines of the
    current flow; the change is the largest move in units of ``tol`` (m)."""

    name = "free_surface"

    def __init__(self, trace: Callable[[], float], tol: float):
        self.trace, self.tol = trace, tol

    def update(self, result) -> float:
        moved = self.trace()
        result.surface_moves.append(moved)
        return moved / self.tol


class ContactEnd(Coupling):
    """Unilateral contact's end x_e (``fem/free_surface.py: ContactEndSearch``): moved to
    where the contact pressure falls to zero (or to the gap), then the mesh follows; the change
    is the move in units of ``tol`` (m)."""

    name = "contact_end"
    reads_pressure = True
    #: its tolerance in units of the traced tops' (1e-2 h by default): the end's pressure
    #: p_end(x_e) carries the flow's coupling noise, about 1e-3 of the peak pressure, which
    #: moves its root by several of the tops' 1e-3 h
    TOLERANCE = 1.0
    #: ... an elastic strip's (1e-2 h): its end lies where the pressure has fallen smoothly to
    #: zero, so the end's error moves the force by its square (thin_strip's force 6e-5 apart
    #: between roll relaxations 1 and 0.5, against 2e-5 at 1e-3 h), and p_end carries the
    #: elastic zone's magnified flow noise: at 1e-3 h the end dithered for 4-6 rounds
    TOLERANCE_ELASTIC = 10.0
    #: (and a strip that curls onto a roll past its gap: its pressure falls smoothly to zero
    #: there too; asymmetric_plate with elastic-disc rolls dithered by 1-5 um (1e-3 h) for 20
    #: rounds and ended unsettled; solvers/full_contact_end.py: end_tolerance)
    #: moved once the other couplings are within 10 tolerances: a_f (3.15) of a warm start from
    #: another pass swings by 10x from update to update, and the end followed each swing
    #: (a study's warm-started Example 1 pass did not settle in 30 updates)
    after_others = 10.0

    def __init__(self, move: Callable[[], float], tol: float):
        self.move, self.tol = move, tol

    def update(self, result) -> float:
        return self.move() / self.tol


class TandemSpeed(Coupling):
    """A tandem stand's roll speed found inside the solve: the speed at which the strip's
    inlet passes the mill's mass flux (``target``, m^2/s, half model). Each update measures
    the inlet flux (``flux``) and moves the speed by the miss, omega / (1 + miss)
    (``set_speed``); the change is |miss| in units of ``tol``. The forward slip hardly
    depends on the speed, so this settles in 1-3 updates."""

    name = "speed"
    #: moved with the others from the first update (the flux of a flow converged to
    #: ``couple_below`` is already that close): waiting for the others to come within 10
    #: tolerances cost a round whose temperature change the speed then undid (finishing_mill
    #: 57 -> 53 Newton iterations, F5 and F6 from 6 to 5; figures 5e-6 apart; session 5)
    after_others = None

    def __init__(self, flux: Callable[[], float], target: float, omega: Callable[[], float],
                 set_speed: Callable[[float], None], tol: float):
        self.flux, self.target, self.omega, self.set_speed, self.tol = (flux, target, omega,
                                                                        set_speed, tol)

    def update(self, result) -> float:
        miss = self.flux() / self.target - 1.0
        self.set_speed(self.omega() / (1.0 + miss))
        return abs(miss) / self.tol


class RollFlattening(Coupling):
    """The flattening work roll (``model/roll_elastic.py``): its surface moved by the contact
    tractions of the current flow (``loads``: angles, pressure, shear in Pa), then the strip's
    roll frame and mesh follow (``apply``); the change is the surface's largest move in units
    of ``tol`` (m)."""

    name = "roll"
    reads_pressure = True
    #: moved only once the flow's other couplings are within 10 tolerances of their fixed
    #: point: the tractions of an unsettled flow (a_f far off) would throw the roll far off
    #: (the thin strip from the slab guess: unsettled after 30 roll updates when the roll
    #: moved from the first round, settled after 13 with the wait). A solve started from a
    #: solved similar pass, whose roll it carries (``SteadyRun``: ``wait=False``), moves it
    #: from the first round (ten stands 131 -> 110-111 Newton iterations, the figures as close
    #: to a solve with every tolerance / 10 as before; session 6)
    after_others = 10.0
    #: points along the arc where the surface's move is measured
    PROBES = 200
    #: the contact's end follows the roll's surface: the roll does not wait for it (an end
    #: re-found after every roll move, and the roll waiting for it, took 3-4 rounds a roll
    #: update on thin_strip)
    waits_not_on = ("contact_end",)

    def __init__(self, roll, loads: Callable[[], tuple], apply: Callable[[], None], tol: float,
                 wait: bool = True):
        self.roll, self.loads, self.apply, self.tol = roll, loads, apply, tol
        self.after_others = type(self).after_others if wait else None
        self.moves: list[float] = []

    def update(self, result) -> float:
        # the change where the strip sees it: the surface's height over the arc at fixed x
        # (from the earlier of the old and the new touching point to the gap). The roll's axis
        # follows the surface's lowest point (the gap), which on a thin strip's flat-bottomed
        # roll wanders with the contact pressure near the exit: on the ten stands' F10 a
        # surface move of 0.3-1 tolerance in w(theta) shifted the axis by 0.01-0.03 mm and the
        # arc at the bite by 2-8 tolerances, round after round in the same direction, while
        # w's own change called the roll settled (issue 34 session 6). The roll's last_move
        # (the summary's roll_last_move) is this change.
        x_before = self.roll.rp.x_touch        # cached with the shape (the copy's would not be)
        before = replace(self.roll.rp, shape=self.roll.rp.shape.copy())
        moved = self.roll.update(*self.loads())
        self.moves.append(moved)
        self.apply()
        rp = self.roll.rp
        x = np.linspace(min(x_before, rp.x_touch), rp.axis_x, self.PROBES)
        change = max(moved, float(np.max(np.abs(rp.height(x) - before.height(x)))))
        self.roll.last_move = change
        return change / self.tol
