"""The temperature carried with the material in the report's transient scheme (issue 16,
hotroll/solvers/thermal_lagrangian.py): an adiabatic pass run to its steady state on the coarse
Example 1 geometry (h = 0.04 m), against the energy balance of the material that has passed the gap."""
from __future__ import annotations

import pytest
from casebuild import build_case, example1_coarse, shared_scope

from hotroll.workflows.runner import run_case

RHO, C = 7600.0, 650.0
T0 = 1373.15

BASE = example1_coarse(
    "transient_thermal", friction={"a_f": 3.0},
    material={"K": 5.0e7, "m": 0.2, "density": RHO, "specific_heat": C, "conductivity": 30.0},
    plate={"length": 1.0, "temperature": T0},
    solver={"method": "transient", "end_time": 3.0, "threads": 1},
    mesh={"h_contact": 0.04},          # 6.7 s to the steady state (h = 0.02: 20 s, the same checks)
    thermal={"htc_contact": 0.0, "roll_temperature": 350.0, "htc_air": 0.0,
             "emissivity": 0.0})


@pytest.fixture(scope=shared_scope)
def adiabatic_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("transient_adiabatic")
    return run_case(build_case(BASE), out), out


@pytest.fixture(scope=shared_scope)
def adiabatic(adiabatic_run):
    return adiabatic_run[0]


def test_adiabatic_transient_exit_rise(adiabatic):
    """Nodes are material points and keep their temperature; each step adds beta q dt/(rho c)
    (lumped implicit step). At the steady state the material in the exit band has taken all
    the plastic and friction heat of the bite: the mixing-cup rise is (beta x plastic power +
    f_s x friction power) / (rho c Q), Q the entry flux. Measured +1.9 % here, +1.2 % on
    h = 0.02 (the summary window's means of an oscillating transient; a hard Coulomb pass of
    hotroll/examples/cases/thermal_pass.toml on h = 0.01: -0.16 %). The step's energy identity (the
    lumped enthalpy change against the heat flows) closes (measured 6e-13: nothing leaves an
    adiabatic plate, so only the plastic heat's quadrature is in it, 2.6e-4 from 0.9 x the
    plastic power)."""
    s = adiabatic
    assert s["status"] == "steady" and s["method"] == "transient"
    rise = (s["plastic_heat"] + s["friction_heat_to_strip"]) / (RHO * C * s["mass_flux_in"])
    assert rise > 1.0                                  # a real heating
    assert s["exit_temperature_mean"] - T0 == pytest.approx(rise, rel=0.03)
    assert s["plastic_heat"] == pytest.approx(0.9 * s["plastic_power"], rel=1e-3)
    assert s["heat_balance_error"] < 1e-3
    assert s["heat_to_roll"] == 0.0 and s["heat_to_air"] == 0.0
    # the surface at the gap: heated by friction and shear, a nodal value of the field, so
    # between the entry and the largest temperature
    assert T0 < s["exit_temperature_surface"] <= s["max_temperature"] + 1e-9


def test_the_plate_temperature_file_is_the_carried_field(adiabatic_run):
    """thermal.npz of the report's scheme: the plate's vertices, its triangles (indices into
    them) and one temperature per vertex (K), between the entry's and the largest."""
    import numpy as np

    s, out = adiabatic_run
    with np.load(out / "thermal.npz") as f:
        assert set(f.files) == {"points", "triangles", "temperature"}
        pts, tri, T = f["points"], f["triangles"], f["temperature"]
    assert pts.shape == (len(T), 2) and tri.shape[1] == 3 and tri.max() == len(T) - 1
    assert T.min() >= T0 - 1e-6 and T.max() == pytest.approx(s["max_temperature"])


def test_checkpoint_carries_the_temperature(tmp_path):
    """The nodal temperatures are in the checkpoint: a run stopped after 3 steps, its
    temperature changed, saved and loaded again, comes back with those temperatures (and a
    case with another fingerprint starts from the entry temperature)."""
    import numpy as np

    from hotroll.solvers.transient import TransientRun
    from hotroll.workflows.runner import build_model

    model, settings = build_model(build_case(BASE))
    ckpt = tmp_path / "ckpt"
    run = TransientRun(model, settings, checkpoint_dir=ckpt, fingerprint="A")
    run.s.end_time = 3.5 * run.s.dt
    run.run()
    assert run.state.step == 3
    assert run.thermal.values.max() > T0 + 1e-3          # three steps of deformation heat
    run.thermal.values[:] += np.linspace(0.0, 5.0, run.thermal.values.size)
    run.save_checkpoint()
    again = TransientRun(model, settings, checkpoint_dir=ckpt, fingerprint="A")
    assert np.array_equal(again.thermal.values, run.thermal.values)
    other = TransientRun(model, settings, checkpoint_dir=ckpt, fingerprint="B")
    assert other.thermal.values == pytest.approx(T0, rel=1e-12)


def test_the_carried_temperature_gives_the_laws_flow_stress():
    """The transient scheme's temperature feeds the flow stress: at a uniform carried 1200 K
    and the entry strain 0.2 (no strain field), the form's consistency ratio is the law's
    K(0.2, 1200 K) / K_ref and its rate-exponent offset m(1200 K) - m_ref, by the law's
    own formula (Hensel-Spittel with m8 != 0)."""
    from netgen.occ import OCCGeometry, WorkPlane, X, Y
    from ngsolve import Integrate, Mesh

    from hotroll.model.flow_stress.hensel_spittel import HenselSpittel
    from hotroll.model.thermal_properties import ThermalBoundary, ThermalProperties
    from hotroll.solvers.thermal_lagrangian import LagrangianThermal

    law = HenselSpittel(1.5e9, m1=-0.0025, m2=0.2, m3=0.05, m4=-0.05, m8=1e-4)
    K_ref, m_ref = 8e7, 0.15
    face = WorkPlane().Rectangle(0.02, 0.01).Face()
    for edges, name in ((face.edges.Min(Y), "sym"), (face.edges.Max(Y), "top"),
                        (face.edges.Min(X), "in"), (face.edges.Max(X), "out")):
        edges.name = name
    mesh = Mesh(OCCGeometry(face, dim=2).GenerateMesh(maxh=0.005))
    thermal = LagrangianThermal(mesh, ThermalProperties(RHO, C, 30.0),
                                ThermalBoundary(1200.0, 300.0, 300.0, 0.0, 0.0, 0.0),
                                K_ref, m_ref, 1e-3, flow=law, entry_strain=0.2)
    assert thermal.values == pytest.approx(1200.0)
    area = Integrate(1.0, mesh)
    ratio = Integrate(thermal.consistency(), mesh) / area
    assert ratio == pytest.approx(float(law.consistency(0.2, 1200.0)) / K_ref, rel=1e-12)
    offset = Integrate(thermal.rate_offset(), mesh) / area
    assert offset == pytest.approx(float(law.rate_exponent(1200.0)) - m_ref, rel=1e-12)
