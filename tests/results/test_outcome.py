"""The reason a run's figures break conservation (results/outcome.py ``conservation_problem``),
as the user reads it in summary.json's ``failure``: the full text written out here."""
from __future__ import annotations

from hotroll.results.outcome import conservation_problem


def test_conservation_reason_names_the_penalty_share_and_roll_speed():
    """Penalty contact: the checks over their tolerance, then the penalty's share and the roll
    speed the reader needs to judge the leak; exact contact: the traced free tops instead."""
    s = {"mass_flux_error": 0.03, "penalty_share": 0.0345, "roll_surface_speed": 0.05}
    assert conservation_problem(s) == (
        "not conserved: mass_flux_error = 0.03 above 0.02, penalty_share = 0.0345 above 0.02; "
        "the contact penalty lets the strip through the roll (penalty share 0.0345, roll "
        "surface speed 0.05 m/s): most at low roll speeds and with sticking friction; exact "
        "contact (contact.method = \"multiplier\") or a finer mesh.h_contact")
    exact = {"mass_flux_error": 0.03, "contact_method": "multiplier"}
    assert conservation_problem(exact) == (
        "not conserved: mass_flux_error = 0.03 above 0.02; exact contact holds the roll; the "
        "flux crosses the traced free tops (their discretisation): a finer mesh.h_contact "
        "tightens it")
