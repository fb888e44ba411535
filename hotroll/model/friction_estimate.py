"""Estimate of the friction parameter a_f from the stability bound (3.15), Remark 3.3.

a_f = (C5 / h) * sum_K int_K |v_h|^p dx / ( (|lam|^(p-1) - |lam|^p) * int_{Gamma_C^-} |U_roll|^p ds )

with p = m + 1, C5 = 2^p, h the contact mesh size, lam = |v_s| / |U_roll| on the first touching
element, Gamma_C^- the part of the contact where the plate slips backwards (before the neutral
point).
"""
from __future__ import annotations

import math


def lambda_factor(lam: float, p: float) -> float:
    """|lam|^(p-1) - |lam|^p, the factor of (3.14)/(3.15)."""
    lam = abs(lam)
    return lam ** (p - 1.0) - lam**p


def estimate_a_f(
    volume_v_p: float,
    h: float,
    lam: float,
    backward_length: float,
    u_roll: float,
    m: float,
    *,
    lam_min: float = 1e-3,
    a_f_max: float = 1e6,
) -> float:
    """Right-hand side of (3.15) solved for a_f.

    ``volume_v_p`` is int_Omega |v_h|^p dx, ``backward_length`` the length of Gamma_C^-.
    ``lam`` is clipped to [lam_min, 1 - lam_min] and the result to a_f_max, so that a sticking
    first element (lam -> 0) or an empty backward-slip zone give a large but finite a_f.
    """
    if volume_v_p <= 0 or h <= 0 or u_roll <= 0:
        raise ValueError("estimate_a_f needs positive volume integral, h and roll speed")
    p = m + 1.0
    c5 = 2.0**p
    lam = min(max(abs(lam), lam_min), 1.0 - lam_min)
    length = max(backward_length, h)  # at least one element of backward slip
    denom = lambda_factor(lam, p) * length * u_roll**p
    a_f = c5 / h * volume_v_p / denom
    return float(min(a_f, a_f_max)) if math.isfinite(a_f) else float(a_f_max)
