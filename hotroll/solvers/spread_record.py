"""The solved 3D pass as data (``model/spread_result.SpreadResult``, issue 53): its figures,
the exit cross-section, the width along the bite, the contact pressure over the arc and width,
and its ParaView writer. The quarter's figures are made the whole strip's here (forces and
torques of one roll x 2, fluxes x 4)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from hotroll.files import atomic
from hotroll.model.spread_result import SpreadResult
from hotroll.solvers.spread_contact import level_contact

#: the exit cross-section's sample heights: this many equal steps through the half thickness
SECTION_POINTS = 40


def spread_record(s3) -> SpreadResult:
    """The ``SpreadResult`` of a solved ``Spread3D`` ``s3`` (with a free edge)."""
    if s3.face is None:
        raise ValueError("spread_record: the 3D pass has its edge held (no spread)")
    fig = s3.figures()
    run, rp, K = s3.run2d, s3.problem.rp, s3.problem.material.K
    nv, levels = run.mesh.nv, len(s3.z)
    # the 3D mesh's deformed vertices, level k's the rows k nv ... (k + 1) nv
    d3 = s3.disp.vec.FV().NumPy()
    n3, nv3 = d3.size // 3, s3.mesh.nv
    X3 = np.array([v.point for v in s3.mesh.vertices]) + np.stack(
        [d3[c * n3:c * n3 + nv3] for c in range(3)], axis=1)
    P = np.array([v.point for v in run.mesh.vertices])[:, :2]          # reference (x, y)
    X = X3[(levels - 1) * nv:, :2]                                      # the edge level's
    # the exit section: the reference outlet's heights (rp.half_exit) scaled to the deformed
    # outlet's, at the edge
    out = np.isclose(P[:, 0], P[:, 0].max())
    scale = X[out, 1].max() / P[out, 1].max()
    step = rp.half_exit / SECTION_POINTS
    y_ref = np.linspace(0.0, rp.half_exit, SECTION_POINTS + 1)[:-1] + 0.5 * step
    section = {"y": y_ref * scale, "half_width": np.asarray(fig["exit_half_width_profile"])}
    # the exit thickness across the width: each level's outlet top (its highest outlet vertex)
    # at that level's z, twice (the full thickness)
    top_out = np.nonzero(out)[0][np.argmax(P[out, 1])]
    rows = np.arange(levels) * nv + top_out
    section_z = {"z": X3[rows, 2], "thickness": 2.0 * X3[rows, 1]}
    if s3.strain is not None:
        # the strain carried through the 3D strip: each level's outlet, its mean over the
        # thickness (the P1 values' trapezoids over the outlet's deformed heights)
        outs = np.nonzero(out)[0]
        outs = outs[np.argsort(P[outs, 1])]
        eps = s3.strain.values
        mean = []
        for k in range(levels):
            idx = k * nv + outs
            y, e = X3[idx, 1], eps[idx]
            mean.append(float(np.sum(0.5 * (e[1:] + e[:-1]) * np.diff(y)) / (y[-1] - y[0])))
        section_z["strain"] = np.array(mean)
    offset = None if s3.cooling is None else exit_offset(s3, X3, out, P)
    # the half width along x at mid-thickness (the sym line) and on the strip's surface (B's
    # vertex values at the edge level's x, the surface's interpolated to the sym line's x)
    B = s3.face.B.vec.FV().NumPy()[:nv]
    sym, surface = _boundary_vertices(run.mesh, ("sym",)), run.top.verts
    sym, surface = (i[np.argsort(X[i, 0])] for i in (sym, surface))
    along = {"x": X[sym, 0], "centre": B[sym],
             "surface": np.interp(X[sym, 0], X[surface, 0], B[surface])}
    # the contact pressure at the arc's vertices in every level (x, angle, z of each): the
    # nodal forces over their lengths along the level, the multiplier's own values beside
    # them (solvers/spread_contact.py, as the 2D pass's contact.csv)
    lev = level_contact(s3)
    cmap = {"x": lev["x"], "angle": rp.angle(np.stack([lev["x"], lev["y"]], axis=-1)),
            "z": lev["z"], "pressure": K * lev["traction"],
            "pressure_multiplier": K * lev["multiplier"]}
    omega = rp.omega
    return SpreadResult(
        stock_width=2.0 * fig["stock_half_width"], exit_width=2.0 * fig["exit_half_width"],
        exit_section=section, exit_thickness=section_z, width_along=along, contact_map=cmap,
        roll_force=fig["roll_force"], roll_torque=fig["roll_torque"],
        roll_power=fig["roll_torque"] * omega,
        flux_in=4.0 * fig["flux_in"], flux_out=4.0 * fig["flux_out"],
        flux_edge=4.0 * fig["flux_edge"],
        midplane={k: fig[k] for k in ("midplane_pressure_deviation",
                                      "midplane_pressure_rms_deviation",
                                      "midplane_contact_pressure_deviation",
                                      "midplane_contact_pressure_rms_deviation",
                                      "midplane_contact_pressure_l2_deviation",
                                      "midplane_velocity_deviation",
                                      "midplane_stress_l2_deviation",
                                      "midplane_bite_stress_l2_deviation")},
        power_balance_error=fig["power_balance_error"], settled=bool(fig["settled"]),
        rounds=int(fig["rounds"]), newton_iterations=int(fig["newton_iterations"]),
        dofs=int(fig["dofs"]), layers=levels - 1, zone_cut=fig["zone_cut"],
        exit_temperature_offset=offset,
        failure=fig["failure"], forward_slip=fig["forward_slip"],
        edge_layer=float(s3.z[-1] - s3.z[-2]), wall_time=fig["wall_time"],
        write_vtk=lambda path, shift=0.0: write_vtk_3d(s3, path, shift))


def exit_offset(s3, X3: np.ndarray, out: np.ndarray, P: np.ndarray) -> dict:
    """The entry temperature's difference from mid-width's as the outlet carries it (K):
    ``values[j][k]`` at the outlet's vertex heights (eta: over each level's top, averaged over
    the levels) and the width levels (zeta: over the edge's half width at that height,
    averaged over the heights), less mid-width's (the first level's: an edge zone's interior
    layer carries its cut's, the entry uniform up to it)."""
    nv, levels = s3.run2d.mesh.nv, len(s3.z)
    outs = np.nonzero(out)[0]
    outs = outs[np.argsort(P[outs, 1])]
    idx = np.arange(levels)[None, :] * nv + outs[:, None]          # (heights, levels)
    y, z = X3[idx, 1], X3[idx, 2]
    eta = np.mean(y / y[-1:, :], axis=1)
    zeta = np.mean(z / z[:, -1:], axis=0)
    values = s3.cooling.values[idx]
    values = values - values[:, :1]      # mid-width's (the carried field's residue there) is 0
    eta[0], eta[-1], zeta[0], zeta[-1] = 0.0, 1.0, 0.0, 1.0
    return {"eta": eta.tolist(), "zeta": zeta.tolist(), "values": values.tolist()}


