"""The roll's elasticity (hotroll/model/roll_elastic.py) against independent answers: the disc
in diametral compression (Timoshenko & Goodier), Hertz's line contact (Johnson 4.2), Hitchcock's
flattened radius as the short-arc limit, and the exact scaling of linear elasticity."""
from __future__ import annotations

import math

import numpy as np
import pytest

from hotroll.model.roll_elastic import ElasticDisc, RollElasticity

STEEL = RollElasticity(210e9, 0.3)


def ellipse(theta, radius, half_width, force):
    """Hertz's (elliptical) pressure of total ``force`` per unit width over the arc length
    |R theta| < half_width (zero at the ends: the disc takes the load as piecewise linear
    between all its nodes)."""
    x = radius * theta
    return 2.0 * force / (math.pi * half_width) * np.sqrt(np.maximum(1.0 - (x / half_width) ** 2, 0.0))


def load_integral(theta, p, radius):
    """The force per unit width of the piecewise linear load the disc is given."""
    return float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(theta))) * radius


def test_two_opposite_loads_widen_the_disc_as_the_closed_form_says():
    """Two opposite narrow loads P: the diameter across them grows by (P/E)((1 - nu^2)(4/pi - 1)
    + nu (1 + nu)) (plane strain; the disc of Timoshenko & Goodier, integrated)."""
    E, nu, R, a = 1.0, 0.3, 1.0, 1e-3
    disc = ElasticDisc(R, RollElasticity(E, nu))
    th = np.linspace(-a, a, 41)
    p = ellipse(th, R, a * R, 1.0)
    out = disc.rim(np.concatenate([th - math.pi / 2, th + math.pi / 2]), np.concatenate([p, p]),
                   at=np.array([0.0, math.pi - 1e-12]))
    P = load_integral(th, p, R)
    expected = (P / E) * ((1 - nu**2) * (4 / math.pi - 1) + nu * (1 + nu))
    assert out["u_r"][0] + out["u_r"][1] == pytest.approx(expected, rel=1e-4)


def hertz_contact(disc: ElasticDisc, force: float, nodes: int = 61, span: float = 2.0):
    """The disc pressed on a rigid flat by ``force`` per unit width, solved with the disc's
    influence matrix by an active set: (peak pressure, half-width) from the fit p^2 = p0^2 (1 -
    x^2/b^2) of the contact nodes."""
    R = disc.radius
    b_guess = disc.elasticity.hertz_half_width(force, R)
    th = np.linspace(-span * b_guess / R, span * b_guess / R, nodes)
    # the rim's height change per unit nodal pressure (hat functions), column by column
    lift = np.empty((nodes, nodes))
    for j in range(nodes):
        unit = np.zeros(nodes)
        unit[j] = 1.0
        o = disc.rim(th, unit)
        lift[:, j] = -o["u_r"] * np.cos(th) + o["u_t"] * np.sin(th)
    height = -R * np.cos(th)                        # undeformed rim, centre at 0
    w = np.full(nodes, th[1] - th[0]) * R           # the hat functions' integrals
    w[[0, -1]] *= 0.5
    active = np.abs(th) < 0.5 * span * b_guess / R
    for _ in range(50):
        idx = np.nonzero(active)[0]
        # rows: y_i + lift_i p = c (flat) on the active nodes; sum w p = force
        A = np.zeros((len(idx) + 1, len(idx) + 1))
        A[:-1, :-1] = lift[np.ix_(idx, idx)]
        A[:-1, -1] = -1.0
        A[-1, :-1] = w[idx]
        rhs = np.concatenate([-height[idx], [force]])
        sol = np.linalg.solve(A, rhs)
        p = np.zeros(nodes)
        p[idx], c = sol[:-1], sol[-1]
        y = height + lift @ p
        new = (p > 0.0) | (~active & (y < c))
        new &= ~(active & (p < 0.0))
        if np.array_equal(new, active):
            break
        active = new
    x = R * np.sin(th)
    inner = active & (np.abs(x) < 0.8 * np.abs(x[active]).max())
    slope, p0sq = np.polyfit(x[inner] ** 2, p[inner] ** 2, 1)
    return math.sqrt(p0sq), math.sqrt(-p0sq / slope)


@pytest.mark.parametrize("force", [2e6, 1e7])
def test_hertz_line_contact_half_width_and_peak_pressure(force):
    """A steel roll (R = 0.35 m) on a rigid flat: b = sqrt(4 F' R / (pi E*)) and
    p0 = 2 F' / (pi b) (Johnson, Contact Mechanics, 4.2: a half-space; the disc's finite radius
    changes them by O(b/R)^2, below 1e-3 here)."""
    R = 0.35
    disc = ElasticDisc(R, STEEL)
    p0, b = hertz_contact(disc, force)
    b_hertz = STEEL.hertz_half_width(force, R)
    assert b == pytest.approx(b_hertz, rel=0.01)
    assert p0 == pytest.approx(2 * force / (math.pi * b_hertz), rel=0.01)


