"""No unintended result change: bundled Example 2 against its golden summary
(tests/data/golden, ``scripts/summary_diff.py run``). [snap] A snapshot: a guard against an
unintended change, not an independent reference. Re-taken only where a change of the solver's
path is intended and measured: the recut into layers changed nothing (against the summary of
88591b2, kept in tests/data/before_recut for the typed summary's test); the primal-dual
Newton tangent (issue 34, session 5) moved it within the solver's tolerance (force 5e-8,
torque 3.2e-7, a_f 4.3e-7; docs/validation/speed.md); the friction's primal-dual tangent
(session 6: 24 -> 17 Newton iterations) moved it within Example 2's tolerance band (force
3.2e-6, torque 8.1e-6, slip 3.3e-6 against 9e-6, 2.1e-5, 4.9e-6; a_f 4.6e-5 of its 1e-2
tolerance), and the golden summary is that run's. Issue 50 made contact unilateral by default
(an intended change of the model: Example 2's thick strip now leaves the roll 0.039 rad before
the gap; force +3.1 %, forward slip 3.39 -> 4.10 %, measured against the summary before), and
the golden summary is that run's. Issue 50 session 2 carries the multiplier with the position
when the contact's end moves (another path to the same fixed point: a_f 1.05e-8, the separation
angle 2.6e-8, the end's residual pressure -5.75e-4 -> -5.75e-4 of a peak near 3, all within
the couplings' tolerances) and adds entry_pressure; the golden summary is that run's. Issue 51
(one neutral story) added two keys, `neutral` (the story in words) and `sticking_zone_x`, and
made `temperature` null where nothing depends on it (Norton-Hoff, no [thermal]): the golden
summary keeps its numbers (the run after the change is the same to 1e-8) and takes those three
from that run. Issue 52 made the symmetry line hold v_y = 0 exactly (a642130: the kinematic
guess's projection error had stayed on it, 2e-4 U on Case R): an intended correction, measured
against the summary before (force 2.1e-4, torque 1.5e-4, forward slip 5.9e-4, the power
balance's error 3.4e-4 -> 3.3e-5; docs/validation/recut.md); the golden summary is that run's
(made with ``scripts/summary_diff.py run`` at a642130). Issue 53 made the steady mesh refined
16x at the contact's start the default (an intended change of the discretisation: force
-2.9e-5, torque +8.3e-4, forward slip 4.098 -> 4.054 %, mass_flux_error 2.6e-4 -> 5.5e-5;
docs/validation/corner-default.md); the golden summary is that run's (e1514be). The traced
tops' cubic rule (an intended change of the discretisation, 1073729: force +1.1e-4, torque
+2.3e-4, forward slip 4.054 -> 4.054 %, mass_flux_error 5.5e-5 -> 1.3e-5;
docs/validation/traced-top.md); the golden summary is that run's.

The whole set (every bundled example, the schedule and a study) is compared by
``python scripts/summary_diff.py run DIR`` on two commits and ``... compare BEFORE AFTER``
(docs/architecture.md)."""
from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parents[1]
BEFORE = HERE / "data" / "before_recut"
GOLDEN = HERE / "data" / "golden"
SCRIPT = HERE.parent / "scripts" / "summary_diff.py"


def _script():
    spec = importlib.util.spec_from_file_location("summary_diff", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.parametrize("name", ["2"])
def test_bundled_example_summary_is_the_golden_one(name, tmp_path):
    """Keys and units identical, every number to 1e-8 (relative, or of its unit's largest
    figure for rounding-level ones such as the horizontal force): NGSolve's threaded assembly
    sums in a different order from run to run, which moved the torque of the same code by
    1.05e-9 between two runs (measured), so 1e-9 is the noise, not a change."""
    out = tmp_path / name
    proc = subprocess.run([sys.executable, "-m", "hotroll.cli", "example", name, "--out", str(out)],
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-2000:]
    problems = _script().compare(GOLDEN / "example" / name, out, 1e-8)
    assert not problems, "\n".join(problems)


def test_the_comparison_sees_a_change(tmp_path):
    """The comparison itself at the suite's 1e-8: a roll force x (1 + 1e-7), a renamed key and
    a changed unit are each reported; a horizontal force moved by 1e-9 of the roll force is
    rounding."""
    sd = _script()
    s = json.loads((BEFORE / "example" / "2" / "summary.json").read_text())
    for change, expect in ((lambda d: d.update(roll_force=d["roll_force"] * (1 + 1e-7)),
                            "roll_force"),
                           (lambda d: d.update(roll_forse=d.pop("roll_force")), "keys only"),
                           (lambda d: d["units"].update(roll_force="kN/m"), "units.roll_force")):
        d = json.loads(json.dumps(s))
        change(d)
        found: list[str] = []
        sd.diff(s, d, 1e-8, "s", found)
        assert any(expect in p for p in found), (expect, found)
    d = json.loads(json.dumps(s))
    d["horizontal_force"] += 1e-9 * s["roll_force"]
    found = []
    sd.diff(s, d, 1e-8, "s", found)
    assert not found, found
