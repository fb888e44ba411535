"""ParaView output of a run with a temperature field (solvers/record_fields.py ``write_vtk``): the
strip mesh's own file thermal.vtu beside fields.vtu, read back with meshio (an independent
reader of the VTK XML format). No solve: the thermal example's pass set up (cold start) and its
temperature set to a linear function of x, which the P1 field holds exactly."""
from __future__ import annotations

import numpy as np
import pytest

from hotroll.config.case import load_case
from hotroll.examples import example_path


@pytest.fixture
def thermal_run():
    from hotroll.solvers.steady import SteadyRun
    from hotroll.workflows.runner import build_model, steady_settings

    case = load_case(example_path("thermal_pass"))
    model, _ = build_model(case)
    run = SteadyRun(model, steady_settings(case), case.plate.length)
    run._cold_start()
    return run


@pytest.mark.parametrize("shift", [0.0, 0.5])
def test_thermal_vtu_is_the_strip_temperature(thermal_run, tmp_path, shift):
    """T = 1000 K + 100 K/m x on the strip: thermal.vtu has the strip mesh's triangles, and at
    each of its points the temperature is 1000 + 100 (x - shift) (the file is in the case's
    frame, moved by ``shift``); the strip's displacement is back as it was afterwards."""
    import meshio
    import ngsolve

    from hotroll.solvers.record_fields import write_vtk

    th = thermal_run.thermal
    th.field.gf.Set(1000.0 + 100.0 * ngsolve.x)
    before = th.strip.disp.vec.FV().NumPy().copy()
    path = write_vtk(thermal_run, tmp_path / "fields.vtu", shift=shift)
    assert path == tmp_path / "fields.vtu"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fields.vtu", "thermal.vtu"]
    vtu = meshio.read(tmp_path / "thermal.vtu")
    assert sum(len(c.data) for c in vtu.cells) == th.strip.mesh.ne
    T = np.asarray(vtu.point_data["temperature"]).ravel()
    assert T == pytest.approx(1000.0 + 100.0 * (vtu.points[:, 0] - shift), abs=1e-6)
    assert np.array_equal(th.strip.disp.vec.FV().NumPy(), before)
