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
    assert case.spread.strain == "transported"
    assert load_case(BASE, {**STEADY, "spread.strain": "frozen"}).spread.strain == "frozen"
    # the entry temperature across the width, a temperature with its unit
    grade = {"material.law": "hensel-spittel", "material.grade": "C45", "material.m": None,
             "material.K": None}
    cold = load_case(BASE, {**STEADY, **grade, "spread.temperature_profile": [
        [0.0, "1100 degC"], [1.0, "1000 degC"]]})
    assert cold.spread.temperature_profile == [(0.0, 1373.15), (1.0, 1273.15)]
    # ... and over the cross-section, its temperatures with their units too
    section = load_case(BASE, {**STEADY, **grade, "spread.temperature_section": {
        "eta": [0.0, 1.0], "zeta": [0.0, 1.0],
        "values": [["1100 degC", "1050 degC"], ["1100 degC", 1300.0]]}})
    assert section.spread.temperature_section.values == [[1373.15, 1323.15], [1373.15, 1300.0]]
    # flat up to an edge zone's cut: taken
    zoned = load_case(BASE, {**STEADY, **grade, "spread.edge_zone": 0.004,
                             "spread.temperature_profile": [[0.0, 1373.15], [0.2, 1373.15],
                                                            [1.0, 1273.15]]})
    assert zoned.spread.temperature_profile[1] == (0.2, 1373.15)
    assert case.spread.layers(0.005, 1e-3) == (1e-3, 1.2, 4e-3)
    assert case.spread.layers(0.0004, 1e-3) == pytest.approx((4e-4, 1.2, 1.6e-3))
    given = load_case(BASE, {**STEADY, "spread.edge_layer": "2 mm", "spread.largest_layer": 0.003})
    assert given.spread.layers(0.005, 1e-3) == (2e-3, 1.2, 3e-3)
    assert load_case(BASE, {k: v for k, v in STEADY.items() if k != "spread.growth"}).spread is None
    # a wide plate in the edge-zone model: the 3D strip 2 h0 wide at each edge
    wide = load_case(BASE, {**STEADY, "pass.width": 0.5, "spread.edge_zone": 0.02})
    assert wide.spread.modelled(0.25) == 0.02 and wide.spread.layers(0.25, 1e-3)[0] == 1e-3


def test_a_transient_case_is_refused_once_for_its_method():
    """[plumb] "auto" contact under the transient solver is the penalty: the method's refusal
    says it, the contact's does not repeat it."""
    with pytest.raises(CaseError) as e:
        load_case(BASE, {**STEADY, "solver.method": "transient"})
    lines = [p for p in str(e.value).splitlines() if "[spread]" in p]
    assert len(lines) == 1 and lines[0].strip().startswith("solver.method:")


