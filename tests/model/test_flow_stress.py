"""Flow-stress laws (hotroll.model.flow_stress) and the grade library (hotroll.model.grades).

Reference numbers come from outside the implementation:

* hand values: each factor of Spittel's formula evaluated separately with Python's ``decimal``
  (30 digits), A in Pa, T in deg C; the factors are quoted next to each value.
* pyroll values: ``flow_stress(coefficients, strain, strain_rate, T_K)`` of
  pyroll-freiberg-flow-stress 3.0.1.post1, obtained with
      pip download --no-deps pyroll-freiberg-flow-stress && unzip *.whl
  and importing pyroll/freiberg_flow_stress/freiberg_flow_stress.py alone (numpy only) with the
  coefficient sets of its materials.py.  That function evaluates the formula at
  (strain + 0.1, strain_rate + 0.1), so it must equal our sigma at the shifted point.
* Al99.5: the same point evaluated by the (re-typed) ``sigma_LB`` function of the public script
  where the set was read (see grades.py): 44.68136585598319 MPa at 400 degC, phi 0.5, 10 1/s.
The tests run offline; neither package is imported here.
"""

import math

import numpy as np
import pytest
from casebuild import shared_scope

from hotroll.model.flow_stress import (
    DEFAULT_STRAIN_MIN,
    HenselSpittel,
    NortonHoffStress,
    ValidityRange,
)
from hotroll.model.grades import GradeData, get_grade, list_grades
from hotroll.model.material import NortonHoff

C2K = 273.15
RNG = np.random.default_rng(20240611)


# --- Hensel-Spittel reduces to Norton-Hoff --------------------------------------------------------
@pytest.mark.parametrize("A, m3", [(150e6, 0.12), (2.0e6, 0.5), (80e6, 1.0)])
def test_hs_with_only_A_and_m3_is_norton_hoff(A, m3):
    hs = HenselSpittel(A, m3=m3, strain_min=1e-6)
    nh = NortonHoffStress(K=A / 3 ** ((m3 + 1) / 2), m=m3)
    strain = RNG.uniform(0.0, 2.0, 50)
    rate = 10 ** RNG.uniform(-3, 3, 50)
    T = RNG.uniform(300.0, 1600.0, 50)
    np.testing.assert_allclose(hs.sigma(strain, rate, T), nh.sigma(strain, rate, T), rtol=1e-13)
    np.testing.assert_allclose(hs.sigma(strain, rate, T), A * rate**m3, rtol=1e-13)
    edot2 = rate**2
    np.testing.assert_allclose(hs.viscosity(edot2, strain, T), nh.viscosity(edot2, strain, T),
                               rtol=1e-13)
    np.testing.assert_allclose(hs.consistency(strain, T), nh.K, rtol=1e-13)
    np.testing.assert_allclose(hs.rate_exponent(T), m3, rtol=0, atol=0)


def test_norton_hoff_stress_matches_material_module():
    """NortonHoffStress against hotroll.model.material.NortonHoff (independent code)."""
    for K, m, eps0 in [(1.3e7, 0.15, 1e-4), (2e6, 1.0, 1e-6), (5e7, 0.3, 1e-2)]:
        law, ref = NortonHoffStress(K, m, eps0), NortonHoff(K=K, m=m, eps0=eps0)
        edot = 10 ** RNG.uniform(-5, 3, 40)
        np.testing.assert_allclose(law.sigma(0.0, edot, 1000.0), ref.sigma_ef(edot), rtol=1e-13)
        np.testing.assert_allclose(law.viscosity(edot**2), ref.viscosity(edot**2), rtol=1e-13)
        np.testing.assert_allclose(law.viscosity(edot**2, m=1.0), ref.viscosity(edot**2, m=1.0),
                                   rtol=1e-13)
        np.testing.assert_allclose(law.power_density(edot), ref.power_density(edot), rtol=1e-13)
        assert law.consistency(0.3, 1200.0) == K and law.rate_exponent(1200.0) == m


