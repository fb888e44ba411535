import sys, json, numpy as np
sys.path[:0] = ["tests", "tests/solvers"]
import hotroll
LAB = {"pass.roll_radius": 0.1, "pass.entry_thickness": 0.010, "pass.exit_thickness": 0.0075,
       "pass.roll_angular_velocity": 10.0}
for h in (0.000625, 0.0003125, 0.00015625):
    case = hotroll.example_case("hot_strip_finishing").with_overrides(
        **{"solver.threads": 1, "output.figures": False, "output.vtk": False, **LAB, "mesh.h_contact": h})
    res = hotroll.solve(case)
    s, c = res.summary, res.contact
    v = np.asarray(c["vertex"]) == 1
    x, p = np.asarray(c["x"])[v], -np.asarray(c["normal_stress"])[v]
    o = np.argsort(x); x, p = x[o], p[o]
    print(json.dumps({"h": h, "force": s["roll_force"], "torque": s["roll_torque"], "slip": s["forward_slip"],
        "entry_pressure": s["entry_pressure"], "mass": s["mass_flux_error"], "exit": s["exit_code"],
        "x_from_start_mm": [round((xx - x[0]) * 1e3, 4) for xx in x[:8]],
        "p_MPa": [round(pp / 1e6, 1) for pp in p[:8]]}), flush=True)