@pytest.mark.parametrize("extra, message", [
    ({"solver.method": "transient"}, 'solver.method: \\[spread\\] needs "steady"'),
    ({"pass.width": None}, "pass.width: \\[spread\\] needs the strip's width"),
    ({"pass.width": 0.002}, "pass.width: .* >= 0.25 .* = 0.2$"),
    ({"spread.edge_layer": 0.006}, "spread.edge_layer: must be <= the modelled width .* = "
                                   "0.005 m"),
    ({"spread.edge_zone": 0.004, "spread.edge_layer": 0.0045},
     "spread.edge_layer: must be <= the modelled width .* = 0.004 m"),
    ({"spread.edge_zone": 0.006}, "spread.edge_zone: must be <= pass.width / 2 = 0.005 m"),
    ({"pass.width": 0.5, "spread.edge_zone": 0.09},
     "spread.edge_zone: at most 8 x entry thickness = 0.08 m"),
    ({"pass.width": 0.5}, "pass.width: .* up to width / entry thickness = 16.*spread.edge_zone"),
    ({"spread.edge_layer": 0.002, "spread.largest_layer": 0.001},
     "spread.largest_layer: must be >= spread.edge_layer"),
    ({"spread.growth": 0.9}, "spread.growth: must be in \\[1, 2\\]"),
    ({"spread.strain": "carried"}, 'spread.strain: .*"transported" or "frozen"'),
    ({"spread.temperature_profile": [[0.0, 1300.0], [1.0, 1200.0]]},
     "spread.temperature_profile: its mid-width value .* plate.temperature = 1373.15 K, got "
     "1300 K"),
    ({"spread.temperature_profile": [[0.0, 1373.15], [1.0, 1273.15]]},
     'spread.temperature_profile: the flow stress law "norton-hoff" does not depend'),
    ({"spread.temperature_profile": [[0.0, 1373.15], [0.5, 1273.15]]},
     "spread.temperature_profile: .*1"),
    ({"spread.edge_zone": 0.004,
      "spread.temperature_profile": [[0.0, 1373.15], [0.1, 1363.15], [1.0, 1273.15]]},
     "spread.temperature_profile: must be the plate's temperature up to the edge zone's cut "
     "\\(zeta = 1 - spread.edge_zone / \\(pass.width / 2\\) = 0.2\\)"),
    ({"spread.temperature_section": {"eta": [0.0, 1.0], "zeta": [0.0, 1.0],
                                     "values": [[1373.15, 1300.0], [1363.15, 1290.0]]},
      **{"material.law": "hensel-spittel", "material.grade": "C45", "material.m": None,
         "material.K": None}},
     "spread.temperature_section: its mid-width column .* at eta = 1: 1373.15 K, got "
     "1363.15 K"),
    ({"spread.temperature_section": {"eta": [0.0, 1.0], "zeta": [0.0, 1.0],
                                     "values": [[1373.15, 1300.0], [1373.15, 1290.0]]},
      "spread.temperature_profile": [[0.0, 1373.15], [1.0, 1273.15]]},
     "spread.temperature_section: not with spread.temperature_profile"),
    ({"spread.temperature_section": {"eta": [0.0, 1.0], "zeta": [0.0, 1.0],
                                     "values": [[1373.15, 1300.0], [1373.15]]}},
     "spread.temperature_section.values: must be > 0, one row per eta of one value per "
     "zeta \\[K\\], got"),
    ({"spread.temperature_section": {"eta": [0.0, 1.0], "zeta": [0.0, 1.0],
                                     "values": [[1373.15, 1350.0], [1300.0, 1250.0]]},
      "plate.temperature_profile": [[0.0, 1373.15], [0.5, 1373.15], [1.0, 1300.0]],
      **{"material.law": "hensel-spittel", "material.grade": "C45", "material.m": None,
         "material.K": None, "thermal.htc_contact": 2e4, "thermal.roll_temperature": 400.0,
         "thermal.htc_air": 20.0, "thermal.emissivity": 0.8}},
     "spread.temperature_section: its mid-width column .* at eta = 0.5: 1373.15 K, got "
     "1336.58 K"),
    ({"spread.temperature_section": {"eta": [0.0, 1.0], "zeta": [0.0, 0.8],
                                     "values": [[1373.15, 1300.0], [1373.15, 1290.0]]}},
     "spread.temperature_section.zeta: must be increasing strictly from 0 to 1, got "
     "\\[0.0, 0.8\\]"),
    ({"spread.edge_zone": 0.004,
      "spread.temperature_section": {"eta": [0.0, 1.0], "zeta": [0.0, 0.1, 1.0],
                                     "values": [[1373.15, 1370.0, 1300.0],
                                                [1373.15, 1370.0, 1290.0]]}},
     "spread.temperature_section: must be the plate's temperature up to the edge zone's cut"),
    ({"pass.speed_ratio": 1.1}, "pass: \\[spread\\] needs a symmetric pass"),
    ({"roll.model": "hitchcock"}, 'roll.model: \\[spread\\] needs "rigid"'),
    ({"pass.roll_gap": 0.0079, "pass.mill_modulus": 5e9, "pass.exit_thickness": None},
     "pass.roll_gap: not with \\[spread\\]"),
    ({"plate.free_surface": "constrained"}, 'plate.free_surface: \\[spread\\] needs "traced"'),
    ({"contact.method": "penalty"}, "contact.method: \\[spread\\] needs the exact contact"),
])
def test_what_the_3d_pass_cannot_run_is_refused_by_key(extra, message):
    """[plumb] each refusal names its key and what is allowed."""
    with pytest.raises(CaseError) as e:
        load_case(BASE, {**STEADY, **extra})
    assert any(re.search(message, line) for line in str(e.value).splitlines()), \
        str(e.value)


def test_a_3d_pass_without_the_contact_start_refined_is_warned():
    """[plumb] a [spread] case on a mesh not refined at the contact's start (set to 1) is
    warned, naming the key and the fix (its 3D mass balance carries the 2D top's leak there:
    5-10e-4, docs/theory.md 4e); at the default (16) it is not, nor is a plane-strain case
    at 1."""
    def lines(over):
        return [w for w in load_case(BASE, over).warnings()
                if w.startswith("mesh.corner_refinement")]
    plane = {k: v for k, v in STEADY.items() if not k.startswith(("spread.", "pass.width"))}
    one = {"mesh.corner_refinement": 1}
    assert len(lines({**STEADY, **one})) == 1 and "16" in lines({**STEADY, **one})[0]
    assert lines(STEADY) == []
    assert lines({**plane, **one}) == []


def test_the_3d_linear_solver_is_read_and_checked():
    """[plumb] ``spread.linear_solver``: UMFPACK by default, "amg+gmres" taken, anything else
    refused naming the key (tests/workflows/test_spread_run.py: it reaches the 3D pass)."""
    assert load_case(BASE, STEADY).spread.linear_solver == "umfpack"
    case = load_case(BASE, {**STEADY, "spread.linear_solver": "amg+gmres"})
    assert case.spread.linear_solver == "amg+gmres"
    with pytest.raises(CaseError, match="spread.linear_solver"):
        load_case(BASE, {**STEADY, "spread.linear_solver": "mumps"})
