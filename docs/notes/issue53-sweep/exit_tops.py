"""The bundled narrow bar's top per width level past the contact (docs/notes/issue53-sweep.md, flag 3): each
level's contact start and end, and the mid-width and edge levels' top y, its gap to the roll and u_y
along x. Reads docs/notes/issue53-trace-flux/narrow_bar_fluxes.py's set-up (as /tmp/mb/diag.py at the time)."""
import sys
sys.argv = [sys.argv[0]]
exec(open(__import__("pathlib").Path(__file__).resolve().parents[1] / "issue53-trace-flux" / "narrow_bar_fluxes.py").read().split("m = s3.mesh")[0])
rp = run.problem.rp
tops = s3.tops
cx, cy = rp.centre
print("gap half (mm)", rp.half_exit * 1e3, "axis x (mm)", cx * 1e3)
print("contact starts (mm from axis)", np.round((tops.contact_starts() - cx) * 1e3, 3))
if s3.ends is not None:
    print("contact ends (mm from axis)", np.round((s3.ends.ends() - cx) * 1e3, 3))
for k in (0, len(s3.z) - 1):
    xy, v, uz, z = tops._level(k)
    o = np.argsort(xy[:, 0])
    xs, ys, vy = xy[o, 0], xy[o, 1], v[o, 1]
    roll_y = cy - np.sqrt(np.maximum(rp.radius**2 - (xs - cx)**2, 0.0))
    sel = np.flatnonzero(xs > cx - 0.012)
    print("level", k, "z (mm)", s3.z[k] * 1e3)
    for i in sel[::2][:25]:
        print(f"  x-axis {(xs[i]-cx)*1e3:8.3f} mm  y {ys[i]*1e3:8.4f} mm  y - roll {(ys[i]-roll_y[i])*1e6:+9.2f} um  u_y {vy[i]:+.4e}")