# --- mu = 2 sigma / (3 edot) ----------------------------------------------------------------------
def _plane_strain_rates(n):
    """Random deviatoric plane-strain rates (eps_zz = 0, eps_xx = -eps_yy), shape (n, 2, 2)."""
    a, b = RNG.normal(0, 3, n), RNG.normal(0, 3, n)
    return np.stack([np.stack([a, b], -1), np.stack([b, -a], -1)], -2)


@pytest.mark.parametrize("law, T_range", [
    (HenselSpittel(3000e6, -0.0025, 0.3, 0.02, 0.0005, -0.0013, 0.05, 0.00013, eps0=1e-12),
     (850.0, 1400.0)),
    (get_grade("Al99.5").law(eps0=1e-12), (550.0, 800.0)),
    (NortonHoffStress(2e7, 0.2, eps0=1e-12), (850.0, 1400.0)),
], ids=["hs", "al", "nh"])
def test_secant_viscosity_reproduces_effective_stress(law, T_range):
    """s = mu eps_dot for random plane-strain deviatoric eps_dot: sqrt(3/2 s:s) == sigma(edot)."""
    eps = _plane_strain_rates(200)
    edot2 = 2.0 / 3.0 * np.einsum("...ij,...ij->...", eps, eps)  # (2.16)
    edot = np.sqrt(edot2)
    strain = RNG.uniform(0.05, 1.0, 200)
    T = RNG.uniform(*T_range, 200)
    s = law.viscosity(edot2, strain, T)[:, None, None] * eps
    s_eff = np.sqrt(1.5 * np.einsum("...ij,...ij->...", s, s))
    np.testing.assert_allclose(s_eff, law.sigma(strain, edot, T), rtol=1e-10)
    # power density s:eps_dot = sigma * edot
    np.testing.assert_allclose(np.einsum("...ij,...ij->...", s, eps),
                               law.power_density(edot, strain, T), rtol=1e-10)


def test_regularised_viscosity():
    """With eps0 > 0: mu = 2 sigma(e) / (3 e), e = sqrt(edot^2 + eps0^2); finite at edot = 0."""
    law = get_grade("S355J2").law(eps0=1e-2)
    edot2 = np.array([0.0, 1e-6, 1e-2, 1.0, 100.0])
    e = np.sqrt(edot2 + 1e-4)
    np.testing.assert_allclose(law.viscosity(edot2, 0.2, 1300.0),
                               2 * law.sigma(0.2, e, 1300.0) / (3 * e), rtol=1e-12)
    assert np.all(np.isfinite(law.viscosity(edot2, 0.2, 1300.0)))


def test_frozen_norton_hoff_equals_law():
    """consistency/rate_exponent define a Norton-Hoff law equal to HS at that (strain, T)."""
    law = get_grade("C45").law()
    for strain, T in [(0.0, 1173.15), (0.25, 1273.15), (1.2, 1473.15)]:
        nh = law.norton_hoff_at(strain, T)
        edot = 10 ** np.linspace(-3, 3, 13)
        np.testing.assert_allclose(nh.sigma_ef(edot), law.sigma(strain, edot, T), rtol=1e-12)
        np.testing.assert_allclose(nh.viscosity(edot**2), law.viscosity(edot**2, strain, T),
                                   rtol=1e-12)
        K, m = law.consistency(strain, T), law.rate_exponent(T)
        np.testing.assert_allclose(K * 3 ** ((m + 1) / 2) * edot**m, law.sigma(strain, edot, T),
                                   rtol=1e-12)


# --- rate exponent -------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["S355J2", "C45", "C20", "Al99.5"])
def test_rate_exponent_is_log_derivative(name):
    law = get_grade(name).law()
    T = np.array([600.0, 700.0, 800.0]) if name == "Al99.5" else np.array([1100.0, 1250.0, 1500.0])
    for strain in (0.0, 0.1, 0.8):
        for edot in (1e-2, 1.0, 50.0):
            h = 1e-4
            num = (np.log(law.sigma(strain, edot * (1 + h), T))
                   - np.log(law.sigma(strain, edot * (1 - h), T))) / (np.log1p(h) - np.log1p(-h))
            np.testing.assert_allclose(num, law.rate_exponent(T), rtol=1e-7)


