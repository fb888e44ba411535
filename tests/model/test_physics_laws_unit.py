"""Fast unit tests of hotroll/physics (flow-stress laws, grades, Norton-Hoff, friction helpers).

Complements tests/model/test_flow_stress.py and tests/fem/test_quantities_unit.py (not repeated here): the
boundaries of every validity check, the error messages (each names the field and the allowed
range: the project's rule for bad input), the user-facing ``describe()`` / ``as_dict()`` /
``range_report()`` outputs written out literally, NGSolve CoefficientFunctions given for only one
argument, and the published grade coefficients at points not checked elsewhere.

Expected numbers are derived by hand from the formula the docstring cites; the comment next to
each says how.  No FE solve: pure numbers and CoefficientFunctions evaluated at a point of a
coarse unit-square mesh (about a second in all).
"""
from __future__ import annotations

import math
import re
import sys
import warnings

import numpy as np
import pytest
from casebuild import shared_scope

from hotroll.model.flow_stress import HenselSpittel, NortonHoffStress, ValidityRange
from hotroll.model.friction import smooth_minimum, smooth_positive_part
from hotroll.model.friction_estimate import estimate_a_f
from hotroll.model.grades import GradeData, get_grade
from hotroll.model.material import NortonHoff, edot_squared

pytestmark = pytest.mark.mutation   # cheap: in mutmut's test selection ([tool.mutmut])

C2K = 273.15


def exactly(message: str) -> str:
    """pytest.raises(match=...) pattern for the whole message, literally."""
    return "^" + re.escape(message) + "$"


@pytest.fixture(scope=shared_scope)
def mesh():
    ngsolve = pytest.importorskip("ngsolve")
    from netgen.geom2d import unit_square

    return ngsolve.Mesh(unit_square.GenerateMesh(maxh=0.5))


@pytest.fixture
def point(mesh):
    """A mesh point to evaluate CoefficientFunctions at (all CFs here are constants); the mesh
    fixture keeps the mesh alive while the point is used."""
    return mesh(0.3, 0.4)


def cf(value):
    import ngsolve

    return ngsolve.CoefficientFunction(value)


# =================================================================================================
# 1. ValidityRange: checks, messages, as_dict
# =================================================================================================
def test_validity_range_accepts_closed_lower_bounds():
    # "0 <= low < high" (the message's own words): a box starting at 0 is allowed, for every entry
    v = ValidityRange(strain=(0.0, 1.0), strain_rate=(0.0, 10.0), temperature=(0.0, 300.0))
    assert (v.strain, v.strain_rate, v.temperature) == ((0.0, 1.0), (0.0, 10.0), (0.0, 300.0))
    assert v.complete


@pytest.mark.parametrize("kwargs, message", [
    # low == high is not a range ("low < high")
    (dict(strain=(0.5, 0.5)),
     "validity range strain must satisfy 0.0 <= low < high, got (0.5, 0.5)"),
    # below absolute zero
    (dict(temperature=(-5.0, 100.0)),
     "validity range temperature must satisfy 0.0 <= low < high, got (-5.0, 100.0)"),
    (dict(strain_rate=(0.1, 0.2, 0.3)),
     "validity range strain_rate must be a pair (low, high), got (0.1, 0.2, 0.3)"),
    (dict(strain=(float("nan"), 1.0)), "strain range low must be finite, got nan"),
    (dict(temperature=(300.0, "hot")),
     "temperature range high must be a real number, got 'hot'"),
])
def test_validity_range_messages_name_the_entry_and_the_rule(kwargs, message):
    with pytest.raises(ValueError, match=exactly(message)):
        ValidityRange(**kwargs)


def test_validity_range_as_dict_literal():
    v = ValidityRange(strain=(0.05, 1.5), strain_rate=(0.1, 100.0), temperature=(1073.0, 1473.0))
    # T_C = T_K - 273.15: 1073 K = 799.85 degC, 1473 K = 1199.85 degC (rounded to 10 decimals,
    # so that the float noise of the subtraction does not show)
    assert v.as_dict() == {
        "strain": (0.05, 1.5),
        "strain_rate_1_per_s": (0.1, 100.0),
        "temperature_K": (1073.0, 1473.0),
        "temperature_C": (799.85, 1199.85),
    }
    assert ValidityRange().as_dict() == {
        "strain": None, "strain_rate_1_per_s": None, "temperature_K": None, "temperature_C": None}
    # the Celsius column is rounded to 10 decimals: 4e-11 K below that is not shown
    # (300.00000000004 K - 273.15 = 26.85000000004 degC -> 26.85)
    assert ValidityRange(temperature=(300.00000000004, 400.0)).as_dict()["temperature_C"] == \
        (26.85, 126.85)


