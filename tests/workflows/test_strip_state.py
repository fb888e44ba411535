"""workflows/strip_state.py by hand, no FE solve: the state's dict, and a pass's exit strain
profile handed on (negative strains clipped to 0; an asymmetric pass's folded about the
middle: the mean of the two halves)."""
from __future__ import annotations

from types import SimpleNamespace

import pytest

from hotroll.model.profile import ThicknessProfile
from hotroll.workflows.strip_state import StripState, exit_state

CASE = SimpleNamespace(thermal=object(), pass_=SimpleNamespace(exit_thickness=0.05, width=None))


def test_a_state_is_its_dict():
    s = StripState(0.02, ThicknessProfile.uniform(1000.0), ThicknessProfile((0.0, 1.0), (0.1, 0.3)),
                   ThicknessProfile.uniform(5e-5))
    assert s.to_dict() == {"thickness": 0.02, "temperature_profile": [[0.0, 1000.0], [1.0, 1000.0]],
                           "strain_profile": [[0.0, 0.1], [1.0, 0.3]],
                           "grain_size_profile": [[0.0, 5e-5], [1.0, 5e-5]]}


def test_a_strain_profile_is_handed_on_clipped_at_zero():
    summary = {"exit_profile": {"eta": [0.0, 0.5, 1.0], "temperature": [1200.0, 1190.0, 1150.0],
                                "strain": [-0.01, 0.2, 0.4]}, "exit_thickness": 0.05}
    s = exit_state(None, CASE, summary)
    assert s.strain.values == (0.0, 0.2, 0.4) and s.temperature.values == (1200.0, 1190.0, 1150.0)


def test_an_asymmetric_exit_profile_is_folded_about_the_middle():
    """eta -1, 0, 1: strain 0.5, 0.1, 0.3 -> (0.1, (0.5 + 0.3)/2); temperature 1000, 1100,
    1200 -> 1100 at both ends."""
    summary = {"exit_profile": {"eta": [-1.0, 0.0, 1.0], "temperature": [1000.0, 1100.0, 1200.0],
                                "strain": [0.5, 0.1, 0.3]}, "exit_thickness": 0.05}
    s = exit_state(None, CASE, summary)
    assert s.strain.eta == (0.0, 1.0) and s.strain.values == pytest.approx((0.1, 0.4), rel=1e-15)
    assert s.temperature.values == (1100.0, 1100.0) and s.thickness == 0.05