def best_circle(theta, r):
    """Least-squares circle through the rim points (radius)."""
    X, Y = -r * np.sin(theta), -r * np.cos(theta)
    A = np.c_[X, Y, np.ones_like(X)]
    c = np.linalg.lstsq(A, X**2 + Y**2, rcond=None)[0]
    return math.sqrt(c[2] + (c[0] / 2) ** 2 + (c[1] / 2) ** 2)


@pytest.mark.parametrize("force, draught", [(1e7, 1e-3), (2e6, 3e-3), (1e6, 1e-3), (1e5, 0.3e-3)])
def test_hitchcock_radius_is_the_short_arc_limit(force, draught):
    """Hitchcock's elliptical pressure over l' = 2a = sqrt(R' dh) on the disc: the loaded arc is
    a circle whose R' - R is Hitchcock's (the half-space's curvature change 2 p0 / (a E*)) less
    the disc's finite-radius part. That part, from the 1/n^2 term of a_n - (1 - nu)/n, is
    d^2 u_r / d theta^2 = -(R / mu) (1 - 2 nu) / 2 p: a relative deficit of
    (1 - 2 nu) / (2 (1 - nu)) a / R (derived by hand; 0.3-1.4 % here), to first order in a/R."""
    R = 0.35
    disc = ElasticDisc(R, STEEL)
    ratio = STEEL.hitchcock_ratio(force, draught)
    a = 0.5 * math.sqrt(R * ratio * draught)
    th = np.linspace(-a / R, a / R, 401)
    o = disc.rim(th, ellipse(th, R, a, force))
    inner = np.abs(th) < 0.8 * a / R
    fitted = best_circle(th[inner], R + o["u_r"][inner])
    deficit = 1.0 - (fitted - R) / (R * (ratio - 1.0))
    first_order = (1 - 2 * STEEL.nu) / (2 * (1 - STEEL.nu)) * a / R
    assert deficit == pytest.approx(first_order, rel=0.15)


def test_the_displacement_scales_with_the_load_over_the_modulus():
    """Linear elasticity: u(E, p, R) = R (p / E) U(theta); doubling the load and the modulus
    changes nothing, a roll twice the size under the same pressure over the same angles
    moves twice as far."""
    th = np.linspace(-0.05, 0.05, 81)
    p = 1e8 * (1.0 - (th / 0.05) ** 2)
    q = 2e7 * th / 0.05
    base = ElasticDisc(0.3, STEEL).rim(th, p, q)
    stiff = ElasticDisc(0.3, RollElasticity(2 * STEEL.E, STEEL.nu)).rim(th, 2 * p, 2 * q)
    big = ElasticDisc(0.6, STEEL).rim(th, p, q)
    for key in ("u_r", "u_t"):
        assert np.allclose(stiff[key], base[key], rtol=1e-12, atol=0)
        assert np.allclose(big[key], 2 * base[key], rtol=1e-12, atol=0)
    assert np.allclose(big["hoop"], base["hoop"], rtol=1e-12, atol=0)


def test_betti_reciprocity_of_the_rim():
    """Identity (Betti): the radial displacement at A from a unit pressure at B equals the one
    at B from a unit pressure at A; the shear's tangential one likewise."""
    disc = ElasticDisc(0.3, STEEL)
    th = np.linspace(-0.1, 0.1, 41)
    i, j = 7, 29
    ei, ej = np.eye(41)[i], np.eye(41)[j]
    assert disc.rim(th, ej)["u_r"][i] == pytest.approx(disc.rim(th, ei)["u_r"][j], rel=1e-9)
    zero = np.zeros(41)
    assert disc.rim(th, zero, ej)["u_t"][i] == pytest.approx(disc.rim(th, zero, ei)["u_t"][j], rel=1e-9)
    # cross terms: u_r from a unit shear at B = u_t from a unit pressure at A, up to the sign
    # of a compressive pressure (a traction -p along e_r)
    assert disc.rim(th, zero, ej)["u_r"][i] == pytest.approx(-disc.rim(th, ei)["u_t"][j], rel=1e-9)


def test_the_hitchcock_constant_of_a_steel_roll():
    """C = 16 (1 - nu^2) / (pi E) = 2.207e-11 1/Pa for 210 GPa, 0.3: R'/R - 1 = 0.0221 F'[MN/m]
    / dh[mm] (docs/notes/elastic-roll-and-pyroll-research.md 1)."""
    assert STEEL.hitchcock_constant == pytest.approx(2.2068e-11, rel=1e-4)
    assert STEEL.hitchcock_ratio(1e7, 1e-3) - 1.0 == pytest.approx(0.2207, rel=1e-3)