def test_rate_exponent_values():
    """m3 + m8 T_C with T_C = T_K - 273.15."""
    law = get_grade("S355J2").law()
    assert law.rate_exponent(1000.0 + C2K) == pytest.approx(0.000127 * 1000.0, rel=1e-12)
    al = get_grade("Al99.5").law()
    assert al.rate_exponent(250.0 + C2K) == pytest.approx(0.06025, rel=1e-12)
    assert al.rate_exponent(550.0 + C2K) == pytest.approx(0.13255, rel=1e-12)


# --- the grades against independent numbers ------------------------------------------------------
# (name, T_C, strain, rate, hand value Pa [factors A, e^(m1T), eps^m2, e^(m4/eps), (1+eps)^(m5T),
#  e^(m7 eps), edot^(m8T)], pyroll value at (strain - 0.1, rate - 0.1) or None)
HAND = [
    ("S355J2", 1100.0, 0.3, 10.0, 109752700.426743497912764,
     # 2852.66e6, 0.0682894493123, 0.603581648619, 1.00293763977, 0.650499317995,
     # 1.03718156426, 1.3794310582
     None),
    ("S355J2", 1100.0, 0.4, 10.1, 111077595.839142651196572, 111077595.83914268),
    ("C45", 1100.0, 0.3, 10.0, 114023455.012404792498655,
     # 3268.49e6, 0.0525282058168, 0.660524889986, 1.0018410727, 0.683127251416,
     # 1.00500249088, 1.46183279267
     None),
    ("C45", 1100.0, 0.4, 10.1, 113375396.747167204581582, 113375396.7471672),
    ("C20", 1100.0, 0.3, 10.0, 101096610.866844907767065,
     # 3304.39e6, 0.0454564751936, 0.6579849731, 1.00006666889, 0.68716496065,
     # 1.02316012536, 1.45478897122
     None),
    ("C20", 1100.0, 0.4, 10.1, 101428386.648839955298567, 101428386.64883995),
    ("Al99.5", 400.0, 0.5, 10.0, 44681365.8559831833695499,
     # 367.651e6, 0.156923006246, 0.796027402408, 1.00334558402, 0.714819575912,
     # 1.08649834775, 1.24853292616 ; source script sigma_LB: 44.68136585598319 MPa
     None),
    ("Al99.5", 300.0, 0.2, 1.0, 50237628.6438946355994614, None),
]


@pytest.mark.parametrize("name, T_C, strain, rate, hand, pyroll", HAND)
def test_grade_values(name, T_C, strain, rate, hand, pyroll):
    law = get_grade(name).law()
    value = law.sigma(strain, rate, T_C + C2K)
    assert value == pytest.approx(hand, rel=1e-12)
    if pyroll is not None:
        # pyroll's flow_stress(c, strain - 0.1, rate - 0.1, T_K) == our sigma(strain, rate, T_K)
        assert value == pytest.approx(pyroll, rel=1e-12)


@pytest.mark.parametrize("name, T_C, strain, rate, pyroll", [
    ("S355J2", 1000.0, 0.2, 1.0, 106885181.44021356),
    ("C45", 1000.0, 0.2, 1.0, 107071726.64917077),
    ("C20", 1000.0, 0.2, 1.0, 96585537.11797267),
])
def test_grade_values_pyroll_offsets(name, T_C, strain, rate, pyroll):
    """pyroll-freiberg-flow-stress at (strain, rate, T) = ours at (strain+0.1, rate+0.1, T)."""
    law = get_grade(name).law()
    assert law.sigma(strain + 0.1, rate + 0.1, T_C + C2K) == pytest.approx(pyroll, rel=1e-12)


def test_grade_library():
    names = list_grades()
    assert {"S355J2", "C45", "Al99.5"} <= set(names)
    for n in names:
        g = get_grade(n)
        assert isinstance(g, GradeData) and g.source and g.read_at
        assert g.law_params["A"] > 1e6  # A in Pa, not MPa
        law = g.law()
        assert isinstance(law, HenselSpittel) and law.name == g.name
        assert g.describe()["source"] == g.source
    assert get_grade("en aw-1050a") is get_grade("AL99.5") is get_grade("aa1050a")
    assert get_grade("1.0577") is get_grade("s355j2")
    with pytest.raises(KeyError, match="available"):
        get_grade("X5CrNi18-10")
    # the published Al99.5 box, in K at the interface
    v = get_grade("Al99.5").validity
    assert v.strain == (0.03, 1.5) and v.strain_rate == (0.01, 500.0)
    assert v.temperature == pytest.approx((523.15, 823.15))


