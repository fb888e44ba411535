"""Tests for hotroll.results.figures on a synthetic run output directory."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from hotroll.results.figures import plot_all, plot_compare

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

ALL_FIGS = ("fig_mesh.png", "fig_sigma_ef.png", "fig_velocity.png",
            "fig_contact.png", "fig_contact_angle.png", "fig_top.png", "fig_history.png")


def _write_csv(path: Path, header: list[str], rows: np.ndarray) -> None:
    with open(path, "w") as f:
        f.write(", ".join(header) + "\n")
        for r in np.atleast_2d(rows):
            f.write(",".join(f"{v:.10g}" for v in r) + "\n")


def make_run(out: Path, *, roll_speed: float = 1.12, m: float = 0.2,
             case_name: str = "synthetic", nx: int = 60, ny: int = 6) -> Path:
    """Synthetic rolling output: roll R=1 at (0, 1.2), entry half thickness 0.25.

    The top boundary follows the roll arc between the first touching point and
    x = 0 (gap 0.2); the velocity field conserves mass (v1 * h = const).
    """
    out.mkdir(parents=True, exist_ok=True)
    R, xc, yc = 1.0, 0.0, 1.2
    h0, h1, v_in = 0.25, yc - R, 1.0
    x_start = -R * math.sqrt(1.0 - ((yc - h0) / R) ** 2)

    def top(x):
        x = np.asarray(x, dtype=float)
        arc = yc - np.sqrt(np.maximum(R**2 - (x - xc) ** 2, 0.0))
        return np.where(x < x_start, h0, np.where(x > xc, h1, arc))

    def dtop(x):
        x = np.asarray(x, dtype=float)
        inside = (x >= x_start) & (x <= xc)
        d = np.zeros_like(x)
        d[inside] = (x[inside] - xc) / np.sqrt(R**2 - (x[inside] - xc) ** 2)
        return d

    # structured mesh, denser inside the bite
    xs = np.unique(np.r_[np.linspace(-1.5, 1.2, nx), np.linspace(x_start, xc, 25)])
    etas = np.linspace(0.0, 1.0, ny + 1)
    X, E = np.meshgrid(xs, etas, indexing="ij")
    Y = E * top(X)
    points = np.column_stack([X.ravel(), Y.ravel()])
    nxp, nyp = X.shape
    idx = np.arange(nxp * nyp).reshape(nxp, nyp)
    a, b = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    c, d = idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    triangles = np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])

    h = top(points[:, 0])
    v1 = v_in * h0 / h
    v2 = v1 * E.ravel() * dtop(points[:, 0])
    v = np.column_stack([v1, v2])
    edot = np.abs(np.gradient(v1, axis=0)) + 0.1
    sigma_ef = 1e7 * (1.0 + 2.0 * np.exp(-((points[:, 0] - x_start) ** 2) / 0.02)
                      * (0.5 + E.ravel()))
    pressure = -5e6 * np.exp(-((points[:, 0] + 0.15) ** 2) / 0.05)

    top_ids = idx[:, -1]
    top_x = points[top_ids, 0]
    in_contact = (top_x >= x_start - 1e-12) & (top_x <= xc + 1e-12)
    cids = top_ids[in_contact]
    contact_edges = np.column_stack([cids[:-1], cids[1:]])

    np.savez(out / "fields.npz", points=points, triangles=triangles, v=v,
             sigma_ef=sigma_ef, pressure=pressure, edot=edot,
             contact_edges=contact_edges, roll_centre=np.array([xc, yc]),
             roll_radius=np.float64(R))

    # contact profile (entry -> exit)
    cx, cy = points[cids, 0], points[cids, 1]
    angle = np.arcsin((xc - cx) / R)
    speed = np.hypot(v1[cids], v2[cids])
    v_slip = speed - roll_speed
    k = 1e7
    xn_idx = np.argmin(np.abs(v_slip))
    sn = -k * (1.0 + 1.5 * np.exp(-((cx - cx[xn_idx]) ** 2) / 0.01))
    snc = sn.copy()
    snc[-3:] *= np.linspace(0.7, 0.1, 3)
    st = -m * k * np.tanh(v_slip / 0.02)
    _write_csv(out / "contact.csv",
               ["x", "y", "angle", "v_slip", "normal_stress", "shear_stress",
                "normal_stress_corrected"],
               np.column_stack([cx, cy, angle, v_slip, sn, st, snc]))

    # neutral point by linear interpolation of v_slip
    j = int(np.nonzero(np.diff(np.sign(v_slip)) > 0)[0][0])
    t = -v_slip[j] / (v_slip[j + 1] - v_slip[j])
    xn = cx[j] + t * (cx[j + 1] - cx[j])
    yn = cy[j] + t * (cy[j + 1] - cy[j])

    _write_csv(out / "top.csv", ["x", "y", "v1", "v2"],
               np.column_stack([top_x, points[top_ids, 1], v1[top_ids], v2[top_ids]]))

    n = 30
    step = np.arange(1, n + 1)
    time = 0.01 * step
    hist = np.column_stack([
        step, time, 0.05 * np.ones(n), 10.0 ** (-1 - 3 * step / n),
        10.0 ** (-0.5 - 2 * step / n), 2e6 * (1 - np.exp(-step / 5)),
        4e5 * (1 - np.exp(-step / 5)), 0.1 + 0.05 * np.exp(-step / 8),
        0.05 * (1 - np.exp(-step / 6)), 3 + (step % 4), 1e-9 * np.ones(n)])
    _write_csv(out / "history.csv",
               ["step", "time", "a_f", "strain_rate_measure", "slip_measure",
                "roll_force", "roll_torque", "neutral_angle", "forward_slip",
                "iterations", "residual"], hist)

    summary = {
        "case_name": case_name, "neutral_point": [float(xn), float(yn)],
        "neutral_angle": float(np.arcsin((xc - xn) / R)), "roll_force": 2e6,
        "roll_torque": 4e5, "roll_power": 4e5 * roll_speed / R,
        "forward_slip": float(v_in * h0 / h1 / roll_speed - 1.0), "a_f": 0.05,
        "converged": True, "steps": n, "roll_centre": [xc, yc], "roll_radius": R,
        "contact_start": [float(cx[0]), float(cy[0])],
        "contact_end": [float(cx[-1]), float(cy[-1])], "m": m,
        "roll_surface_speed": roll_speed,
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    return out


def _assert_png(path: Path, min_size: int = 5000) -> None:
    assert path.is_file(), path
    assert path.read_bytes()[:8] == PNG_MAGIC, path
    assert path.stat().st_size > min_size, (path, path.stat().st_size)


def test_plot_all_writes_every_figure(tmp_path):
    run = make_run(tmp_path / "run")
    paths = plot_all(run)
    assert sorted(p.name for p in paths) == sorted(ALL_FIGS)
    for name in ALL_FIGS:
        _assert_png(run / name)


def test_plot_all_summary_only(tmp_path):
    d = tmp_path / "only_summary"
    d.mkdir()
    (d / "summary.json").write_text(json.dumps({"case_name": "empty", "converged": False}))
    assert plot_all(d) == []


def test_plot_all_partial_run(tmp_path):
    run = make_run(tmp_path / "partial")
    (run / "history.csv").unlink()
    (run / "fields.npz").unlink()
    paths = plot_all(run)
    assert sorted(p.name for p in paths) == ["fig_contact.png", "fig_contact_angle.png", "fig_top.png"]
    for p in paths:
        _assert_png(p)


def test_plot_compare(tmp_path):
    runs = {f"v_R = {vr}": make_run(tmp_path / f"r{i}", roll_speed=vr, case_name=f"r{i}")
            for i, vr in enumerate((1.08, 1.12, 1.16))}
    out = plot_compare(runs, tmp_path / "cmp" / "compare.png", title="roll speed study")
    assert out == tmp_path / "cmp" / "compare.png"
    _assert_png(out, min_size=20000)


def test_plot_compare_tolerates_missing_files(tmp_path):
    a = make_run(tmp_path / "a")
    b = tmp_path / "b"
    b.mkdir()
    out = plot_compare({"full": a, "empty": b}, tmp_path / "cmp.png")
    _assert_png(out)


def test_the_exit_profile_figure_draws_the_files_columns(tmp_path, monkeypatch):
    """fig_exit_profile by its data: a panel per column exit_profile.csv holds (temperature,
    strain, pass strain, shear strain; a column of NaN left out), each the column against
    eta; an asymmetric pass's eta from -1 named on the axis; None without the file."""
    import matplotlib.axes

    from hotroll.results.figures.exit_profile import fig_exit_profile
    from hotroll.results.figures.run_files import RunFiles

    run = make_run(tmp_path / "run")
    assert fig_exit_profile(RunFiles(run), run / "fig_exit_profile.png") is None
    eta = np.linspace(-1.0, 1.0, 5)
    T, gamma = 1300.0 - 50.0 * eta**2, 0.1 * eta + 0.05
    _write_csv(run / "exit_profile.csv", ["eta", "temperature", "strain", "shear_strain"],
               np.column_stack([eta, T, np.full(5, np.nan), gamma]))
    drawn = []
    real = matplotlib.axes.Axes.plot
    monkeypatch.setattr(matplotlib.axes.Axes, "plot",
                        lambda ax, *a, **k: (drawn.append((ax, a)), real(ax, *a, **k))[1])
    path = fig_exit_profile(RunFiles(run), run / "fig_exit_profile.png")
    _assert_png(path, 2000)
    assert len(drawn) == 2                       # the NaN strain has no panel
    np.testing.assert_allclose(drawn[0][1][0], T)
    np.testing.assert_allclose(drawn[1][1][0], gamma)
    np.testing.assert_allclose(drawn[0][1][1], eta)
    assert "-1 lower" in drawn[0][0].get_ylabel()


