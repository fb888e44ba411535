"""Misaka's law (model/flow_stress/misaka.py), added through the law registry.

[ref] the published formula evaluated by hand; [ref] exact reductions: rate and strain powers,
Norton-Hoff at every (strain, T), and at one temperature it is Hensel-Spittel with A = the
Misaka factor, m2 = 0.21, m3 = 0.13, so a rolling run with each gives the same pass; the case
file refuses bad input naming the field.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from casebuild import build_case

from hotroll.config.case import CaseError
from hotroll.model.flow_stress import LAWS, HenselSpittel, Misaka
from hotroll.workflows.runner import run_case

BASE = {
    "name": "misaka",
    "pass": {"roll_radius": 0.3, "entry_thickness": 0.02, "exit_thickness": 0.016,
             "roll_angular_velocity": 5.0},
    "plate": {"length": 0.2, "temperature": 1323.15},
    "material": {"law": "misaka", "carbon": 0.18},
    "friction": {"law": "coulomb", "mu": 0.3},
    "solver": {"method": "steady", "threads": 1},
    "output": {"figures": False, "vtk": False},
}


def _published(C: float, eps: float, rate: float, T: float) -> float:
    """Misaka & Yoshimoto (1967) as printed, kgf/mm^2 -> Pa, T in K, C in weight percent."""
    kgf = math.exp(0.126 - 1.75 * C + 0.594 * C * C + (2851 + 2968 * C - 1120 * C * C) / T) \
        * eps ** 0.21 * rate ** 0.13
    return kgf * 9.80665e6


@pytest.mark.parametrize("C, eps, rate, T", [(0.2, 0.3, 50.0, 1273.15), (0.05, 0.5, 30.0, 1473.15),
                                             (1.2, 0.1, 200.0, 1023.15), (0.0, 0.04, 1.0, 1173.15)])
def test_the_published_formula_by_hand(C, eps, rate, T):
    assert Misaka(C).sigma(eps, rate, T) == pytest.approx(_published(C, eps, rate, T), rel=1e-13)


def test_a_hot_steel_value():
    """0.2 % C, 1000 degC, strain 0.3, 50 1/s: about 150 MPa (15.3 kgf/mm^2), the magnitude
    of a hot-rolled carbon steel's flow stress."""
    assert Misaka(0.2).sigma(0.3, 50.0, 1273.15) == pytest.approx(149.7e6, rel=2e-3)


def test_powers_floor_and_norton_hoff_reduction():
    law = Misaka(0.45)
    T = 1200.0
    assert law.sigma(0.2, 80.0, T) / law.sigma(0.2, 8.0, T) == pytest.approx(10 ** 0.13, rel=1e-13)
    assert law.sigma(0.4, 8.0, T) / law.sigma(0.2, 8.0, T) == pytest.approx(2 ** 0.21, rel=1e-13)
    assert law.sigma(0.0, 8.0, T) == law.sigma(law.strain_min, 8.0, T)    # the strain floor
    assert law.rate_exponent(T) == 0.13 and law.depends_on_strain
    K = law.consistency(0.2, T)
    for rate in (1e-2, 1.0, 300.0):   # Norton-Hoff at (strain, T): sigma = K 3^((m+1)/2) rate^m
        assert law.sigma(0.2, rate, T) == pytest.approx(K * 3 ** (1.13 / 2) * rate ** 0.13,
                                                        rel=1e-13)


def test_coefficient_functions_give_the_numbers():
    """The same law on NGSolve CoefficientFunctions (what the weak form evaluates)."""
    from ngsolve import CF, Mesh, unit_square

    mesh = Mesh(unit_square.GenerateMesh(maxh=0.5))
    law = Misaka(0.3)
    cf = law.sigma(CF(0.25), CF(12.0), CF(1250.0))
    assert cf(mesh(0.5, 0.5)) == pytest.approx(law.sigma(0.25, 12.0, 1250.0), rel=1e-12)


def test_registered_and_refused_outside_its_carbon_range():
    assert LAWS["misaka"].build({"carbon": 0.1}, 1e-4).carbon == 0.1
    with pytest.raises(ValueError, match="carbon"):
        Misaka(1.5)


@pytest.mark.parametrize("material, key", [
    ({"law": "misaka"}, "material.carbon: missing required key"),
    ({"law": "misaka", "carbon": 1.3}, "material.carbon"),
    ({"law": "misaka", "carbon": 0.2, "K": 1e8}, "material.K: only for law = \"norton-hoff\""),
    ({"law": "norton-hoff", "K": 1e8, "m": 0.2, "carbon": 0.2}, "material.carbon: only for law"),
])
def test_bad_input_names_the_field(material, key):
    with pytest.raises(CaseError) as e:
        build_case(BASE, "material", material)
    assert key in str(e.value)