@pytest.mark.parametrize("kwargs, field", [({"E": 0.0}, "Young"), ({"E": float("nan")}, "Young"),
                                           ({"nu": 0.5}, "Poisson"), ({"nu": -0.1}, "Poisson")])
def test_bad_roll_data_is_refused(kwargs, field):
    with pytest.raises(ValueError, match=field):
        RollElasticity(**kwargs)


def test_bad_loads_are_refused():
    disc = ElasticDisc(0.3)
    with pytest.raises(ValueError, match="increase"):
        disc.rim(np.array([0.1, 0.0]), np.ones(2))
    with pytest.raises(ValueError, match="one length"):
        disc.rim(np.array([0.0, 0.1]), np.ones(3))
    with pytest.raises(ValueError, match="radius"):
        ElasticDisc(0.0)
    with pytest.raises(ValueError, match="draught"):
        STEEL.hitchcock_ratio(1e7, 0.0)


def test_the_rim_displacement_converges_at_second_order_in_the_node_spacing():
    """A smooth load (cos^2 bump of 5 MN/m over |theta| < 0.05 rad) given at n nodes, piecewise
    linear between them: the rim displacement over the loaded arc converges to the finest
    sampling's at the rate of linear interpolation, h^2 (observed orders between 1.8 and 2.2;
    the FFT grid follows the node spacing)."""
    R, a = 0.35, 0.05
    disc = ElasticDisc(R, STEEL)
    at = np.linspace(-a, a, 41)

    def u(n):
        t = np.linspace(-a, a, n)
        p = 5e6 / (R * a) * np.cos(0.5 * math.pi * t / a) ** 2
        w = disc.rim(t, p, at=at)["u_r"]
        return w - w[20]                 # the rim's shape (the rigid shift is the supports')

    ref = u(2561)
    errors = [float(np.max(np.abs(u(n) - ref))) for n in (21, 41, 81, 161)]
    orders = [math.log2(e0 / e1) for e0, e1 in zip(errors, errors[1:])]
    assert all(1.8 < q < 2.2 for q in orders), (errors, orders)
    assert errors[-1] < 1e-3 * float(np.max(np.abs(ref)))


def test_a_carried_roll_surface_keeps_its_shape_in_bite_fractions_and_its_gap():
    """``FlatteningRoll.carry`` (a schedule's next pass starts from the last pass's roll, issue
    34): onto the same pass the surface is the same; onto a pass with another bite angle, w at
    the same fraction of the bite differs by one constant, and the lowest point is at the gap,
    max (R + w) cos t = R (the normalisation ``target`` uses), to rounding."""
    from hotroll.model.geometry import RollPass
    from hotroll.model.roll_elastic import FlatteningRoll

    src_rp, src = FlatteningRoll.start(RollPass(0.35, 0.014, 0.010, omega=3.0), "elastic")
    theta = np.linspace(0.0, src_rp.bite_angle, 60)
    p = 2e8 * np.sin(np.pi * theta / src_rp.bite_angle) + 1e6
    src.update(theta, p, 0.05 * p)
    same_rp, same = FlatteningRoll.start(RollPass(0.35, 0.014, 0.010, omega=5.0), "elastic")
    same.carry(src)
    t = same.shape.theta
    scale = np.ptp(src.shape.w)
    assert np.allclose(same.shape.offset(t), src.shape.offset(t), rtol=0, atol=1e-3 * scale)
    assert np.allclose(same.shape.strain(t), src.shape.strain(t), rtol=0,
                       atol=1e-3 * np.ptp(src.shape.hoop))

    dst_rp, dst = FlatteningRoll.start(RollPass(0.30, 0.005, 0.004, omega=9.0), "elastic")
    b_src, b_dst = src_rp.rigid_bite_angle, dst_rp.rigid_bite_angle   # carry()'s bites
    dst.carry(src)
    R = dst_rp.radius
    t = dst.shape.theta
    assert float(np.max((R + dst.shape.w) * np.cos(t))) == pytest.approx(R, rel=1e-14)
    fractions = np.linspace(-0.4, 2.4, 29)
    shift = dst.shape.offset(fractions * b_dst) - src.shape.offset(fractions * b_src)
    assert np.ptp(shift) < 1e-3 * np.ptp(src.shape.w)   # splines through linear interpolants
    assert np.ptp(dst.shape.w) > 0.5 * np.ptp(src.shape.w)   # the surface, not zeros, carried