def _boundary_vertices(mesh, names) -> np.ndarray:
    """The vertex numbers of the boundary elements named ``names``."""
    from ngsolve import BND

    return np.array(sorted({v.nr for el in mesh.Elements(BND) if el.mat in names
                            for v in el.vertices}), dtype=int)


def write_vtk_3d(s3, path: Path, shift: float = 0.0) -> Path:
    """ParaView file (.vtu) of the 3D quarter strip: velocity (m/s), pressure (Pa), equivalent
    strain rate (1/s) and, where they are carried through the 3D flow, the strain (-) and the
    entry temperature's difference from mid-width's (K, ``temperature_offset``) on the
    deformed mesh, moved by ``shift`` in x."""
    import ngsolve

    from hotroll.fem.forms import strain_rate
    from hotroll.model.material import edot_squared

    f, K = s3.form, s3.problem.material.K
    u = f.nonlinear.velocity
    d = s3.disp.vec.FV().NumPy()
    nv = s3.mesh.nv
    d[:nv] += shift                      # the x displacement's vertex DOFs (bubbles unmoved)
    try:
        s3.mesh.SetDeformation(s3.disp)
        edot = ngsolve.sqrt(edot_squared(strain_rate(u)) + 1e-300)
        coefs, names = [u, K * f.nonlinear.pressure, edot], ["velocity", "pressure", "edot"]
        if s3.strain is not None:
            coefs.append(s3.strain.gf)
            names.append("strain")
        if s3.cooling is not None:
            coefs.append(s3.cooling.gf)
            names.append("temperature_offset")
        with atomic(Path(path).with_suffix(".vtu")) as tmp:     # NGSolve appends .vtu
            ngsolve.VTKOutput(s3.mesh, coefs=coefs, names=names,
                              filename=str(tmp.with_suffix("")), subdivision=0).Do()
    finally:
        d[:nv] -= shift
        s3.mesh.SetDeformation(s3.disp)
    return Path(path).with_suffix(".vtu")