def test_the_temperature_figure_draws_both_surfaces_of_an_asymmetric_pass(tmp_path, monkeypatch):
    """fig_temperature of an asymmetric pass by its data: the upper surface from top.csv, the
    lower from top_lower.csv, each roll's heat flux (MW/m^2) from its own contact file, the
    exit lines of both surfaces' temperatures (values written here, no solve)."""
    import matplotlib.axes

    from hotroll.results.figures.run_files import RunFiles
    from hotroll.results.figures.thermal import fig_temperature

    run = make_run(tmp_path / "run")
    summary = json.loads((run / "summary.json").read_text())
    summary.update(thermal=True, exit_temperature_mean=1370.0, exit_temperature_surface=1200.0,
                   exit_temperature_surface_lower=1190.0)
    (run / "summary.json").write_text(json.dumps(summary))
    f = dict(np.load(run / "fields.npz"))
    f["temperature"] = 1300.0 + 10.0 * f["points"][:, 1]
    np.savez(run / "fields.npz", **f)
    x = np.linspace(-1.5, 1.2, 7)
    T_up, T_lo = 1300.0 - 20.0 * x, 1290.0 - 30.0 * x
    q_up, q_lo = np.array([1.0e7, 2.0e7, 3.0e7]), np.array([1.5e7, 2.5e7, 3.5e7])
    xc = np.array([-0.5, -0.3, -0.1])
    _write_csv(run / "top.csv", ["x", "y", "v1", "v2", "temperature"],
               np.column_stack([x, np.ones(7), np.ones(7), np.zeros(7), T_up]))
    _write_csv(run / "top_lower.csv", ["x", "y", "v1", "v2", "temperature"],
               np.column_stack([x, np.ones(7), np.ones(7), np.zeros(7), T_lo]))
    for name, q in (("contact.csv", q_up), ("contact_lower.csv", q_lo)):
        _write_csv(run / name, ["x", "y", "angle", "normal_stress", "shear_stress",
                                "heat_flux_to_roll"],
                   np.column_stack([xc, np.ones(3), np.zeros(3), -np.ones(3), np.zeros(3), q]))
    lines, hlines = [], []
    real_plot, real_axh = matplotlib.axes.Axes.plot, matplotlib.axes.Axes.axhline
    monkeypatch.setattr(matplotlib.axes.Axes, "plot",
                        lambda ax, *a, **k: (lines.append((k.get("label"), a)),
                                             real_plot(ax, *a, **k))[1])
    monkeypatch.setattr(matplotlib.axes.Axes, "axhline",
                        lambda ax, y=0, *a, **k: (hlines.append((k.get("label"), y)),
                                                  real_axh(ax, y, *a, **k))[1])
    path = fig_temperature(RunFiles(run), run / "fig_temperature.png")
    _assert_png(path, 5000)
    drawn = {label: a for label, a in lines}
    np.testing.assert_allclose(drawn["upper surface (top.csv)"][1], T_up)
    np.testing.assert_allclose(drawn["lower surface (top_lower.csv)"][1], T_lo)
    np.testing.assert_allclose(drawn["heat flux to the upper roll"][1], q_up / 1e6)
    np.testing.assert_allclose(drawn["heat flux to the lower roll"][1], q_lo / 1e6)
    assert ("exit lower surface 1190.0 K", 1190.0) in hlines
    assert ("exit upper surface 1200.0 K", 1200.0) in hlines
