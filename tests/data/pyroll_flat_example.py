"""PyRolL's documented flat example (the Freiberg notebook ``flat-rolling/pyroll-flat-rolling.ipynb``
of Institute-of-Metal-Forming/notebooks-ilsenburg, docs/notes/issue51-research.md 3), its first
two passes and the transport between them, for tests/workflows/test_pyroll_out_profile.py. Run
as ``python pyroll_flat_example.py [--plugin] [--thermal]``: prints one JSON line with every
unit's and the sequence's out profile (the values set on it, and its height and width); with
``--plugin`` ``import hotroll.pyroll`` first and the passes' FE summaries; with ``--thermal``
``import pyroll.integral_thermal`` (PyRolL's lumped pass and transport heat) and the
temperature a lone Transport of PyRolL's gives from the transport's in state.

The notebook rolls with ``pyroll.basic`` (Freiberg's flow stress of C45); here pyroll-core
rolls with its tests' constant ``flow_stress = 100e6`` Pa (its roll force needs one)."""
from __future__ import annotations

import json
import math
import sys

import pyroll.core as pr

#: the plugin's mesh for this example (m): a quarter of pass II's exit half-thickness
MESH = {"h_contact": 0.00125}

GAPS = (25e-3, 10e-3)     # m
DURATION = 5.0            # s
WIDTH = 70e-3             # m
USABLE_WIDTH = 250e-3     # m


def profile():
    return pr.Profile.box(height=35e-3, width=WIDTH, corner_radius=2e-3,
                          temperature=1100 + 273.15, strain=0, material="C45", density=7.5e3,
                          specific_heat_capacity=690, flow_stress=100e6)


def sequence():
    roll1 = pr.Roll(groove=pr.FlatGroove(usable_width=USABLE_WIDTH), nominal_radius=300e-3 / 2)
    return pr.PassSequence([
        pr.RollPass(label="Flach Sack I", roll=roll1, gap=GAPS[0], velocity=0.3),
        pr.Transport(label="I -> II", duration=DURATION),
        pr.RollPass(label="Flach Sack II", roll=roll1, gap=GAPS[1], velocity=0.3),
    ])


def _json(v):
    if hasattr(v, "area") and hasattr(v, "bounds"):          # a shapely polygon
        return {"area": float(v.area), "bounds": [float(b) for b in v.bounds]}
    if isinstance(v, dict):
        return {str(k): _json(x) for k, x in v.items()}
    if isinstance(v, (set, frozenset)):
        return sorted(v)
    if isinstance(v, (list, tuple)):
        return [_json(x) for x in v]
    if isinstance(v, str) or v is None:
        return v
    try:
        x = float(v)
    except (TypeError, ValueError):
        return repr(v)
    return None if math.isnan(x) else x


def dump(p) -> dict:
    """The values set on the profile, and its height and width (computed)."""
    out = {k: _json(v) for k, v in p.__dict__.items() if not k.startswith("_")}
    for k in ("height", "width"):
        if p.has_value(k):
            out[f"computed {k}"] = float(getattr(p, k))
    return out


def _result(rp) -> dict:
    s = rp.hotroll_result
    keys = ("exit_velocity", "exit_thickness", "contact_length", "outlet_temperature_mean",
            "outlet_strain_mean", "homogeneous_exit_strain", "flow_stress_fit", "case_toml",
            "roll_force", "exit_profile")
    return {k: _json(s[k]) if k != "exit_profile" else
            {c: _json(s[k].get(c)) for c in ("eta", "temperature", "strain")} for k in keys}


def run(plugin: bool, thermal: bool = False) -> dict:
    """Roll the example (the plugins already imported); its out profiles as ``dump`` gives."""
    seq = sequence()
    seq.solve(profile())
    units = []
    for u in seq.units:
        row = {"type": type(u).__name__, "label": u.label, "in": dump(u.in_profile),
               "out": dump(u.out_profile), "duration": float(u.duration)}
        if isinstance(u, pr.RollPass):
            row["usable_width"] = float(u.usable_width)
            if plugin:
                row["hotroll"] = _result(u)
        units.append(row)
    out = {"units": units, "sequence": dump(seq.out_profile)}
    if thermal:
        tr = seq.units[1]
        lone = pr.Transport(label="lone", duration=DURATION)
        state = pr.Profile(**{k: v for k, v in tr.in_profile.__dict__.items()
                              if not k.startswith("_")})
        out["lone_transport_temperature"] = float(lone.solve(state).temperature)
    return out


if __name__ == "__main__":
    if "--plugin" in sys.argv:
        import hotroll.pyroll as hp

        hp.Config.MESH = dict(MESH)
        hp.Config.SOLVER = {"threads": 1}
    if "--thermal" in sys.argv:
        import pyroll.integral_thermal  # noqa: F401

        # its transport is implicit (the mean of in and out temperature): PyRolL iterates a
        # unit to its root hooks' relative precision, 1e-3 by default (about 1 K here)
        pr.Config.DEFAULT_ITERATION_PRECISION = 1e-10
    print(json.dumps(run("--plugin" in sys.argv, "--thermal" in sys.argv), sort_keys=True))