# =================================================================================================
# 2. NortonHoffStress: construction, messages, describe
# =================================================================================================
@pytest.mark.parametrize("args, message", [
    (("soft", 0.2), "K must be a real number, got 'soft'"),
    ((float("inf"), 0.2), "K must be finite, got inf"),
    ((1e7, float("nan")), "m must be finite, got nan"),
    ((1e7, 0.2, float("inf")), "eps0 must be finite, got inf"),
    # eps0 > 0 strictly: eps0 = 0 would make the viscosity infinite at rest
    ((1e7, 0.2, 0.0), "eps0 must be > 0 (1/s), got 0.0"),
])
def test_norton_hoff_stress_messages(args, message):
    with pytest.raises(ValueError, match=exactly(message)):
        NortonHoffStress(*args)


def test_norton_hoff_stress_name_and_validity_are_kept():
    law = NortonHoffStress(1e7, 0.2)
    assert law.name == "Norton-Hoff"      # the default name (shown in messages)
    with pytest.raises(ValueError, match=exactly(
            "validity range(s) strain, strain_rate, temperature unknown for Norton-Hoff;"
            " cannot tell whether the state is inside the fit")):
        law.in_range(0.1, 1.0, 1273.15)
    box = ValidityRange(strain=(0.0, 2.0), strain_rate=(0.01, 10.0), temperature=(1000.0, 1500.0))
    named = NortonHoffStress(1e7, 0.2, validity=box, name="my law")
    assert named.name == "my law" and named.validity is box
    assert named.in_range(1.0, 1.0, 1200.0) is True
    assert named.in_range(1.0, 100.0, 1200.0) is False


def test_norton_hoff_stress_describe_literal():
    law = NortonHoffStress(2.0e7, 0.25, 1e-3, validity=ValidityRange(strain_rate=(0.01, 10.0)))
    assert law.describe() == {
        "law": "NortonHoff",
        "formula": "sigma = K 3^((m+1)/2) edot^m",
        "K_Pa_s^m": 2.0e7,
        "m": 0.25,
        "eps0_1_per_s": 1e-3,
        "validity": {"strain": None, "strain_rate_1_per_s": (0.01, 10.0), "temperature_K": None,
                     "temperature_C": None},
        "units": {"sigma": "Pa", "strain_rate": "1/s", "temperature": "K"},
    }


# =================================================================================================
# 3. HenselSpittel: construction checks and their boundaries
# =================================================================================================
@pytest.mark.parametrize("kwargs, message", [
    (dict(A="a lot", m3=0.1), "A must be a real number, got 'a lot'"),
    (dict(A=1e8, m3=0.1, eps0=float("nan")), "eps0 must be finite, got nan"),
    (dict(A=1e8, m3=0.1, strain_min=float("inf")), "strain_min must be finite, got inf"),
])
def test_hensel_spittel_messages_name_the_parameter(kwargs, message):
    with pytest.raises(ValueError, match=exactly(message)):
        HenselSpittel(**kwargs)


def test_hensel_spittel_a_only_needs_to_be_positive():
    # "A (> 0)" in Pa: 0.5 Pa is accepted (a tiny but valid value)
    assert HenselSpittel(0.5, m3=0.1).A == 0.5


def test_default_name_is_empty_and_messages_fall_back_to_the_class_name():
    law = HenselSpittel(1e8, m3=0.1, validity=ValidityRange(temperature=(1000.0, 1500.0)))
    assert law.name == ""
    with pytest.raises(ValueError, match=exactly(
            "validity range(s) strain, strain_rate unknown for HenselSpittel;"
            " cannot tell whether the state is inside the fit")):
        law.in_range(0.1, 1.0, 1200.0)
    # a named set is named
    with pytest.raises(ValueError, match=exactly(
            "validity range(s) strain, strain_rate, temperature unknown for S355J2;"
            " cannot tell whether the state is inside the fit")):
        get_grade("S355J2").law().in_range(0.3, 10.0, 1373.15)


@pytest.mark.parametrize("strain_box, floor", [
    ((0.05, 2.0), 0.05),    # default strain_min = the fit's lower strain bound (> 0)
    ((1.5, 3.0), 1.5),      # ... whatever its size
    ((0.0, 1.0), 0.03),     # a bound of 0 is no floor: DEFAULT_STRAIN_MIN = 0.03
])
def test_strain_floor_defaults_to_the_lower_strain_bound(strain_box, floor):
    law = HenselSpittel(1e8, m3=0.1, validity=ValidityRange(strain=strain_box))
    assert law.strain_min == floor


def test_rate_exponent_may_reach_one_at_the_ends_of_the_validity_range():
    # m = m3 + m8 T_C in (0, 1]: closed at m = 1.
    # m8 > 0: m3 = 0.5, m8 = 0.001 -> m = 1 at T_C = 500 degC, the upper end of the box
    law = HenselSpittel(1e8, m3=0.5, m8=0.001,
                        validity=ValidityRange.from_celsius(temperature_c=(100.0, 500.0)))
    assert law.rate_exponent(500.0 + C2K) == 1.0
    # m8 < 0: m3 = 1.25, m8 = -2^-10 -> m = 1 at T_C = 0.25 * 1024 = 256 degC, the lower end
    law = HenselSpittel(1e8, m3=1.25, m8=-0.0009765625,
                        validity=ValidityRange.from_celsius(temperature_c=(256.0, 1000.0)))
    assert law.rate_exponent(256.0 + C2K) == 1.0


