"""The strip's elastic moduli at the rolling temperature: the default of ``[contact]
strip_youngs_modulus = "auto"`` (its elastic thickness strain in the contact, docs/theory.md 1e).

The strip unloads at the exit in milliseconds: the modulus that governs it is the lattice's
(dynamic or fast static), not the fire-design "effective" moduli of EN 1993-1-2 Table 3.1 or
EN 1999-1-2, which are slopes of slow creep-inclusive tests (9.5 GPa for steel at 1000 degC,
zero at 1200 degC, 7-10 times below every lattice value). Sources (read in public code; the
papers themselves were not read: docs/notes/strip-modulus.md):

- **steels** (S355J2, C45, C20): Ghosh and Olson, Acta Mater. 50 (2002) 2655, the isotropic
  shear modulus of Fe solid solutions, T in K, mu in Pa:
  austenite mu = 9.2648e10 (1 - 7.9921e-7 T^2 + 3.317e-10 T^3) from 800 degC up;
  ferrite mu = 8.407e10 (1 - 0.48797 t^2 + 0.12651 t^3), t = T / 1043 K, up to 700 degC;
  linear between (the two-phase range); E = 2 mu (1 + nu), nu = 0.3. Read in
  mfrichtl/librecalphad, libreCalphad/models/steels.py (commit 0f6c791), lines 47-51. Checked:
  ferrite at 600 degC mu = 61.6 GPa against 61 GPa of a Steel 25 handbook table; austenite at
  1000 degC E = 97 GPa, at the low edge of the 95-125 GPa the readable data allow.
- **aluminium** (Al99.5): Frost and Ashby (1982), mu = mu_300 (1 - k (T - 300 K) / T_m),
  mu_300 = 25.4 GPa, k = 0.46, T_m = 933 K; E = 2 mu (1 + nu), nu = 0.35. Parameters read in
  PhilipSargent/defm-maps, MATLPARS.DAT (commit 2c28fad); 68.6 GPa at 20 degC against 70.1 GPa
  from Gerlich and Fisher's single-crystal constants.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

#: degC -> K
_K = 273.15


def _steel_shear(T: float) -> float:
    """Ghosh and Olson's shear modulus (Pa) of ferrite (<= 700 degC) and austenite (>= 800
    degC), linear between."""
    lo, hi = 700.0 + _K, 800.0 + _K

    def ferrite(t):
        tau = t / 1043.0
        return 8.407e10 * (1.0 - 0.48797 * tau**2 + 0.12651 * tau**3)

    def austenite(t):
        return 9.2648e10 * (1.0 - 7.9921e-7 * t**2 + 3.317e-10 * t**3)

    if T <= lo:
        return ferrite(T)
    if T >= hi:
        return austenite(T)
    s = (T - lo) / (hi - lo)
    return (1.0 - s) * ferrite(lo) + s * austenite(hi)


def _aluminium_shear(T: float) -> float:
    """Frost and Ashby's linear shear modulus (Pa) of aluminium."""
    return 25.4e9 * (1.0 - 0.46 * (T - 300.0) / 933.0)


@dataclass(frozen=True)
class StripModulus:
    """A family's Young's modulus E(T) and Poisson's ratio; T in K within ``valid`` (K)."""

    family: str
    shear: Callable[[float], float]
    nu: float
    valid: tuple[float, float]
    source: str

    def youngs_modulus(self, T: float) -> float:
        """E(T) = 2 mu(T) (1 + nu), Pa; T in K within ``valid``."""
        lo, hi = self.valid
        if not lo <= T <= hi:
            raise ValueError(f"the {self.family} modulus law holds from {lo - _K:.0f} to "
                             f"{hi - _K:.0f} degC, not at {T - _K:.0f} degC")
        return 2.0 * self.shear(T) * (1.0 + self.nu)


#: the families; the steel law's austenite cubic has its minimum at 1606 K: valid to 1330 degC
FAMILIES = {
    "steel": StripModulus("steel", _steel_shear, 0.3, (20.0 + _K, 1330.0 + _K),
                          "Ghosh and Olson, Acta Mater. 50 (2002) 2655"),
    "aluminium": StripModulus("aluminium", _aluminium_shear, 0.35, (20.0 + _K, 600.0 + _K),
                              "Frost and Ashby, Deformation-Mechanism Maps (1982)"),
}


def family_modulus(family: str) -> StripModulus:
    """The ``StripModulus`` of a grade's family (``GradeData.family``)."""
    return FAMILIES[family]