def _responses(n, nu):
    """(a_n, b_n) of roll_elastic's module docstring, written out here, zero for n < 2 (the
    supports' modes)."""
    n = np.asarray(n, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        den = 2.0 * (n**2 - 1.0)
        a = np.where(n >= 2, ((2 * n - 1) - 2 * (n - 1) * nu) / den, 0.0)
        b = np.where(n >= 2, (2 * (n - 1) * nu - (n - 2)) / den, 0.0)
    return a, b


def _rim_by_fft(disc, theta, p, q, at, N):
    """The rim's series summed the way hotroll did before issue 34 session 7: the load
    sampled on a uniform grid of N points, an FFT, the responses a_n, b_n, the inverse FFT
    and linear interpolation at ``at`` (first order in the grid: the load's ends are jumps)."""
    grid = -math.pi + 2.0 * math.pi * np.arange(N) / N
    P = np.fft.rfft(np.interp(grid, theta, p, left=0.0, right=0.0))
    Q = np.fft.rfft(np.interp(grid, theta, q, left=0.0, right=0.0))
    n = np.arange(len(P))
    a, b = _responses(n, disc.elasticity.nu)
    c = disc.radius / disc.elasticity.shear_modulus
    Ur, Ut = -c * (a * P + 1j * b * Q), c * (-1j * b * P + a * Q)
    Ur[0] = -c * 0.5 * (1.0 - 2.0 * disc.elasticity.nu) * P[0]
    out = {}
    for key, spec in (("u_r", Ur), ("u_t", Ut), ("hoop", (Ur + 1j * n * Ut) / disc.radius)):
        values = np.fft.irfft(spec, N)
        out[key] = np.interp(at, np.append(grid, math.pi), np.append(values, values[0]))
    return out


def test_the_closed_form_sum_is_the_limit_of_the_fft_sum():
    """An independent summation of the same series (the FFT on a uniform grid) converges to
    the closed form at first order in the grid spacing, for u_r, u_t and the hoop strain, on
    a load with jumps at both ends and a kink (a pressure hill, a shear changing sign)."""
    R, bite = 0.3, 0.05
    disc = ElasticDisc(R, STEEL)
    th = np.linspace(0.0, bite, 41)
    p = 1e9 * np.sqrt(np.sin(np.pi * th / bite)) + 1e8
    q = 0.1 * p * np.where(th < 0.3 * bite, -1.0, 1.0)
    at = np.linspace(-0.5 * bite, 2.5 * bite, 124)     # none at a node
    exact = disc.rim(th, p, q, at=at)
    for key in ("u_r", "u_t", "hoop"):
        scale = float(np.max(np.abs(exact[key])))
        err = [float(np.max(np.abs(_rim_by_fft(disc, th, p, q, at, N)[key] - exact[key])))
               / scale for N in (2**16, 2**18, 2**20)]
        assert err[2] < 1e-4, (key, err)
        assert err[2] < 0.5 * err[1] < 0.25 * err[0], (key, err)
    # at the load's own nodes (a jump at each end): finite, the hoop strain's log taken at
    # half the node spacing there
    at_nodes = disc.rim(th, p, q)
    assert all(np.all(np.isfinite(v)) for v in at_nodes.values())


@pytest.mark.parametrize("psi", [1e-3, 0.3, 2.0, -1.0, 3.1])
def test_the_series_sums_term_by_term(psi):
    """The closed forms of sum_{n>=2} a_n e^(i n psi) / n^2 and b_n's (Li1, Li2 on the unit
    circle, Clausen's series) against the series summed term by term to n = 2e6 (tail below
    1 / 2e6)."""
    from hotroll.model.roll_elastic import _series

    disc = ElasticDisc(0.3, STEEL)
    n = np.arange(2, 2_000_001, dtype=float)
    a, b = _responses(n, disc.elasticity.nu)
    e = np.exp(1j * n * psi)
    _, _, _, _, re_a2, im_b2 = _series(np.array([psi]), STEEL.nu)
    assert re_a2[0] == pytest.approx(np.sum(a * e.real / n**2), abs=1e-6)
    assert im_b2[0] == pytest.approx(np.sum(b * e.imag / n**2), abs=1e-6)


def test_a_load_on_one_node_moves_nothing():
    """One node: a load of zero width (piecewise linear between the nodes, zero outside), so
    the rim does not move (an FFT of it is zero too); from the session's review, where the
    kinks' sum saw a jump with no jump back."""
    disc = ElasticDisc(0.3, STEEL)
    out = disc.rim(np.array([0.01]), np.array([1e9]), np.array([1e8]),
                   at=np.linspace(-0.05, 0.05, 11))
    assert all(np.all(v == 0.0) for v in out.values())