def test_rate_exponent_zero_at_the_lower_end_is_refused():
    # the steel form m = m8 T_C (m3 = 0) is 0 at 0 degC: a box from 0 degC is refused
    # (m = 0: rate-insensitive, no Norton-Hoff viscosity); admissible T: 273.15 .. 273.15 + 1/m8
    with pytest.raises(ValueError, match=exactly(
            "rate exponent m3 + m8*T_C must lie in (0, 1] over the validity temperature range "
            "(273.15, 1473.15) K; it is 0 .. 0.1524 (admissible T: 273.15 .. 8147.17 K)")):
        HenselSpittel(1e8, m8=0.000127,
                      validity=ValidityRange.from_celsius(temperature_c=(0.0, 1200.0)))


def test_rate_exponent_above_one_at_the_upper_end_is_refused():
    # m3 = 0.5, m8 = 0.001: m = 0.6 at 100 degC, 1.4 at 900 degC; m = 1 at 500 degC = 773.15 K,
    # m = 0 at -500 degC (below 0 K, so the admissible range starts at 0 K)
    with pytest.raises(ValueError, match=exactly(
            "rate exponent m3 + m8*T_C must lie in (0, 1] over the validity temperature range "
            "(373.15, 1173.15) K; it is 0.6 .. 1.4 (admissible T: 0 .. 773.15 K)")):
        HenselSpittel(1e8, m3=0.5, m8=0.001,
                      validity=ValidityRange.from_celsius(temperature_c=(100.0, 900.0)))


def test_m9_and_temperatures_at_or_below_zero_celsius():
    # without m9 a box below 0 degC is fine (m = 0.1 - 0.0001 * 50 = 0.095 at -50 degC)
    law = HenselSpittel(1e8, m3=0.1, m8=0.0001,
                        validity=ValidityRange.from_celsius(temperature_c=(-50.0, 900.0)))
    assert law.validity.temperature[0] < C2K
    # T^m9 needs T_C > 0: a box starting at exactly 0 degC is refused
    with pytest.raises(ValueError, match=exactly(
            "m9 != 0 needs T_C > 0 (T > 273.15 K) over the validity temperature range, "
            "got (273.15, 773.15) K")):
        HenselSpittel(1e8, m3=0.1, m9=0.1,
                      validity=ValidityRange.from_celsius(temperature_c=(0.0, 500.0)))


# =================================================================================================
# 4. admissible_temperature_range: T where m3 + m8 (T - 273.15) lies in (0, 1]
# =================================================================================================
def test_admissible_temperature_range_by_hand():
    # m8 = 0: m = m3 everywhere
    assert HenselSpittel(1e8, m3=0.2).admissible_temperature_range() == (0.0, math.inf)
    # m3 = -0.1, m8 = 0.0005: m = 0 at T_C = 200, m = 1 at T_C = 1.1 / 0.0005 = 2200
    lo, hi = HenselSpittel(1e8, m3=-0.1, m8=0.0005).admissible_temperature_range()
    assert lo == pytest.approx(200.0 + C2K, rel=1e-14)
    assert hi == pytest.approx(2200.0 + C2K, rel=1e-14)
    # m8 < 0: m3 = 1.25, m8 = -2^-10: m = 1 at T_C = 256, m = 0 at T_C = 1280 (lo, hi swapped)
    lo, hi = HenselSpittel(1e8, m3=1.25, m8=-0.0009765625).admissible_temperature_range()
    assert lo == pytest.approx(256.0 + C2K, rel=1e-14)
    assert hi == pytest.approx(1280.0 + C2K, rel=1e-14)
    # m3 = 0.1, m8 = 0.0001: m = 0 at T_C = -1000 (below 0 K: clipped to 0 K), m = 1 at T_C = 9000
    lo, hi = HenselSpittel(1e8, m3=0.1, m8=0.0001).admissible_temperature_range()
    assert lo == 0.0
    assert hi == pytest.approx(9000.0 + C2K, rel=1e-14)


def test_rate_exponent_positive_only_below_absolute_zero_is_refused():
    # m3 = -273.15, m8 = -1: m = -T_K, positive only for T < 0 K (the range would be the single
    # point T = 0 K, where m = 0)
    with pytest.raises(ValueError, match=exactly(
            "rate exponent m3 + m8*T_C (m3=-273.15, m8=-1.0) is nowhere in (0, 1] for T > 0 K")):
        HenselSpittel(1e8, m3=-273.15, m8=-1.0)


