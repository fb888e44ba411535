"""PyRolL scenarios hotroll does not solve (tests/workflows/test_pyroll_flat_sequences.py):
run as ``python pyroll_untouched.py [--plugin]``, prints one JSON line of what pyroll-core
computed, with ``import hotroll.pyroll`` first when ``--plugin`` is given. The test compares
the two lines: loading the plugin must change nothing here."""
from __future__ import annotations

import json
import math
import sys

if "--plugin" in sys.argv:
    import hotroll.pyroll  # noqa: F401

import pyroll.core as pr  # noqa: E402


def _number(x):
    try:
        x = float(x)
    except (TypeError, ValueError):
        return None
    return None if math.isnan(x) else round(x, 12)


def _profile(p) -> dict:
    out = {k: _number(getattr(p, k)) for k in ("height", "width", "temperature", "strain",
                                                "velocity") if p.has_value(k)}
    out["classifiers"] = sorted(p.classifiers) if p.has_value("classifiers") else None
    return out


def _units(seq) -> list:
    rows = []
    for u in seq.units:
        row = {"type": type(u).__name__, "label": u.label, "in": _profile(u.in_profile),
               "out": _profile(u.out_profile)}
        for k in ("roll_force", "velocity", "duration"):
            if u.has_value(k):
                row[k] = _number(getattr(u, k))
        if isinstance(u, pr.RollPass):
            row["contact_length"] = _number(u.roll.contact_length)
        rows.append(row)
    return rows


def _run(make):
    made = make()
    seq, ip, extra = made if len(made) == 3 else (*made, None)
    processor = extra if isinstance(extra, type) else None
    if processor is not None:
        pr.Transport.post_processors.append(processor)
    try:
        seq.solve(ip)
        out = _units(seq)
        if extra == "plot":
            out.append(_plot(seq.units[0]))
        return out
    except Exception as e:  # noqa: BLE001 - the outcome is what is compared
        return f"{type(e).__name__}: {str(e)[:120]}"
    finally:
        if processor is not None:
            pr.Transport.post_processors.remove(processor)


def _plot(unit) -> list:
    """The lines of the unit's matplotlib plot: per line its point count and coordinate sums."""
    import matplotlib

    matplotlib.use("Agg")
    fig = unit.plot_matplotlib()
    return [[len(ln.get_xdata()), _number(sum(map(float, ln.get_xdata()))),
             _number(sum(map(float, ln.get_ydata())))]
            for ax in fig.axes for ln in ax.get_lines()]


def flat_without_speed():
    """Flat after flat, no roll speed anywhere: PyRolL's own models (and its 90 degree turn)."""
    ip = pr.Profile.box(height=0.02, width=0.25, corner_radius=1e-3, temperature=1373.15,
                        strain=0.0, material="C45", flow_stress=100e6, density=7.5e3,
                        specific_heat_capacity=690)
    roll = pr.Roll(groove=pr.FlatGroove(usable_width=0.3), nominal_radius=0.15)
    return pr.PassSequence([pr.RollPass(label="I", roll=roll, gap=0.015),
                            pr.Transport(label="T", duration=5.0),
                            pr.RollPass(label="II", roll=roll, gap=0.011)]), ip


def flat_with_speed_no_flow_stress():
    """A roll speed, but no flow stress (no flow_stress, no flow_stress_function) and no hotroll
    grade: PyRolL's models (which need a flow stress too: the same error)."""
    ip = pr.Profile.box(height=0.02, width=0.25, corner_radius=1e-3, temperature=1373.15,
                        strain=0.0, material="AISI 304", density=7.5e3,
                        specific_heat_capacity=690)
    roll = pr.Roll(groove=pr.FlatGroove(usable_width=0.3), nominal_radius=0.15)
    return pr.PassSequence([pr.RollPass(label="I", roll=roll, gap=0.015, velocity=1.0),
                            pr.Transport(label="T", duration=5.0),
                            pr.RollPass(label="II", roll=roll, gap=0.011, velocity=1.0)]), ip


def round_bar_in_flat_passes():
    """A round bar through flat passes with a roll speed, a flow stress and a hotroll grade:
    no flat strip (its polygon fills 78 % of its bounding box), PyRolL's models."""
    ip = pr.Profile.round(diameter=0.03, temperature=1373.15, strain=0.0, material="C45",
                          flow_stress=100e6, density=7.5e3, specific_heat_capacity=690)
    roll = pr.Roll(groove=pr.FlatGroove(usable_width=0.05), nominal_radius=0.15,
                   rotational_frequency=1.0)
    return pr.PassSequence([pr.RollPass(label="I", roll=roll, gap=0.024),
                            pr.Transport(label="T", duration=2.0)]), ip


def box_pass_of_a_hotroll_grade():
    """A grooved pass, with a hotroll grade and a speed: not flat, PyRolL's."""
    ip = pr.Profile.round(diameter=0.03, temperature=1373.15, strain=0.0, material="C45",
                          flow_stress=100e6, density=7.5e3, specific_heat_capacity=690)
    roll = pr.Roll(groove=pr.BoxGroove(depth=0.008, r1=0.002, r2=0.004, ground_width=0.025,
                                       flank_angle=80), nominal_radius=0.15,
                   rotational_frequency=1.0)
    return pr.PassSequence([pr.RollPass(label="box", roll=roll, gap=0.004),
                            pr.Transport(label="T", duration=2.0)]), ip


def transport_without_temperature():
    """A profile with no temperature through a transport (no roll pass)."""
    ip = pr.Profile.round(diameter=0.02, strain=0.0, flow_stress=100e6)
    return pr.PassSequence([pr.Transport(label="T", duration=1.0)]), ip


def transport_of_a_hot_strip_alone():
    """A hot strip through a transport that follows no hotroll pass: PyRolL keeps its
    temperature (no thermal plugin), so must hotroll."""
    ip = pr.Profile.box(height=0.02, width=0.25, corner_radius=1e-3, temperature=1373.15,
                        strain=0.0, material="C45", flow_stress=100e6, density=7.5e3,
                        specific_heat_capacity=690)
    return pr.PassSequence([pr.Transport(label="T", duration=10.0)]), ip


def a_users_post_processor():
    """A post-processor of the user's own on Transport (PyRolL's Unit.post_processors, where
    the plugin registers its cooling too): it runs as without the plugin."""

    class Halve:
        label = "10 K off"

        def __init__(self, unit):
            pass

        def solve(self, profile):
            profile.temperature = profile.temperature - 10.0
            return profile

    ip = pr.Profile.box(height=0.02, width=0.25, corner_radius=1e-3, temperature=1373.15,
                        strain=0.4, material="C45", flow_stress=100e6, density=7.5e3,
                        specific_heat_capacity=690)
    return pr.PassSequence([pr.Transport(label="T", duration=10.0),
                            pr.Transport(label="T2", duration=5.0)]), ip, Halve


def the_box_pass_plotted():
    """A roll pass's plot (matplotlib): the same lines with and without the plugin."""
    seq, ip = box_pass_of_a_hotroll_grade()
    return seq, ip, "plot"


SCENARIOS = (flat_without_speed, flat_with_speed_no_flow_stress, round_bar_in_flat_passes,
             box_pass_of_a_hotroll_grade, transport_without_temperature,
             transport_of_a_hot_strip_alone, a_users_post_processor, the_box_pass_plotted)

if __name__ == "__main__":
    print(json.dumps({f.__name__: _run(f) for f in SCENARIOS}, sort_keys=True))