def test_a_misaka_pass_is_the_equivalent_hensel_spittel_pass(tmp_path):
    """At one temperature Misaka's law is Hensel-Spittel with A = 9.80665e6 exp(0.126 - 1.75 C
    + 0.594 C^2 + theta(C)/T), m2 = 0.21, m3 = 0.13 (both floor the strain at 0.03): the two
    rolling runs give the same force, torque, slip and exit strain (1e-9), and the force lies
    between the law frozen at the strain floor and at the exit strain."""
    C, T = 0.18, BASE["plate"]["temperature"]
    misaka = run_case(build_case(BASE, "material", None), tmp_path / "misaka")
    A = 9.80665e6 * math.exp(0.126 - 1.75 * C + 0.594 * C * C
                             + (2851 + 2968 * C - 1120 * C * C) / T)
    hs = {"law": "hensel-spittel", "A": A, "m2": 0.21, "m3": 0.13}
    assert HenselSpittel(A, m2=0.21, m3=0.13).sigma(0.2, 7.0, T) == pytest.approx(
        Misaka(C).sigma(0.2, 7.0, T), rel=1e-13)
    same = run_case(build_case(BASE, "material", hs), tmp_path / "hs")
    assert misaka["exit_code"] == 0 and same["exit_code"] == 0
    for key in ("roll_force", "roll_torque", "forward_slip", "exit_strain", "plastic_power"):
        assert misaka[key] == pytest.approx(same[key], rel=1e-9), key
    floor = run_case(build_case(BASE, "material", {"law": "hensel-spittel", "A": A * 0.03 ** 0.21,
                                                   "m3": 0.13}), tmp_path / "floor")
    top = run_case(build_case(BASE, "material", {
        "law": "hensel-spittel", "A": A * misaka["exit_strain"] ** 0.21, "m3": 0.13}),
        tmp_path / "top")
    assert floor["roll_force"] < misaka["roll_force"] < top["roll_force"]
    assert np.isfinite(misaka["exit_strain"])


def test_the_registry_refuses_a_second_name_or_a_parameter_that_means_two_things():
    """A name once; a parameter name shared by two laws must have the same unit and limits."""
    from dataclasses import replace

    from hotroll.model.flow_stress.registry import register
    from hotroll.model.parameters import Parameter

    spec = LAWS["misaka"]
    with pytest.raises(ValueError, match="flow-stress law 'misaka' registered twice"):
        register(spec)
    carbon = next(p for p in spec.parameters if p.name == "carbon")
    clash = replace(spec, name="misaka2", parameters=(replace(carbon, unit="ppm"),))
    with pytest.raises(ValueError, match="parameter 'carbon' of 'misaka2' differs from 'misaka'"):
        register(clash)
    same = replace(spec, name="misaka3", parameters=(carbon, Parameter("x3", "", "", "")))
    try:
        assert register(same) is same and LAWS["misaka3"] is same   # shared and equal: fine
    finally:
        LAWS.pop("misaka3", None)
    assert "misaka2" not in LAWS


def test_the_law_describes_itself_and_refuses_bad_numbers():
    """describe() as the compare files write it, the repr, and each refused argument with its
    rule (carbon's range at both ends, eps0 and strain_min > 0)."""
    law = Misaka(0.18, strain_min=0.02)
    d = law.describe()
    assert d["law"] == "Misaka" and d["name"] == "Misaka"
    assert d["parameters"] == {"carbon": 0.18} and d["parameter_units"] == {"carbon": "wt %"}
    assert d["strain_min"] == 0.02 and d["eps0_1_per_s"] == law.eps0
    assert d["units"] == {"sigma": "Pa", "strain_rate": "1/s", "temperature": "K"}
    assert d["formula"].startswith("sigma = 9.80665e6 exp(0.126 - 1.75 C")
    assert d["validity"] == law.validity.as_dict()
    assert repr(law) == "Misaka(carbon=0.18, strain_min=0.02)"
    assert Misaka(0.1, name="S235").describe()["name"] == "S235"
    assert Misaka(0.0).carbon == 0.0 and Misaka(1.2).carbon == 1.2         # the range's ends
    for bad, msg in (({"carbon": -0.01}, r"carbon must be in \[0, 1.2\] weight percent, "
                                         r"got -0.01"),
                     ({"carbon": 1.21}, r"carbon must be in \[0, 1.2\] weight percent"),
                     ({"carbon": 0.2, "eps0": 0.0}, r"eps0 must be > 0 \(1/s\), got 0.0"),
                     ({"carbon": 0.2, "strain_min": 0.0}, r"strain_min must be > 0, got 0.0"),
                     ({"carbon": float("nan")}, r"^carbon must be finite, got nan$"),
                     ({"carbon": 0.2, "eps0": float("inf")}, r"^eps0 must be finite, got inf$"),
                     ({"carbon": 0.2, "strain_min": "x"}, r"^strain_min must be a real number")):
        c = bad.pop("carbon")
        with pytest.raises(ValueError, match=msg):
            Misaka(c, **bad)


def test_no_rate_no_stress_and_the_rate_exponent_everywhere():
    """edot = 0 gives sigma = 0 (no warning); the rate exponent is 0.13 at any temperature."""
    import warnings

    law = Misaka(0.2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert float(law.sigma(0.2, 0.0, 1273.15)) == 0.0
    assert law.rate_exponent(900.0) == law.rate_exponent(1400.0) == law.rate_exponent() == 0.13