# =================================================================================================
# 5. HenselSpittel.sigma: the m6 and m9 terms, zero rate, one CoefficientFunction argument
# =================================================================================================
def test_m6_term_by_hand():
    # only A, m3, m6: sigma = A (1 + eps)^m6 edot^m3; eps = 3, edot = 1: 1e8 * 4^0.5 = 2e8
    law = HenselSpittel(1e8, m3=0.1, m6=0.5)
    assert law.sigma(3.0, 1.0, 1273.15) == pytest.approx(2e8, rel=1e-14)


def test_m9_term_by_hand():
    # T^m9 with T in degC: T_C = 100 -> 1e8 * 100^0.5 = 1e9, 1e8 * 100^1 = 1e10
    assert HenselSpittel(1e8, m3=0.1, m9=0.5).sigma(0.5, 1.0, 100.0 + C2K) == \
        pytest.approx(1e9, rel=1e-13)
    assert HenselSpittel(1e8, m3=0.1, m9=1.0).sigma(0.5, 1.0, 100.0 + C2K) == \
        pytest.approx(1e10, rel=1e-13)
    # without m9 the law is defined below 0 degC (no log of T_C): sigma = A edot^m3 = 1e8
    assert HenselSpittel(1e8, m3=0.1).sigma(0.5, 1.0, -10.0 + C2K) == pytest.approx(1e8, rel=1e-14)


def test_zero_rate_gives_zero_stress_without_floating_point_warnings():
    # edot = 0: edot^m = 0 (log -> -inf, exp -> 0), silently (module docstring)
    law = get_grade("S355J2").law()
    with np.errstate(all="raise"), warnings.catch_warnings():
        warnings.simplefilter("error")
        assert law.sigma(0.2, 0.0, 1273.15) == 0.0
        np.testing.assert_array_equal(law.sigma(0.2, np.array([0.0, 0.0]), 1273.15), [0.0, 0.0])


# S355J2 at (strain 0.3, 10 1/s, 1100 degC): 109752700.426743497912764 Pa, the hand value of
# tests/model/test_flow_stress.py (each factor of Spittel's formula in 30-digit decimal)
S355_HAND = 109752700.426743497912764


def test_sigma_with_only_strain_or_only_temperature_a_coefficient_function(point):
    # "any argument may be a CoefficientFunction; the result is then one too"
    law = get_grade("S355J2").law()
    T = 1100.0 + C2K
    assert law.sigma(cf(0.3), 10.0, T)(point) == pytest.approx(S355_HAND, rel=1e-12)
    assert law.sigma(0.3, 10.0, cf(T))(point) == pytest.approx(S355_HAND, rel=1e-12)
    assert law.sigma(0.3, cf(10.0), T)(point) == pytest.approx(S355_HAND, rel=1e-12)


def test_viscosity_with_the_exponent_a_coefficient_function(point):
    # m overrides the exponent with K kept; m = 1 (Newtonian): mu = 2 K sqrt3^0 (...)^0 = 2 K
    nh = NortonHoffStress(1e7, 0.5)
    assert nh.viscosity(3.0, m=cf(1.0))(point) == pytest.approx(2e7, rel=1e-14)
    law = get_grade("S355J2").law()
    K = float(law.consistency(0.3, 1100.0 + C2K))
    mu = law.viscosity(3.0, 0.3, 1100.0 + C2K, m=cf(1.0))
    assert mu(point) == pytest.approx(2 * K, rel=1e-14)
    # ... and K from the hand value: sigma(edot = 1) / 3^((m+1)/2), m = m8 T_C = 0.1397,
    # sigma(edot = 1) = S355_HAND / 10^0.1397
    m = 0.000127 * 1100.0
    assert K == pytest.approx(S355_HAND / 10.0**m / 3.0 ** ((m + 1.0) / 2.0), rel=1e-12)


def test_numbers_do_not_need_ngsolve(monkeypatch):
    # the numpy backend works with NGSolve not importable (flow_stress._is_cf: "nothing can be
    # a CF if ngsolve was never imported"; friction._is_cf: the ImportError branch)
    monkeypatch.setitem(sys.modules, "ngsolve", None)
    law = get_grade("S355J2").law()
    assert law.sigma(0.3, 10.0, 1100.0 + C2K) == pytest.approx(S355_HAND, rel=1e-12)
    assert np.isfinite(law.viscosity(100.0, 0.3, 1100.0 + C2K))
    # (3, 4, 5): (-3 + 5) / 2 = 1
    assert smooth_positive_part(-3.0, 4.0) == pytest.approx(1.0, rel=1e-15)


def test_smooth_helpers_on_coefficient_functions(point):
    # the same Pythagorean triples as on numbers: (-3 + sqrt(9 + 16)) / 2 = 1,
    # (10 + 4 - sqrt(36 + 64)) / 2 = 2
    assert smooth_positive_part(cf(-3.0), 4.0)(point) == pytest.approx(1.0, rel=1e-15)
    assert smooth_minimum(cf(10.0), 4.0, 8.0)(point) == pytest.approx(2.0, rel=1e-15)


