"""The ``[spread]`` section (config/spread.py, issue 53): what the 3D pass needs is checked with
the case, each refusal naming its key and the allowed range, before any computation."""
from __future__ import annotations

import re

import pytest

from hotroll.config.base import CaseError
from hotroll.config.case import load_case

BASE = "hotroll/examples/cases/example1.toml"
#: a steady pass 10 -> 8 mm on a 250 mm roll (Case R) with a 10 mm wide bar
STEADY = {"pass.roll_radius": 0.25, "pass.entry_thickness": 0.01, "pass.exit_thickness": 0.008,
          "pass.roll_angular_velocity": 4.0, "mesh.h_contact": 1e-3, "solver.method": "steady",
          "plate.length": 0.2, "pass.width": 0.01, "spread.growth": 1.2}


def test_a_spread_case_loads_and_resolves_its_layers():
    """[plumb] "auto" layers: the edge layer the contact mesh size (at most the half width),
    the largest 4 of them."""
    case = load_case(BASE, STEADY)
    assert case.spread is not None and case.spread.max_rounds == 30
    assert case.spread.layers(0.005, 1e-3) == (1e-3, 1.2, 4e-3)
    assert case.spread.layers(0.0004, 1e-3) == pytest.approx((4e-4, 1.2, 1.6e-3))
    given = load_case(BASE, {**STEADY, "spread.edge_layer": "2 mm", "spread.largest_layer": 0.003})
    assert given.spread.layers(0.005, 1e-3) == (2e-3, 1.2, 3e-3)
    assert load_case(BASE, {k: v for k, v in STEADY.items() if k != "spread.growth"}).spread is None


@pytest.mark.parametrize("extra, message", [
    ({"solver.method": "transient"}, 'solver.method: \\[spread\\] needs "steady"'),
    ({"pass.width": None}, "pass.width: \\[spread\\] needs the strip's width"),
    ({"pass.width": 0.002}, "pass.width: .* in \\[0.25, 16\\].* = 0.2$"),
    ({"pass.width": 0.17}, "pass.width: .* in \\[0.25, 16\\].* = 17$"),
    ({"spread.edge_layer": 0.006}, "spread.edge_layer: must be <= pass.width / 2 = 0.005 m"),
    ({"spread.edge_layer": 0.002, "spread.largest_layer": 0.001},
     "spread.largest_layer: must be >= spread.edge_layer"),
    ({"spread.growth": 0.9}, "spread.growth: must be in \\[1, 2\\]"),
    ({"pass.speed_ratio": 1.1}, "pass: \\[spread\\] needs a symmetric pass"),
    ({"roll.model": "hitchcock"}, 'roll.model: \\[spread\\] needs "rigid"'),
    ({"plate.free_surface": "constrained"}, 'plate.free_surface: \\[spread\\] needs "traced"'),
    ({"contact.method": "penalty"}, "contact.method: \\[spread\\] needs the exact contact"),
])
def test_what_the_3d_pass_cannot_run_is_refused_by_key(extra, message):
    """[plumb] each refusal names its key and what is allowed."""
    with pytest.raises(CaseError) as e:
        load_case(BASE, {**STEADY, **extra})
    assert any(re.search(message, line) for line in str(e.value).splitlines()), \
        str(e.value)
