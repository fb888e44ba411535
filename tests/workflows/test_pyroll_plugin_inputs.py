"""The PyRolL plugin's inputs and hand-offs without an FE solve: the roll's own contact heat
transfer coefficient and temperature reach the pass's case (pyroll_case.pass_case), a pass's
out profile has no recrystallisation yet (it follows in the transport:
pyroll_microstructure.pass_values, the pass state and exit profile faked), and a transport
whose sequence is gone answers with its last softening (pyroll_microstructure.softened)."""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

pr = pytest.importorskip("pyroll.core", reason="the [pyroll] extra (scripts/setup.sh installs it)")

import hotroll.pyroll as hp  # noqa: E402
import hotroll.pyroll_microstructure as hm  # noqa: E402

WIDTH, R = 1.2, 0.3


def test_the_rolls_heat_transfer_coefficient_and_temperature_reach_the_case():
    rp = pr.RollPass(label="R1", gap=0.08, rotation=False, coulomb_friction_coefficient=0.25,
                     roll=pr.Roll(groove=pr.FlatGroove(usable_width=WIDTH), nominal_radius=R,
                                  rotational_frequency=0.3 / (2.0 * math.pi * R),
                                  contact_heat_transfer_coefficient=5e4, temperature=400.0))
    rp.in_profile = pr.Profile.box(height=0.1, width=WIDTH, temperature=1373.15, strain=0.0,
                                   material="S355J2", density=7600.0,
                                   specific_heat_capacity=650.0, thermal_conductivity=30.0)
    case, _ = hp.pass_case(rp)
    assert (case.thermal.htc_contact, case.thermal.roll_temperature) == (5e4, 400.0)


def test_a_passs_out_profile_has_no_recrystallisation_yet(monkeypatch):
    eta = np.array([0.0, 0.5, 1.0])
    ps = SimpleNamespace(eta=eta, grain=np.full(3, 1e-4), strain=np.array([0.3, 0.35, 0.5]))
    monkeypatch.setattr(hm, "deformed", lambda rp: ps)
    monkeypatch.setattr(hm._P, "solve", lambda rp: {"exit_profile": {
        "eta": eta.tolist(), "strain": [0.3, 0.35, 0.5]}})
    values = hm.pass_values(object())
    assert values["recrystallized_fraction"] == 0.0
    assert values["hotroll_recrystallized_fraction_profile"] == [0.0, 0.0, 0.0]
    assert values["grain_size"] == pytest.approx(1e-4, rel=1e-12)


def test_a_transport_without_its_sequence_answers_with_its_last_softening(monkeypatch):
    monkeypatch.setattr(hp.Config, "MICROSTRUCTURE", "hodgson_gibbs_cmn")
    tr = pr.Transport(label="T1", duration=1.0)
    last = ("the pass state", "its softening")
    tr.__dict__["_hotroll_last"] = last
    assert tr.parent is None and hm.softened(tr) is last