def test_array_likes_and_single_precision_inputs():
    law = get_grade("S355J2").law()
    # lists are evaluated like arrays: the m = m8 T_C of 1000 and 1100 degC = 0.127, 0.1397
    np.testing.assert_allclose(law.rate_exponent([1000.0 + C2K, 1100.0 + C2K]), [0.127, 0.1397],
                               rtol=1e-12)
    np.testing.assert_allclose(law.sigma([0.3, 0.3], [10.0, 10.0], [1100.0 + C2K] * 2),
                               [S355_HAND] * 2, rtol=1e-12)
    # float32 arrays (single-precision fields from a file) are evaluated in double precision:
    # the value at the float32 numbers equals the float64 evaluation at the same numbers
    s32 = np.array([0.3, 0.7], np.float32)
    r32 = np.array([10.0, 3.3], np.float32)
    t32 = np.array([1373.15, 1250.3], np.float32)
    got = law.sigma(s32, r32, t32)
    assert got.dtype == np.float64
    ref = [law.sigma(float(s), float(r), float(t)) for s, r, t in zip(s32, r32, t32)]
    np.testing.assert_allclose(got, ref, rtol=1e-14)
    nh = NortonHoffStress(1e7, 0.2)
    np.testing.assert_allclose(nh.sigma(0.0, r32), [nh.sigma(0.0, float(r)) for r in r32],
                               rtol=1e-14)


# =================================================================================================
# 6. viscosity: refused rate exponents, with a message naming m and the temperature
# =================================================================================================
def test_viscosity_refuses_a_rate_exponent_above_one():
    # m3 = 0.5, m8 = 0.001: m = 0.5 + 0.001 * 1000 = 1.5 at 1000 degC
    law = HenselSpittel(1e8, m3=0.5, m8=0.001)
    with pytest.raises(ValueError, match=exactly(
            "rate exponent m must lie in (0, 1]; got m = [1.5] at temperature [1273.15] K")):
        law.viscosity(1.0, 0.2, 1000.0 + C2K)
    # an integer temperature is reported as the float it is used as (1273 K: m = 1.49985)
    with pytest.raises(ValueError, match=exactly(
            "rate exponent m must lie in (0, 1]; got m = [1.49985] at temperature [1273.] K")):
        law.viscosity(1.0, 0.2, 1273)


def test_viscosity_refuses_zero_rate_exponent():
    # steel form m = m8 T_C: m = 0 at exactly 0 degC (rate-insensitive) -> refused
    law = get_grade("S355J2").law()
    with pytest.raises(ValueError, match=exactly(
            "rate exponent m must lie in (0, 1]; got m = [0.] at temperature [273.15] K")):
        law.viscosity(1.0, 0.2, C2K)


def test_viscosity_message_lists_at_most_three_bad_points():
    # m = 0.5 + 0.001 T_C = 1.5, 1.6, 1.7, 1.8 at 1000 .. 1300 degC, all > 1: three are shown
    law = HenselSpittel(1e8, m3=0.5, m8=0.001)
    T = np.array([1000.0, 1100.0, 1200.0, 1300.0]) + C2K
    with pytest.raises(ValueError, match=exactly(
            "rate exponent m must lie in (0, 1]; got m = [1.5 1.6 1.7] at temperature "
            "[1273.15 1373.15 1473.15] K")):
        law.viscosity(np.ones(4), 0.2, T)


# =================================================================================================
# 7. frozen Norton-Hoff law, range_report / in_range, describe
# =================================================================================================
def test_norton_hoff_at_keeps_the_regularisation_rate():
    law = NortonHoffStress(1e7, 0.5, eps0=1e-2)
    nh = law.norton_hoff_at(0.3, 1273.15)
    assert (nh.K, nh.m, nh.eps0) == (1e7, 0.5, 1e-2)
    # at rest: mu = 2 K sqrt3^(m-1) eps0^(m-1) = 2e7 * 3^-0.25 * 0.01^-0.5 = 2e8 / 3^0.25
    assert nh.viscosity(0.0) == pytest.approx(2e8 / 3**0.25, rel=1e-14)


def test_range_report_literal_and_closed_bounds():
    box = ValidityRange(strain=(0.1, 1.0), strain_rate=(0.5, 50.0), temperature=(1000.0, 1400.0))
    law = HenselSpittel(1e8, m3=0.1, validity=box)
    # the published ranges are closed: both ends of each are inside
    inside = {"strain": True, "strain_rate": True, "temperature": True, "inside": True}
    assert law.range_report(0.1, 0.5, 1000.0) == inside
    assert law.range_report(1.0, 50.0, 1400.0) == inside
    assert law.range_report(0.5, 60.0, 1200.0) == {
        "strain": True, "strain_rate": False, "temperature": True, "inside": False}
    rep = law.range_report(np.array([0.05, 0.1, 1.0, 1.5]), 1.0, 1200.0)
    assert set(rep) == {"strain", "strain_rate", "temperature", "inside"}
    np.testing.assert_array_equal(rep["strain"], [False, True, True, False])
    assert rep["strain_rate"] is True and rep["temperature"] is True
    np.testing.assert_array_equal(rep["inside"], [False, True, True, False])
    # unknown ranges are None, and so is "inside"
    assert HenselSpittel(1e8, m3=0.1).range_report(0.5, 1.0, 1200.0) == {
        "strain": None, "strain_rate": None, "temperature": None, "inside": None}


