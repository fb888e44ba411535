"""Heat-transfer laws as plug-ins (hotroll/model/heat_transfer): the laws on numbers worked by
hand, their derivative, the registry and the [thermal] section built from it."""
from __future__ import annotations

import numpy as np
import pytest

from hotroll.config.case import CaseError
from hotroll.config.thermal import ThermalConfig
from hotroll.model.heat_transfer import (
    HEAT_TRANSFER_LAWS,
    SIGMA_SB,
    ConstantConductance,
    ConvectionRadiation,
    laws_of,
)
from hotroll.model.interpass import cool
from hotroll.model.thermal_properties import ThermalBoundary, ThermalInputError, ThermalProperties

pytestmark = pytest.mark.mutation


def test_laws_on_numbers_by_hand():
    """q = 2e4 (1300 - 350) = 1.9e7 W/m^2; q = 20 (1300 - 300) + 0.8 sigma (1300^4 - 300^4)
    = 2e4 + 0.8 x 5.670374419e-8 x (2.8561e12 - 8.1e9) = 2e4 + 1.29194e5 W/m^2."""
    assert ConstantConductance(2e4).flux(1300.0, 350.0) == pytest.approx(1.9e7, rel=1e-15)
    rad = 0.8 * 5.670374419e-8 * (1300.0 ** 4 - 300.0 ** 4)
    assert rad == pytest.approx(1.29194e5, rel=1e-5)
    assert ConvectionRadiation(20.0, 0.8).flux(1300.0, 300.0) == pytest.approx(2e4 + rad, rel=1e-14)
    assert SIGMA_SB == 5.670374419e-8       # CODATA 2018 (exact in the 2019 SI)


@pytest.mark.parametrize("law", [ConstantConductance(3e3), ConvectionRadiation(15.0, 0.7)])
def test_derivative_is_the_slope_of_the_flux(law):
    """dflux against a central difference (the 1D cooling's Newton uses it)."""
    T = np.array([400.0, 900.0, 1400.0])
    d = 1e-3
    fd = (law.flux(T + d, 300.0) - law.flux(T - d, 300.0)) / (2 * d)
    assert np.allclose(law.dflux(T, 300.0), fd, rtol=1e-8)


def test_registry_knows_each_law_and_where_it_acts():
    assert list(laws_of("contact")) == ["constant"]
    assert list(laws_of("surface")) == ["convection_radiation"]
    for spec in HEAT_TRANSFER_LAWS.values():
        law = spec.build({p.name: 0.5 for p in spec.parameters})
        assert law.kind == spec.kind and law.name == spec.name and spec.source


def test_thermal_section_takes_the_chosen_laws_parameters():
    t = ThermalConfig(htc_contact=2e4, roll_temperature=350.0, htc_air=20.0, emissivity=0.8)
    bc = t.boundary(1300.0)
    assert bc.contact == ConstantConductance(2e4)
    assert bc.surface == ConvectionRadiation(20.0, 0.8)
    assert t.law("surface", htc_air=5.0) == ConvectionRadiation(5.0, 0.8)   # a transport's


def test_missing_parameter_is_named():
    with pytest.raises((CaseError, ValueError), match=r"thermal.htc_contact: required for "
                                                       r"contact_law = \"constant\""):
        ThermalConfig(roll_temperature=350.0, htc_air=20.0, emissivity=0.8)
    with pytest.raises((CaseError, ValueError), match="contact_law"):
        ThermalConfig(contact_law="glue", htc_contact=1.0, roll_temperature=350.0, htc_air=20.0,
                      emissivity=0.8)


def test_a_law_of_the_wrong_kind_is_refused():
    with pytest.raises(ThermalInputError, match="thermal.contact_law"):
        ThermalBoundary(1300.0, 350.0, 300.0, 1e4, 20.0, 0.8, contact=ConvectionRadiation(1, 0))


def test_interpass_cooling_takes_the_surface_law():
    """A law object gives the same cooling as its parameters (plumbing), and a hotter law cools
    more."""
    props = ThermalProperties(7800.0, 650.0, 30.0)
    args = ([0.0], [1300.0], 0.01, 5.0, props)
    by_numbers = cool(*args, 20.0, 0.8, 300.0)
    by_law = cool(*args, None, None, 300.0, surface=ConvectionRadiation(20.0, 0.8))
    assert by_law.mean == by_numbers.mean
    stronger = cool(*args, None, None, 300.0, surface=ConvectionRadiation(200.0, 0.8))
    assert stronger.mean < by_law.mean - 1.0


def test_registering_a_name_twice_or_an_unknown_kind_is_refused():
    from hotroll.model.heat_transfer import HeatTransferSpec, register

    spec = HEAT_TRANSFER_LAWS["constant"]
    with pytest.raises(ValueError, match="heat-transfer law 'constant' registered twice"):
        register(spec)
    odd = HeatTransferSpec("odd", "roll_core", "", "", (), lambda v: None)
    with pytest.raises(ValueError, match=r"'odd': kind must be one of \('contact', 'surface'\)"):
        register(odd)
    assert "odd" not in HEAT_TRANSFER_LAWS and HEAT_TRANSFER_LAWS["constant"] is spec
