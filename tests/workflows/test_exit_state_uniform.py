"""The state a pass hands on (workflows/schedule.py's ``exit_state``) when its exit profile has
a temperature but no strain (a thermal pass whose law ignores the strain): the homogeneous
exit strain, uniform through the thickness, the temperature profile as written, and the
exit thickness (the case's, measured the same); and a pass without streamline histories is named by its number
(workflows/microstructure.py's ``deformed``: pass k + 1 for the k-th, counted from 0)."""
from __future__ import annotations

from types import SimpleNamespace

import pytest

from hotroll.workflows.microstructure import MicrostructureError, deformed
from hotroll.workflows.schedule import exit_state


def test_a_pass_without_a_strain_profile_hands_on_its_homogeneous_strain():
    summary = {"exit_profile": {"eta": [0.0, 0.5, 1.0], "temperature": [1300.0, 1290.0, 1250.0],
                                "strain": None},
               "homogeneous_exit_strain": 0.3, "exit_thickness": 0.08}
    case = SimpleNamespace(thermal=object(), pass_=SimpleNamespace(exit_thickness=0.08, width=None))
    state = exit_state(None, case, summary)
    assert state.thickness == 0.08
    assert [state.strain(e) for e in (0.0, 0.7, 1.0)] == [0.3, 0.3, 0.3]
    assert state.temperature(1.0) == 1250.0 and state.temperature(0.0) == 1300.0


def test_a_pass_without_streamline_histories_is_named_by_its_number():
    with pytest.raises(MicrostructureError, match=r"^pass 3: its exit profile has no streamline"):
        deformed(None, None, None, {"exit_profile": {"eta": [0.0, 1.0]}}, 2)