# --- NGSolve CoefficientFunctions ----------------------------------------------------------------
@pytest.fixture(scope=shared_scope)
def mesh():
    ngsolve = pytest.importorskip("ngsolve")
    from netgen.geom2d import unit_square

    return ngsolve.Mesh(unit_square.GenerateMesh(maxh=0.5))


@pytest.mark.parametrize("law", [
    get_grade("S355J2").law(),
    get_grade("Al99.5").law(),
    HenselSpittel(3e9, -0.0027, 0.3, 0.01, 0.0005, -0.0013, 0.02, 0.00015, 0.05, m6=0.1),
    NortonHoffStress(1.5e7, 0.18),
], ids=["s355", "al", "hs-all-terms", "nh"])
def test_coefficient_function_equals_numpy(mesh, law):
    from ngsolve import CoefficientFunction, sqrt, x, y

    if isinstance(law, HenselSpittel) and law.name == "Al99.5":
        T_cf, T_of = 600.0 + 100.0 * y, lambda X, Y: 600.0 + 100.0 * Y
    else:
        T_cf, T_of = 1200.0 + 200.0 * y, lambda X, Y: 1200.0 + 200.0 * Y
    strain_cf = 0.05 * x + 0.4 * x * y          # 0 on the left edge: strain floor active there
    edot2_cf = 0.5 + 30.0 * x * x
    for X, Y in [(0.3, 0.4), (0.0, 0.7), (0.9, 0.1)]:
        p = mesh(X, Y)
        s, T, e2 = 0.05 * X + 0.4 * X * Y, T_of(X, Y), 0.5 + 30.0 * X * X
        e = math.sqrt(e2)
        checks = [
            (law.sigma(strain_cf, sqrt(edot2_cf), T_cf), law.sigma(s, e, T)),
            (law.viscosity(edot2_cf, strain_cf, T_cf), law.viscosity(e2, s, T)),
            (law.viscosity(edot2_cf, strain_cf, T_cf, m=1.0), law.viscosity(e2, s, T, m=1.0)),
            (law.consistency(strain_cf, T_cf), law.consistency(s, T)),
            (law.power_density(sqrt(edot2_cf), strain_cf, T_cf), law.power_density(e, s, T)),
            (law.sigma(s, sqrt(edot2_cf), T), law.sigma(s, e, T)),   # mixed float / CF arguments
        ]
        if isinstance(law, HenselSpittel):
            checks.append((law.rate_exponent(T_cf), law.rate_exponent(T)))
        for cf, ref in checks:
            val = cf(p) if isinstance(cf, CoefficientFunction) else cf  # NH: K, m are numbers
            assert val == pytest.approx(float(ref), rel=1e-12)


# --- strain floor, ranges, validation ------------------------------------------------------------
def test_strain_floor():
    law = get_grade("S355J2").law()
    assert law.strain_min == DEFAULT_STRAIN_MIN
    s0 = law.sigma(0.0, 1.0, 1273.15)
    assert np.isfinite(s0) and s0 > 0
    assert s0 == law.sigma(law.strain_min, 1.0, 1273.15) == law.sigma(1e-9, 1.0, 1273.15)
    assert law.sigma(0.3, 1.0, 1273.15) > s0
    al = get_grade("Al99.5").law()
    assert al.strain_min == 0.03  # the fit's lower strain bound
    assert get_grade("Al99.5").law(strain_min=0.01).strain_min == 0.01
    # the floor also applies to arrays (no warnings, no nan)
    with np.errstate(all="raise"):
        v = law.sigma(np.array([0.0, 0.01, 0.5]), 1.0, 1273.15)
    assert np.all(np.isfinite(v)) and v[0] == v[1]
    # zero strain rate: sigma = 0, the viscosity stays finite through eps0
    assert law.sigma(0.2, 0.0, 1273.15) == 0.0
    assert np.isfinite(law.viscosity(0.0, 0.2, 1273.15))


