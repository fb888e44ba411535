"""The mill's stretch and the gap to set (results/engineering.py ``mill_setup``, the gaugemeter
equation h1 = S + F/M) and its input (``[pass] mill_modulus``)."""
from __future__ import annotations

import copy

import pytest

from hotroll.config.case import CaseError, case_from_dict
from hotroll.results.engineering import mill_setup


def test_the_gap_plus_the_stretch_is_the_exit_thickness():
    """15 MN over the width on a 5 MN/mm stand: 3 mm of stretch, so a 4 mm strip needs the
    rolls set 1 mm apart at no load; a stiffer stand needs a gap nearer the exit thickness."""
    s = {"roll_force_total": 15e6}
    out = mill_setup(s, 0.004, 5e9)
    assert out["mill_stretch"] == pytest.approx(0.003, rel=1e-15)
    assert out["gap_setting"] + 15e6 / 5e9 == pytest.approx(0.004, rel=1e-15)
    stiff = mill_setup(s, 0.004, 50e9)
    assert out["gap_setting"] < stiff["gap_setting"] < 0.004
    # a soft stand under a big force: the rolls must be pressed together (a negative gap)
    assert mill_setup({"roll_force_total": 30e6}, 0.004, 4e9)["gap_setting"] < 0.0
    assert mill_setup(s, 0.004, None) == {}


def test_a_mill_modulus_needs_the_width(tmp_path):
    import tomllib

    from hotroll.examples import example_path

    with open(example_path("hot_strip_finishing"), "rb") as fh:
        d = tomllib.load(fh)
    d = copy.deepcopy(d)
    d["pass"].pop("width", None)
    d["pass"]["mill_modulus"] = 5e9
    with pytest.raises(CaseError, match="pass.mill_modulus: needs pass.width"):
        case_from_dict(d)
    d["pass"]["width"] = 1.2
    assert case_from_dict(d).pass_.mill_modulus == 5e9
    d["pass"]["mill_modulus"] = -1.0
    with pytest.raises(CaseError, match="pass.mill_modulus"):
        case_from_dict(d)