def test_range_report_compares_the_exact_value():
    # Al99.5: 250 .. 550 degC = 523.15 .. 823.15 K.  float32(823.15) = 823.1500244 K is above
    # the upper bound (a single-precision value is not rounded to the bound's precision)
    al = get_grade("Al99.5").law()
    assert float(np.float32(823.15)) > 823.15
    assert al.range_report(0.5, 10.0, np.float32(823.15))["temperature"] is False
    assert al.range_report(0.5, 10.0, 823.15)["temperature"] is True


def test_range_report_refuses_coefficient_functions():
    law = get_grade("Al99.5").law()
    with pytest.raises(TypeError, match=exactly(
            "range_report needs numeric values, not CoefficientFunctions")):
        law.range_report(0.5, cf(10.0), 700.0)


def test_hensel_spittel_describe_literal():
    law = HenselSpittel(2.0e8, m1=-0.0025, m2=0.2, m3=0.125, m4=0.001, m5=-0.001, m7=0.1,
                        m8=0.000244140625, m6=0.05, eps0=1e-3, name="test set",
                        validity=ValidityRange(strain=(0.05, 1.0), strain_rate=(0.1, 100.0),
                                               temperature=(1073.0, 1473.0)))
    # admissible T: m = 0.125 + 2^-12 T_C is 0 at T_C = -512 (below 0 K -> 0 K) and 1 at
    # T_C = 0.875 * 4096 = 3584 (3857.15 K); strain_min = the lower strain bound 0.05
    assert law.describe() == {
        "law": "HenselSpittel",
        "name": "test set",
        "formula": "sigma = A e^(m1 T) T^m9 eps^m2 e^(m4/eps) (1+eps)^(m5 T + m6) e^(m7 eps) "
                   "edot^(m3 + m8 T), T in degC",
        "parameters": {"A": 2.0e8, "m1": -0.0025, "m2": 0.2, "m3": 0.125, "m4": 0.001,
                       "m5": -0.001, "m6": 0.05, "m7": 0.1, "m8": 0.000244140625, "m9": 0.0},
        "parameter_units": {"A": "Pa", "m1": "1/degC", "m5": "1/degC", "m8": "1/degC",
                            "others": "1"},
        "validity": {"strain": (0.05, 1.0), "strain_rate_1_per_s": (0.1, 100.0),
                     "temperature_K": (1073.0, 1473.0), "temperature_C": (799.85, 1199.85)},
        "strain_min": 0.05,
        "eps0_1_per_s": 1e-3,
        "admissible_temperature_K": (0.0, 3857.15),
        "out_of_range_policy": "strain floored at strain_min; strain, rate and temperature "
                               "otherwise extrapolated by the formula; see in_range()",
        "units": {"sigma": "Pa", "strain_rate": "1/s", "temperature": "K"},
    }


