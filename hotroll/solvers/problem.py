"""The typed stages of a solve: the ``Problem`` (what is solved), the ``Solver`` interface that
the direct steady solver (``steady.py``) and the report's scheme (``transient.py``) both
implement, and the ``Solution`` their ``run`` returns (``model/solution.py``, re-exported here;
``solution_record`` fills in its fields for the results: docs/architecture.md)."""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Callable, Protocol

from hotroll.fem.mesh import MeshSpec
from hotroll.fem.strain import StrainField
from hotroll.model.friction import FrictionLaw
from hotroll.model.geometry import RollPass
from hotroll.model.material import NortonHoff
from hotroll.model.solution import Solution  # noqa: F401 (re-exported: the solvers' callers)
from hotroll.solvers.thermal_coupling import ThermalCoupling
from hotroll.solvers.thermal_lagrangian import LagrangianThermal


@dataclass(frozen=True)
class GapRolls:
    """The two rolls of an asymmetric pass, what the full-thickness strip takes
    (``solvers/full_steady.FullSteadyRun``), keyed by side (+1 upper, -1 lower): ``rolls`` each
    roll's ``RollPass`` in its own frame (``RollGap.arc``: y mirrored for the lower), the same
    axis_x and half_exit; ``frictions`` each roll's law in reduced units (stresses over K, v_reg
    from that roll's surface speed); ``a_f`` each roll's a_f (m^-m; None for a law without
    it); ``speed_ratio`` the upper over the lower surface speed (-); ``roll_models`` each
    flattening roll's (kind, ``RollElasticity``, relaxation, tie in m), none for a rigid one
    (the full strip builds its ``FlatteningRoll`` on the roll as it places it)."""

    rolls: dict
    frictions: dict
    a_f: dict
    speed_ratio: float
    roll_models: dict = field(default_factory=dict)

    def at_axis(self, axis_x: float) -> GapRolls:
        """The same rolls with their axes at x = ``axis_x`` (m)."""
        return replace(self, rolls={s: replace(rp, axis_x=axis_x) for s, rp in self.rolls.items()})


