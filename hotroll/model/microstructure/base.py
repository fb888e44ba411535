"""The interface of a recrystallisation parameter set (issue 33; docs/theory.md 1g).

A set is the Sellars-type family of C-Mn austenite kinetics (Sellars 1990; Hodgson and Gibbs
1992; Beynon and Sellars 1992), each law a power term with an Arrhenius factor:

    Z       = edot exp(Q_def / (R T))                                  Zener-Hollomon (1/s)
    eps_c   = critical(d0, Z)              onset of dynamic recrystallisation in the pass
    t_0.5   = srx(eps, d0, edot, T)        static recrystallisation, eps < eps_c
    t_0.5   = mdrx(Z, T)                   metadynamic, eps >= eps_c (DRX started in the pass)
    X(t)    = 1 - exp(ln 0.5 (t / t_0.5)^n)                            JMAK
    d_rex   = srx_grain(eps, d0, T)  or  mdrx_grain(Z)
    d^k     = d_rex^k + K t exp(-Q_gg / (R T))                         grain growth

The terms take the units their sources use: grain sizes in micrometres, rates in 1/s, T in K,
energies in J/mol; the interface (``RecrystallisationSet``'s methods) takes grain sizes in m.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: The gas constant, J/(mol K).
R = 8.314462618
#: Micrometres per metre: the sets' grain sizes are in um.
UM = 1e6


@dataclass(frozen=True)
class PowerTerm:
    """a strain^strain d0^grain edot^rate Z^zener exp(q / (R T)) (d0 in um; a positive q
    slows, a negative q of a grain size makes it smaller when colder)."""

    a: float
    strain: float = 0.0
    grain: float = 0.0
    rate: float = 0.0
    zener: float = 0.0
    q: float = 0.0

    def __call__(self, *, strain=1.0, grain_um=1.0, rate=1.0, Z=1.0, T=None):
        value = self.a * np.ones_like(np.asarray(strain * grain_um * rate * Z, dtype=float))
        for base, p in ((strain, self.strain), (grain_um, self.grain), (rate, self.rate),
                        (Z, self.zener)):
            if p != 0.0:
                value = value * np.asarray(base, dtype=float) ** p
        if self.q != 0.0:
            value = value * np.exp(self.q / (R * np.asarray(T, dtype=float)))
        return value


@dataclass(frozen=True)
class GrowthLaw:
    """d^k = d_0^k + K W, W = int exp(-q / (R T)) dt (temperature-compensated time, s); d in um."""

    exponent: float
    K: float
    q: float

    def rate(self, T):
        """dW/dt at T (K): exp(-q / (R T))."""
        return np.exp(-self.q / (R * np.asarray(T, dtype=float)))

    def grown(self, d_um, W):
        """The grain size (um) grown from ``d_um`` over temperature-compensated time W (s)."""
        d = np.asarray(d_um, dtype=float)
        return (d**self.exponent + self.K * np.asarray(W, dtype=float)) ** (1.0 / self.exponent)


@dataclass(frozen=True)
class RecrystallisationSet:
    """One published parameter set; grain sizes at the interface in m (module docstring)."""

    name: str
    description: str
    source: str
    q_def: float                    # J/mol, the Zener-Hollomon parameter's energy
    critical: PowerTerm             # eps_c(d0 um, Z)
    srx_time: PowerTerm             # t_0.5 (s) of static recrystallisation
    srx_exponent: float             # JMAK n
    srx_grain: PowerTerm            # d_srx (um)
    mdrx_time: PowerTerm            # t_0.5 (s) of metadynamic recrystallisation
    mdrx_exponent: float
    mdrx_grain: PowerTerm           # d_mdrx (um)
    growth: GrowthLaw
    steels: tuple[str, ...]         # grades of model/grades.py the set is for
    temperature_range: tuple[float, float]    # K, where the kinetics may be applied
    validity: str = ""              # the source's own tested ranges, as stated

    def zener(self, rate, T):
        """Z = edot exp(Q_def / (R T)) (1/s)."""
        return np.asarray(rate, dtype=float) * np.exp(self.q_def / (R * np.asarray(T, float)))

    def critical_strain(self, d0, Z):
        """The strain at which dynamic recrystallisation starts in the pass (d0 in m)."""
        return self.critical(grain_um=np.asarray(d0) * UM, Z=Z)

    def srx_half_time(self, strain, d0, rate, T):
        """t_0.5 (s) of static recrystallisation after ``strain`` (d0 in m, rate 1/s, T K)."""
        return self.srx_time(strain=strain, grain_um=np.asarray(d0) * UM, rate=rate, T=T)

    def mdrx_half_time(self, Z, T):
        """t_0.5 (s) of metadynamic recrystallisation (Z of the pass, T of the hold)."""
        return self.mdrx_time(Z=Z, T=T)

    def srx_grain_size(self, strain, d0, T):
        """The statically recrystallised grain size (m)."""
        return self.srx_grain(strain=strain, grain_um=np.asarray(d0) * UM, T=T) / UM

    def mdrx_grain_size(self, Z):
        """The metadynamically recrystallised grain size (m)."""
        return self.mdrx_grain(Z=Z) / UM

    def grown(self, d, W):
        """Grain growth from d (m) over temperature-compensated time W (s): m."""
        return self.growth.grown(np.asarray(d) * UM, W) / UM