# =================================================================================================
# 8. grades: the published coefficients, the library's messages and describe()
# =================================================================================================
# Coefficients as published (A in MPa, T in degC), read in pyroll-freiberg-flow-stress
# (pyroll/freiberg_flow_stress/materials.py: hooks s355j2, c45, c20) and, for Al99.5, in the
# public transcription of the Landolt-Boernstein datasheet cited in hotroll/model/grades.py
# ('al995_hot_deformed.py': A = 367.651, theta 250..550 degC, phi 0.03..1.50, phidot 0.01..500).
# Expected values: Spittel's formula, each factor in 30-digit decimal (Python's decimal module,
# x^y = exp(y ln x)), at points other than those of tests/model/test_flow_stress.py: the steels at
# (0.1, 0.1 1/s, 900 degC) and (1.0, 100 1/s, 1250 degC), Al99.5 at the two corners of its box.
# Factors listed: e^(m1 T), eps^m2, e^(m4/eps), (1+eps)^(m5 T), e^(m7 eps), edot^(m8 T).
PUBLISHED = {
    "S355J2": dict(A=2852.66, m1=-0.00244, m2=0.41934, m4=0.00088, m5=-0.00149, m7=0.12169,
                   m8=0.000127),
    "C45": dict(A=3268.49, m1=-0.00267855, m2=0.34446, m4=0.000551814, m5=-0.00132042,
                m7=0.0166334, m8=0.000149907),
    "C20": dict(A=3304.39, m1=-0.00281, m2=0.34766, m4=0.00002, m5=-0.00130, m7=0.07632,
                m8=0.000148),
    "Al99.5": dict(A=367.651, m1=-0.00463, m2=0.32911, m4=0.00167, m5=-0.00207, m7=0.16592,
                   m8=0.000241),
}
GRADE_POINTS = [
    # 0.111247258604, 0.380767611736, 1.00883883383, 0.880019730166, 1.01224334354, 0.768599327262
    ("S355J2", 900.0, 0.1, 0.1, 83463858.9461834040488149886389),
    # 0.0473589243911, 1, 1.00088038731, 0.274999328320, 1.12940393229, 2.07730372557
    ("S355J2", 1250.0, 1.0, 100.0, 87239858.0790064216761661428312),
    # 0.0897528946290, 0.452418129663, 1.00553339298, 0.892914434384, 1.00166472412, 0.732965781363
    ("C45", 900.0, 0.1, 0.1, 87487910.6983366405645135773476),
    # 0.0351480021563, 1, 1.00055196628, 0.318524224049, 1.01677250519, 2.37010452805
    ("C45", 1250.0, 1.0, 100.0, 88231002.7353788751678837401192),
    # 0.0797387191490, 0.449096840798, 1.00020002000, 0.894479843262, 1.00766119794, 0.735868139651
    ("C20", 900.0, 0.1, 0.1, 78500515.2316700166030993353718),
    # 0.0298222655009, 1, 1.00002000020, 0.324209888663, 1.07930789743, 2.34422881532
    ("C20", 1250.0, 1.0, 100.0, 80837380.0082134919513255303968),
    # 0.314270876796, 0.315359106268, 1.05724520992, 0.984819719785, 1.00499000883, 0.757704732866
    ("Al99.5", 250.0, 0.03, 0.01, 28889463.1523027541526113426220),
    # 0.0783554306408, 1.14275569491, 1.00111395332, 0.352326492334, 1.28258811326, 2.27902177181
    ("Al99.5", 550.0, 1.5, 500.0, 33940852.5523045195146329448734),
]


@pytest.mark.parametrize("name, T_C, strain, rate, hand", GRADE_POINTS)
def test_grade_flow_stress_against_the_published_coefficients(name, T_C, strain, rate, hand):
    law = get_grade(name).law()
    assert law.sigma(strain, rate, T_C + C2K) == pytest.approx(hand, rel=1e-12)
    # the grade's rate exponent is the published m8 T_C (m3 = 0 in all four sets)
    assert law.rate_exponent(T_C + C2K) == pytest.approx(PUBLISHED[name]["m8"] * T_C, rel=1e-12)
    # A converted from the published MPa to Pa
    assert law.A == pytest.approx(PUBLISHED[name]["A"] * 1e6, rel=1e-15)


def test_grade_validity_ranges_as_published():
    # Al99.5 (Landolt-Boernstein datasheet): phi 0.03..1.50, phidot 0.01..500 1/s, 250..550 degC
    assert get_grade("Al99.5").law().validity.as_dict() == {
        "strain": (0.03, 1.5), "strain_rate_1_per_s": (0.01, 500.0),
        "temperature_K": (250.0 + C2K, 550.0 + C2K), "temperature_C": (250.0, 550.0)}
    # the steel sets: no readable ranges -> all unknown, the strain floor is the default 0.03
    for name in ("S355J2", "C45", "C20"):
        law = get_grade(name).law()
        assert law.validity.as_dict() == {"strain": None, "strain_rate_1_per_s": None,
                                          "temperature_K": None, "temperature_C": None}
        assert law.strain_min == 0.03


def test_unknown_grade_message_lists_the_available_ones():
    with pytest.raises(KeyError) as err:
        get_grade("X5CrNi18-10")
    assert err.value.args[0] == "unknown grade 'X5CrNi18-10'; available: S355J2, C45, C20, Al99.5"


def test_grade_describe_literal():
    g = GradeData(name="Test-1", description="a made-up set", law_params={"A": 1e8, "m3": 0.1},
                  validity_celsius=((0.1, 1.0), None, (800.0, 1200.0)), density=7800.0,
                  source="a source", read_at="read here", density_source="a density source",
                  aliases=("T1",), notes="some notes")
    assert g.describe() == {
        "name": "Test-1",
        "description": "a made-up set",
        "law": "HenselSpittel",
        "law_params (A in Pa, T in degC)": {"A": 1e8, "m3": 0.1},
        "validity (strain, strain_rate 1/s, T degC)": ((0.1, 1.0), None, (800.0, 1200.0)),
        "density_kg_per_m3": 7800.0,
        "density_source": "a density source",
        "source": "a source",
        "read_at": "read here",
        "notes": "some notes",
        "elastic family": "steel",
    }