@dataclass
class Problem:
    """What is solved: the pass, the material, friction, mesh, tensions and the fields a
    strain- or temperature-dependent flow stress needs, in SI units; both solvers take it."""

    rp: RollPass
    length: float
    material: NortonHoff
    friction: FrictionLaw     # in reduced units (stresses over K): viscoplastic with K = 1
    mesh: MeshSpec
    back_tension: float = 0.0   # Pa, mean tensile stress on the entry face
    front_tension: float = 0.0  # Pa, mean tensile stress on the exit face
    flow_stress: object = None  # flow-stress law of a strain or temperature field (None: the
                                # material is the law)
    temperature: float = 1373.15  # K: uniform, or the entry temperature with ``thermal``
    entry_strain: float = 0.0
    carries_strain: bool = True   # the law depends on the strain: a strain field is carried
    thermal: tuple | None = None  # (ThermalProperties, ThermalBoundary, strip mesh refinement)
    strain_profile: object = None  # the inlet's strain over the half thickness (a
                                   # process.profile.ThicknessProfile; steady solver), or None
    roll: object = None            # a flattening roll (model/roll_elastic.FlatteningRoll) whose
                                   # shape rp holds, or None: the rigid roll
    v_reg_per_speed: float | None = None   # v_reg / U where the regularisation follows the
                                           # roll speed (the laws' default), None: v_reg given
    strip_elasticity: tuple | None = None  # (E_s Pa, nu_s) of the strip: its elastic thickness
                                           # strain in the contact (docs/theory.md 1e), or None
    gap: GapRolls | None = None    # an asymmetric pass's two rolls (the full-thickness strip),
                                   # or None: the half model with its symmetry plane

    @property
    def strip_compliance(self) -> float | None:
        """(1 - nu_s^2) / E_s times K: the strip's plane-strain elastic compliance per unit of
        reduced pressure, or None (rigid-plastic)."""
        if self.strip_elasticity is None:
            return None
        E, nu = self.strip_elasticity
        return (1.0 - nu * nu) / E * self.material.K

    @property
    def strip_layer_depth(self) -> float | None:
        """The strip's elastic layer's largest depth (m), with its elasticity: a thin strip's
        elastic thickness strain is its whole half thickness's (a Winkler layer, c_e = (h/2)
        (1 - nu^2)/E), a thick one's reaches as deep as its elastic exit zone is long, which
        for a thick strip recovering over about its thickness is 2 R (1 - nu^2) 2k / E (the
        strip's recovery slope delta/h against the roll's rise x^2/2R, delta = h (1 - nu^2)
        2k / E). The layer is min(h/2, this): its Winkler zone sqrt(2 R c_e 2k) then equals it
        (docs/theory.md 1e). 2k = 2/sqrt3 sigma_ef at the pass's mean strain rate; R the
        surface's radius of curvature at the gap when the solve starts (a flattened roll's
        start: the rigid circle, or Hitchcock's)."""
        if self.strip_elasticity is None:
            return None
        E, nu = self.strip_elasticity
        rp, two_k = self.rp, self.mean_two_k
        return 2.0 * min(rp.gap_radius, 1e3 * rp.radius) * (1.0 - nu * nu) * two_k / E

    @property
    def mean_two_k(self) -> float:
        """2k = (2/sqrt3) sigma_ef (Pa) at the pass's mean strain rate U/l 2/sqrt3 ln(h0/h1)
        (the reference law's, at the entry strain): the plane-strain flow stress of estimates."""
        import math

        rp = self.rp
        rate = rp.u_roll / rp.contact_length * 2.0 / math.sqrt(3.0) * math.log(
            rp.half_entry / rp.half_exit)
        return 2.0 / math.sqrt(3.0) * self.material.sigma_ef(rate)

    @property
    def v_reg(self) -> float:
        return self.friction.v_reg

    def field_setup(self, mesh, lagrangian: bool = False):
        """(StrainField or None, ThermalCoupling or None, the form's consistency K(eps, T)/K_ref
        as a CF, or 1.0): the fields a strain- or temperature-dependent flow stress needs
        (``fem/strain.py``, ``solvers/thermal_coupling.py``)."""
        strain = None
        if self.flow_stress is not None and self.carries_strain:
            strain = StrainField(mesh, self.entry_strain, profile=self.strain_profile)
        if self.thermal is not None and lagrangian:     # carried with the moving mesh

            props, bc, _ = self.thermal
            coupling = LagrangianThermal(mesh, props, bc, K_ref=self.material.K,
                                         m_ref=self.material.m, eps0=self.material.eps0,
                                         flow=self.flow_stress, strain=strain,
                                         entry_strain=self.entry_strain)
            return strain, coupling, coupling.consistency()
        if self.thermal is not None:
            props, bc, refine = self.thermal
            coupling = ThermalCoupling(mesh, props, bc, refine=refine, K_ref=self.material.K,
                                       m_ref=self.material.m, eps0=self.material.eps0,
                                       flow=self.flow_stress, strain=strain,
                                       entry_strain=self.entry_strain)
            return strain, coupling, coupling.consistency()
        if strain is None:
            return None, None, 1.0
        ratio = self.flow_stress.consistency(strain.gf, self.temperature) / self.material.K
        return strain, None, ratio

    @property
    def reduced_tensions(self) -> tuple[float, float]:
        """(back, front) tension over K, as the form takes every stress."""
        return (self.back_tension / self.material.K, self.front_tension / self.material.K)

    @property
    def h(self) -> float:
        return self.mesh.h


class Solver(Protocol):
    """What the two solvers share: the problem, the FE objects the record reads
    (``solvers/record.py``), ``run`` and its ``Solution``. The results layer reads only the
    ``Solution`` that ``solution_record`` returns (``results/run_summary.py``)."""

    problem: Problem
    time_stepping: bool     # the report's scheme (True) or the direct steady solver (False)
    window: int             # the summary's means: the last ``window`` history rows
    state: Solution
    form: object            # fem.rolling_form.RollingForm (velocity, pressure, contact)
    top: object             # fem.top_boundary.TopBoundary
    strain: object          # fem.strain.StrainField or None
    thermal: object         # a temperature coupling (solvers/thermal_*.py) or None

    def run(self, progress: Callable[[dict], None] | None = None) -> Solution: ...

    def head_x(self) -> float: ...

    def solution_record(self, frame_shift: float = 0.0) -> Solution: ...