def test_in_range_and_report():
    al = get_grade("Al99.5").law()
    assert al.in_range(0.5, 10.0, 673.15) is True
    assert al.in_range(0.02, 10.0, 673.15) is False
    assert al.in_range(0.5, 1000.0, 673.15) is False
    assert al.in_range(0.5, 10.0, 900.0) is False
    got = al.in_range(np.array([0.01, 0.5, 2.0]), 1.0, 700.0)
    np.testing.assert_array_equal(got, [False, True, False])
    rep = al.range_report(0.5, 1e3, 700.0)
    assert rep["strain"] and not rep["strain_rate"] and rep["temperature"] and not rep["inside"]
    steel = get_grade("S355J2").law()
    with pytest.raises(ValueError, match="unknown"):
        steel.in_range(0.3, 10.0, 1373.15)
    assert steel.range_report(0.3, 10.0, 1373.15)["inside"] is None


@pytest.mark.parametrize("kwargs, match", [
    (dict(A=0.0, m3=0.1), "A must be > 0"),
    (dict(A=-1e6, m3=0.1), "A must be > 0"),
    (dict(A=float("nan"), m3=0.1), "A must be finite"),
    (dict(A=1e8, m3=0.0), "m3"),
    (dict(A=1e8, m3=1.5), "m3"),
    (dict(A=1e8, m3=0.1, m2=float("inf")), "m2 must be finite"),
    (dict(A=1e8, m3=2.0, m8=0.001), "nowhere in \\(0, 1\\]"),
    (dict(A=1e8, m8=0.0001, validity=ValidityRange.from_celsius(temperature_c=(-50.0, 900.0))),
     "rate exponent"),
    (dict(A=1e8, m3=0.1, strain_min=0.0), "strain_min must be > 0"),
    (dict(A=1e8, m3=0.1, eps0=0.0), "eps0 must be > 0"),
    (dict(A=1e8, m3=0.1, m9=0.1, validity=ValidityRange.from_celsius(temperature_c=(-10.0, 500.0))),
     "m9"),
])
def test_bad_parameters(kwargs, match):
    with pytest.raises(ValueError, match=match):
        HenselSpittel(**kwargs)


def test_bad_parameters_norton_hoff_and_ranges():
    with pytest.raises(ValueError, match="K must be > 0"):
        NortonHoffStress(0.0, 0.2)
    with pytest.raises(ValueError, match=r"m \(rate exponent\) must lie in \(0, 1\]"):
        NortonHoffStress(1e7, 0.0)
    with pytest.raises(ValueError, match=r"m \(rate exponent\)"):
        NortonHoffStress(1e7, 1.2)
    with pytest.raises(ValueError, match="strain"):
        ValidityRange(strain=(0.5, 0.1))
    with pytest.raises(ValueError, match="temperature"):
        ValidityRange(temperature=(-5.0, 100.0))


def test_viscosity_refuses_non_monotone_temperatures():
    """Steel sets have m = m8 T_C: at or below 0 degC the exponent is <= 0 -> ValueError."""
    law = get_grade("S355J2").law()
    lo, hi = law.admissible_temperature_range()
    assert lo == pytest.approx(C2K) and hi > 5000.0
    with pytest.raises(ValueError, match="rate exponent"):
        law.viscosity(1.0, 0.2, 250.0)
    assert np.isfinite(law.viscosity(1.0, 0.2, 1273.15))


def test_describe():
    d = get_grade("Al99.5").law().describe()
    assert d["law"] == "HenselSpittel" and d["parameters"]["A"] == 367.651e6
    assert d["validity"]["temperature_C"] == (250.0, 550.0)
    assert d["units"]["temperature"] == "K" and "strain_min" in d
    assert NortonHoffStress(1e7, 0.2).describe()["m"] == 0.2


def test_repr_names_the_coefficients_given():
    """repr: A and every non-zero coefficient (zeros left out), the strain floor and the name."""
    law = HenselSpittel(1.5e9, m1=-0.0025, m3=0.1, strain_min=0.05, name="lab")
    assert repr(law) == "HenselSpittel(A=1500000000.0, m1=-0.0025, m3=0.1, strain_min=0.05, name='lab')"