# =================================================================================================
# 9. material.py: edot_squared on numbers, an explicit K
# =================================================================================================
def test_edot_squared_of_plane_strain_states_by_hand():
    # (2.16) edot^2 = 2/3 eps:eps.  Plane-strain compression eps = diag(a, -a) (eps_zz = 0):
    # 2/3 * 2 a^2 = 4/3 a^2, edot = 2a / sqrt3 (the classical plane-strain factor 2/sqrt3)
    assert edot_squared(np.array([[1.5, 0.0], [0.0, -1.5]])) == pytest.approx(3.0, rel=1e-15)
    # simple shear, engineering rate gamma = 2g: eps = [[0, g], [g, 0]], 2/3 * 2 g^2 = gamma^2/3,
    # edot = gamma / sqrt3 (von Mises); g = 3 -> 12
    assert edot_squared(np.array([[0.0, 3.0], [3.0, 0.0]])) == pytest.approx(12.0, rel=1e-15)
    # a stack (n, 2, 2) gives n values
    stack = np.array([[[1.5, 0.0], [0.0, -1.5]], [[0.0, 3.0], [3.0, 0.0]],
                      [[0.0, 0.0], [0.0, 0.0]]])
    np.testing.assert_allclose(edot_squared(stack), [3.0, 12.0, 0.0], rtol=1e-15)


def test_edot_squared_on_a_coefficient_function(point):
    import ngsolve

    eps = ngsolve.CoefficientFunction((1.5, 0.0, 0.0, -1.5), dims=(2, 2))
    assert edot_squared(eps)(point) == pytest.approx(3.0, rel=1e-15)


def test_norton_hoff_explicit_consistency_by_hand():
    law = NortonHoff(K=1e7, m=1.0, eps0=1e-4)
    # m = 1 (Newtonian): sigma_ef = K 3 edot; K = 2e7, edot = 0.5 -> 3e7
    assert law.sigma_ef(0.5, K=2e7) == pytest.approx(3e7, rel=1e-15)
    # power density K (sqrt3 edot)^2 = 3 K edot^2 = 3 * 2e7 * 0.25 = 1.5e7
    assert law.power_density(0.5, K=2e7) == pytest.approx(1.5e7, rel=1e-14)
    # viscosity 2 K sqrt3^0 (...)^0 = 2 K = 4e7
    assert law.viscosity(0.25, K=2e7) == pytest.approx(4e7, rel=1e-15)
    # without K: the law's own (1e7)
    assert law.sigma_ef(0.5) == pytest.approx(1.5e7, rel=1e-15)


# =================================================================================================
# 10. friction_estimate: the message names the inputs and the rule
# =================================================================================================
@pytest.mark.parametrize("args", [
    (0.0, 0.5, 0.5, 1.0, 1.0, 1.0),    # volume integral
    (1.0, -0.5, 0.5, 1.0, 1.0, 1.0),   # h
    (1.0, 0.5, 0.5, 1.0, 0.0, 1.0),    # roll speed
])
def test_estimate_a_f_message(args):
    with pytest.raises(ValueError, match=exactly(
            "estimate_a_f needs positive volume integral, h and roll speed")):
        estimate_a_f(*args)


def test_numpy_scalars_are_evaluated_in_double_precision():
    """float32 numpy scalars give the same flow stress as Python floats (double precision),
    as float32 arrays do."""
    from hotroll.model.grades import get_grade

    law = get_grade("S355J2").law()
    args = (0.3, 10.0, 1373.15)
    exact = law.sigma(*args)
    f32 = law.sigma(*(np.float32(a) for a in args))
    arr = law.sigma(*(np.array([a], dtype=np.float32) for a in args))
    assert isinstance(exact, float)
    # the float32 inputs are rounded: compare with the law at the rounded inputs in float64
    rounded = law.sigma(*(float(np.float32(a)) for a in args))
    assert f32 == rounded and float(arr[0]) == rounded
    assert rounded == pytest.approx(exact, rel=1e-6)


def test_regularised_effective_stress_by_hand():
    """(2.21): sigma_ef = K 3^((m+1)/2) (eps0^2 + edot^2)^(m/2); m and K default to the law's
    and are overridden when given (the form passes its own m and the consistency field)."""
    from hotroll.model.material import NortonHoff

    law = NortonHoff(K=2.0, m=0.25, eps0=1e-3)
    # edot = 0: only the regularisation, 2 3^0.625 (1e-6)^0.125 = 2 3^0.625 10^-0.75
    assert law.sigma_ef_reg(0.0) == pytest.approx(2.0 * 3.0**0.625 * 10.0**-0.75, rel=1e-14)
    assert law.sigma_ef_reg(4.0) == pytest.approx(2.0 * 3.0**0.625 * (4.0 + 1e-6) ** 0.125,
                                                  rel=1e-14)
    assert law.sigma_ef_reg(4.0, m=0.5) == pytest.approx(2.0 * 3.0**0.75 * (4.0 + 1e-6) ** 0.25,
                                                         rel=1e-14)
    assert law.sigma_ef_reg(4.0, K=3.0) == pytest.approx(3.0 * 3.0**0.625 * (4.0 + 1e-6) ** 0.125,
                                                         rel=1e-14)
