"""Interpass cooling's default time steps and its profile check (hotroll/model/interpass.py):
the docstring's rule "at least 100, and dt at most a tenth of H^2 / alpha" counted by hand,
and a profile whose y repeats a value refused (y must increase)."""
from __future__ import annotations

import pytest

from hotroll.model.interpass import cool
from hotroll.model.thermal_properties import ThermalInputError, ThermalProperties

STEEL = ThermalProperties(7600.0, 650.0, 28.0)
ALPHA = 28.0 / (7600.0 * 650.0)


@pytest.mark.parametrize("H, duration", [(0.002, 100.0), (0.1, 10.0)])
def test_the_default_steps_keep_dt_below_a_tenth_of_the_diffusion_time(H, duration):
    """2 mm for 100 s: H^2/alpha = 0.706 s, so ceil(100 / 0.0706) = 1418 steps; 100 mm for
    10 s: 100 steps (the floor). ``record`` keeps a time per step."""
    r = cool([0.0], [1273.15], H, duration, STEEL, 20.0, 0.8, 300.0, record=True)
    steps = {0.002: 1418, 0.1: 100}[H]                       # by hand (docstring)
    assert len(r.times) - 1 == steps
    assert r.times[1] - r.times[0] <= 0.1 * H * H / ALPHA or steps == 100


def test_a_profile_with_a_repeated_y_is_refused():
    with pytest.raises(ThermalInputError, match="y increasing"):
        cool([0.0, 0.5, 0.5, 1.0], [1300.0, 1290.0, 1280.0, 1270.0], 0.01, 1.0, STEEL,
             20.0, 0.8, 300.0)
