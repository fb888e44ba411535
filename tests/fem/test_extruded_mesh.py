"""The 3D strip's prism mesh (fem/extruded_mesh.py, issue 53 stage 0).

Labels: [hand] volumes, areas and normals of a box computed by hand; [analytic] a manufactured
Stokes solution on the extruded prisms and the convergence orders Taylor-Hood P2/P1 must reach
(velocity L2 O(h^3), pressure L2 O(h^2)); [id] the layers' construction rules."""
from __future__ import annotations

import math

import numpy as np
import pytest

from hotroll.fem.extruded_mesh import extrude, width_axis
from hotroll.fem.mesh import structured_triangle_mesh


def box(nx: int, ny: int, z: np.ndarray, lx: float = 2.0, ly: float = 1.0):
    return extrude(structured_triangle_mesh(np.linspace(0.0, lx, nx + 1),
                                            np.linspace(0.0, ly, ny + 1)), z)


def test_width_layers_are_thin_at_the_edge_and_grow_inwards():
    """[id] from the edge inwards: the edge layer, then x1.2 each, capped at ``largest``; the
    innermost layer at least half of the one before it; the ends exact."""
    z = width_axis(0.75, 0.01, largest=0.05)
    dz = np.diff(z)[::-1]                         # edge first
    assert z[0] == 0.0 and z[-1] == 0.75
    assert dz[0] == pytest.approx(0.01)
    for a, b in zip(dz[:-2], dz[1:-1]):
        assert b == pytest.approx(min(1.2 * a, 0.05))
    assert dz[-1] >= 0.5 * dz[-2]
    assert width_axis(0.1, 0.1).tolist() == [0.0, 0.1]
    for bad in ((0.1, 0.0), (0.1, 0.2)):
        with pytest.raises(ValueError, match="edge"):
            width_axis(*bad)


def test_a_box_has_its_volume_faces_and_outward_normals():
    """[hand] the box [0, 2] x [0, 1] x [0, 0.5] in three graded layers: volume 1, each face's
    area and its outward unit normal (integrated over the face: area times the normal)."""
    from ngsolve import Integrate, specialcf

    mesh = box(4, 2, width_axis(0.5, 0.1))
    assert mesh.ne == 8 * 2 * 4 and mesh.GetMaterials() == ("strip",)
    assert Integrate(1.0, mesh) == pytest.approx(1.0, rel=1e-12)
    n = specialcf.normal(3)
    faces = {"bottom": (1.0, (0, -1, 0)), "top": (1.0, (0, 1, 0)), "left": (0.5, (-1, 0, 0)),
             "right": (0.5, (1, 0, 0)), "zsym": (2.0, (0, 0, -1)), "edge": (2.0, (0, 0, 1))}
    assert set(mesh.GetBoundaries()) == set(faces)
    for name, (area, normal) in faces.items():
        on = mesh.Boundaries(name)
        assert Integrate(1.0, mesh, definedon=on) == pytest.approx(area, rel=1e-12)
        got = [Integrate(n[i], mesh, definedon=on) for i in range(3)]
        assert got == pytest.approx([area * c for c in normal], abs=1e-12)


def test_the_steady_strip_mesh_keeps_its_boundary_names():
    """[hand] hotroll's 2D steady strip extruded: its boundaries plus ``zsym`` and ``edge``,
    the volume its area times the half width, the extruded arc's area its length times it."""
    from ngsolve import Integrate

    from hotroll.fem.mesh import MeshSpec, build_steady_mesh
    from hotroll.model.geometry import RollPass

    rp = RollPass(0.3, 0.005, 0.004, omega=10.0, axis_x=0.0)
    m2 = build_steady_mesh(rp, 0.02, 0.02, MeshSpec(h=1e-3, fine_length=0.03), margin=0.005)
    half_width = 0.02
    mesh = extrude(m2, width_axis(half_width, 2e-3))
    assert set(mesh.GetBoundaries()) == set(m2.GetBoundaries()) | {"zsym", "edge"}
    area = Integrate(1.0, m2)
    assert Integrate(1.0, mesh) == pytest.approx(area * half_width, rel=1e-12)
    arc = Integrate(1.0, m2, definedon=m2.Boundaries("arc"))
    assert Integrate(1.0, mesh, definedon=mesh.Boundaries("arc")) == pytest.approx(
        arc * half_width, rel=1e-12)


def test_the_contacts_start_and_lateral_edge_are_named_lines():
    """[id] the elastic layer's line terms (``RollingForm3D.layer_ends``) sit on the arc's
    boundary: the 2D mesh's named ``start`` point a line across every layer, ``arc_edge`` the
    arc's segments in the last layer (z = the half width), its length the arc's; a mesh
    without an arc has neither."""
    from ngsolve import BBND, BND, Integrate

    from hotroll.fem.mesh import MeshSpec, build_steady_mesh
    from hotroll.model.geometry import RollPass

    rp = RollPass(0.3, 0.005, 0.004, omega=10.0, axis_x=0.0)
    m2 = build_steady_mesh(rp, 0.02, 0.02, MeshSpec(h=1e-3, fine_length=0.03), margin=0.005)
    (start,) = [el.vertices[0].nr for el in m2.Elements(BBND) if el.mat == "start"]
    arc = {v.nr for el in m2.Elements(BND) if el.mat == "arc" for v in el.vertices}
    z = width_axis(0.02, 2e-3)
    mesh = extrude(m2, z)
    nl, nv = len(z) - 1, m2.nv
    lines: dict[str, list[tuple[int, int]]] = {}
    for el in mesh.Elements(BBND):
        lines.setdefault(el.mat, []).append(tuple(sorted(v.nr for v in el.vertices)))
    assert sorted(lines) == ["arc_edge", "start"]
    assert sorted(lines["start"]) == [(k * nv + start, (k + 1) * nv + start) for k in range(nl)]
    assert all(a // nv == nl and b // nv == nl for a, b in lines["arc_edge"])
    assert {v - nl * nv for ab in lines["arc_edge"] for v in ab} == arc
    assert len(lines["arc_edge"]) == len(arc) - 1
    length = Integrate(1.0, mesh, BBND, definedon=mesh.BBoundaries("arc_edge"))
    assert length == pytest.approx(Integrate(1.0, m2, definedon=m2.Boundaries("arc")),
                                   rel=1e-12)
    assert not any(el.mat for el in box(2, 2, width_axis(0.5, 0.1)).Elements(BBND))


def stokes_errors(n: int) -> tuple[float, float]:
    """L2 errors of Taylor-Hood P2/P1 on the unit cube in n x n x n prism layers for the
    divergence-free u = (sin(pi x) cos(pi z) y, 0, -cos(pi x) sin(pi z) y) and
    p = cos(pi x) cos(pi y) cos(pi z) (the body force from them by the coefficient
    functions' symbolic derivatives, Diff)."""
    import ngsolve as ng
    from ngsolve import CF, cos, pi, sin, x, y, z

    from hotroll.fem.reproducible import fe_space

    mesh = extrude(structured_triangle_mesh(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1)),
                   np.linspace(0.0, 1.0, n + 1))
    # div u = 0: d/dx (sin(pi x) cos(pi z) y) + d/dz (-cos(pi x) sin(pi z) y) = 0
    ue = CF((sin(pi * x) * cos(pi * z) * y, CF(0.0), -cos(pi * x) * sin(pi * z) * y))
    pe = cos(pi * x) * cos(pi * y) * cos(pi * z)
    coords = (x, y, z)
    eps = [[0.5 * (ue[i].Diff(coords[j]) + ue[j].Diff(coords[i])) for j in range(3)]
           for i in range(3)]
    f = CF(tuple(-sum((2.0 * eps[i][j]).Diff(coords[j]) for j in range(3))
                 + pe.Diff(coords[i]) for i in range(3)))
    V = fe_space(ng.VectorH1, mesh, order=2, dirichlet=".*")
    X = V * fe_space(ng.H1, mesh, order=1) * fe_space(ng.NumberSpace, mesh)
    (u, p, lam), (v, q, mu) = X.TnT()
    a = ng.BilinearForm(X)
    a += (2.0 * ng.InnerProduct(ng.Sym(ng.grad(u)), ng.Sym(ng.grad(v))) - ng.div(u) * q - ng.div(v) * p
          + p * mu + q * lam) * ng.dx
    a.Assemble()
    lf = ng.LinearForm(X)
    lf += f * v * ng.dx
    lf.Assemble()
    gf = ng.GridFunction(X)
    gf.components[0].Set(ue, definedon=mesh.Boundaries(".*"))
    r = lf.vec.CreateVector()
    r.data = lf.vec - a.mat * gf.vec
    gf.vec.data += a.mat.Inverse(X.FreeDofs(), inverse="umfpack") * r
    uh, ph = gf.components[0], gf.components[1]
    eu = ng.sqrt(ng.Integrate(ng.InnerProduct(uh - ue, uh - ue), mesh))
    mean = ng.Integrate(pe, mesh)
    ep = ng.sqrt(ng.Integrate((ph - (pe - mean)) ** 2, mesh))
    return float(eu), float(ep)


def test_taylor_hood_on_the_prisms_converges_at_its_orders():
    """[analytic] a manufactured Stokes solution (viscosity 1, the velocity on the whole
    boundary, mean pressure 0): the L2 errors fall by 2^3 (velocity) and at least 2^2
    (pressure) per halving of the prisms. Measured (n = 2, 3, 4, 6, 8): velocity 2.73, 2.84,
    2.92, 2.96; pressure 2.94, 2.94, 2.64, 2.46."""
    (u1, p1), (u2, p2) = stokes_errors(3), stokes_errors(6)
    assert math.log2(u1 / u2) > 2.6
    assert math.log2(p1 / p2) > 1.8
    assert u2 < 1e-3


def norton_hoff_errors(n: int, m: float = 0.3) -> tuple[float, float]:
    """L2 errors of the Norton-Hoff volume form (fem/forms.py: norton_hoff_volume, the one the
    rolling form integrates) on the unit cube in n x n x n prism layers, Newton to 1e-12, for
    the manufactured velocity and pressure of ``stokes_errors`` (the body force from the law's
    viscosity mu(edot^2) of (2.21) by the coefficient functions' symbolic derivatives)."""
    import ngsolve as ng
    from ngsolve import CF, cos, pi, sin, x, y, z

    from hotroll.fem.forms import norton_hoff_volume, strain_rate
    from hotroll.fem.reproducible import fe_space
    from hotroll.model.material import NortonHoff, edot_squared

    law = NortonHoff(1.0, m, 0.5)
    mesh = extrude(structured_triangle_mesh(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1)),
                   np.linspace(0.0, 1.0, n + 1))
    ue = CF((sin(pi * x) * cos(pi * z) * y, CF(0.0), -cos(pi * x) * sin(pi * z) * y))
    pe = cos(pi * x) * cos(pi * y) * cos(pi * z)
    coords = (x, y, z)
    grad_e = [[ue[i].Diff(coords[j]) for j in range(3)] for i in range(3)]
    eps = CF(tuple(0.5 * (grad_e[i][j] + grad_e[j][i]) for i in range(3) for j in range(3)),
             dims=(3, 3))
    mu = law.viscosity(edot_squared(eps))
    f = CF(tuple(-sum((mu * eps[i, j]).Diff(coords[j]) for j in range(3)) + pe.Diff(coords[i])
                 for i in range(3)))
    V = fe_space(ng.VectorH1, mesh, order=2, dirichlet=".*")
    X = V * fe_space(ng.H1, mesh, order=1) * fe_space(ng.NumberSpace, mesh)
    (u, p, lam), (v, q, nu) = X.TnT()
    a = ng.BilinearForm(X)
    a += (norton_hoff_volume(law, m, u, p, u, v, q) + p * nu + q * lam) * ng.dx
    a += -f * v * ng.dx
    gf = ng.GridFunction(X)
    gf.components[0].Set(ue, definedon=mesh.Boundaries(".*"))
    r, du = gf.vec.CreateVector(), gf.vec.CreateVector()
    for _ in range(30):
        a.Apply(gf.vec, r)
        a.AssembleLinearization(gf.vec)
        du.data = a.mat.Inverse(X.FreeDofs(), inverse="umfpack") * r
        gf.vec.data -= du
        if np.abs(du.FV().NumPy()).max() < 1e-12:
            break
    else:
        pytest.fail(f"Newton did not converge on n = {n}")
    uh, ph = gf.components[0], gf.components[1]
    assert float(np.abs(strain_rate(uh)[0, 0](mesh(0.5, 0.5, 0.5)))) < 10.0
    eu = ng.sqrt(ng.Integrate(ng.InnerProduct(uh - ue, uh - ue), mesh))
    mean = ng.Integrate(pe, mesh)
    ep = ng.sqrt(ng.Integrate((ph - (pe - mean)) ** 2, mesh))
    return float(eu), float(ep)


def test_the_norton_hoff_volume_form_on_the_prisms_converges_at_its_orders():
    """[analytic] the rolling form's Norton-Hoff volume term (m = 0.3, eps0 = 0.5, K = 1) with
    a manufactured solution: Newton converges and the L2 errors fall at Taylor-Hood's orders
    (velocity > 2.6, pressure > 1.8 per halving). Measured (n = 2, 3, 4, 6): velocity 2.00,
    3.82, 3.00; pressure 3.36, 2.85, 2.39 (3 -> 6: 3.34 and 2.58)."""
    (u1, p1), (u2, p2) = norton_hoff_errors(3), norton_hoff_errors(6)
    assert math.log2(u1 / u2) > 2.6
    assert math.log2(p1 / p2) > 1.8


def test_a_field_of_its_own_in_each_layer_is_linear_in_z_between_them():
    """[hand] P2 fields f_k = (1 + k^2) g in the layers z_k (g a P2 field of the 2D mesh): the
    3D field is f_k on each layer and, between two, their linear interpolation in z, at
    points inside the prisms (exact: a layer's shape functions are the triangle's times the
    layer's hat in z); ``take`` reads each layer back."""
    import ngsolve as ng

    from hotroll.fem.extruded_mesh import LayerCopy
    from hotroll.fem.reproducible import fe_space

    m2 = structured_triangle_mesh(np.linspace(0.0, 2.0, 5), np.linspace(0.0, 1.0, 3))
    z = np.array([0.0, 0.3, 0.5])
    m3 = extrude(m2, z)
    s2, s3 = fe_space(ng.H1, m2, order=2), fe_space(ng.H1, m3, order=2)
    g = ng.GridFunction(s2)
    g.Set(ng.sin(ng.x) * ng.y * ng.y + ng.x * ng.y)
    f = [(1.0 + k * k) * g.vec.FV().NumPy() for k in range(3)]
    copy = LayerCopy(m2, m3)
    h = ng.GridFunction(s3)
    copy.per_layer(s2, f, s3, h.vec.FV().NumPy())
    for px, py in ((0.3, 0.2), (1.7, 0.65)):
        gv = g(m2(px, py))
        for k, zk in enumerate(z):
            assert h(m3(px, py, zk)) == pytest.approx((1.0 + k * k) * gv, rel=1e-12, abs=1e-14)
        zm = 0.4                                   # 1/2 of the way from z_1 to z_2
        assert h(m3(px, py, zm)) == pytest.approx(0.5 * (2.0 + 5.0) * gv, rel=1e-12, abs=1e-14)
    back = np.zeros(s2.ndof)
    for k in range(3):
        copy.take(k, s3, h.vec.FV().NumPy(), s2, back)
        assert back == pytest.approx(f[k], rel=1e-14, abs=1e-15)
    with pytest.raises(ValueError, match="2 fields for 3 layers"):
        copy.per_layer(s2, f[:2], s3, h.vec.FV().NumPy())


def test_with_the_layers_z_a_field_quadratic_in_z_is_carried_exactly():
    """[hand] fields f_k = a + b z_k + c z_k^2 (a, b, c P2 fields of the 2D mesh) on unequal
    layers: with ``z`` the 3D field equals a + b z + c z^2 everywhere (L2 error at rounding;
    linear between layers it is off by c (z - z_k)(z - z_k+1)); ``where`` keeps a DOF linear;
    at equal spacing the midpoint where two quadratics exist is the cubic's."""
    import ngsolve as ng

    from hotroll.fem.extruded_mesh import LayerCopy, spine_bubbles
    from hotroll.fem.reproducible import fe_space

    m2 = structured_triangle_mesh(np.linspace(0.0, 2.0, 5), np.linspace(0.0, 1.0, 3))
    z = np.array([0.0, 0.7, 1.1, 1.3, 1.4])
    m3 = extrude(m2, z)
    s2, s3 = fe_space(ng.H1, m2, order=2), fe_space(ng.H1, m3, order=2)
    g = ng.GridFunction(s2)

    def exact(zz):
        return (ng.x * ng.x + ng.y) * (1.0 + 2.0 * zz - 3.0 * zz * zz) + ng.x * ng.y * zz

    f = []
    for zk in z:
        g.Set(exact(float(zk)))
        f.append(g.vec.FV().NumPy().copy())
    copy, h = LayerCopy(m2, m3), ng.GridFunction(s3)
    copy.per_layer(s2, f, s3, h.vec.FV().NumPy(), z=z)
    assert ng.Integrate((h - exact(ng.z)) ** 2, m3, order=8) ** 0.5 < 1e-13
    copy.per_layer(s2, f, s3, h.vec.FV().NumPy())
    assert ng.Integrate((h - exact(ng.z)) ** 2, m3, order=8) ** 0.5 > 1e-2
    # only a mask's DOFs curved: the others linear in z
    keep = np.zeros(s2.ndof, dtype=bool)
    copy.per_layer(s2, f, s3, h.vec.FV().NumPy(), z=z, where=keep)
    lin = h.vec.FV().NumPy().copy()
    copy.per_layer(s2, f, s3, h.vec.FV().NumPy())
    assert lin == pytest.approx(h.vec.FV().NumPy(), abs=0.0)
    # the midpoint value the bubbles give (the chord's middle less 1/8 of the bubble): at
    # equal spacing the cubic's where two quadratics exist, z^3 exact inside, not at the ends
    zu = np.arange(5.0)
    cube = (zu ** 3)[:, None]
    mid = (0.5 * (cube[:-1] + cube[1:]) - 0.125 * spine_bubbles(zu, cube))[:, 0]
    zm = 0.5 * (zu[:-1] + zu[1:])
    assert mid[1:-1] == pytest.approx(zm[1:-1] ** 3, rel=1e-14)
    assert abs(mid[0] - zm[0] ** 3) > 0.1 and abs(mid[-1] - zm[-1] ** 3) > 0.1


def test_the_bubbles_skip_ill_trios_and_keep_flat_layers_linear():
    """[hand] ``spine_bubbles`` on values per level (midpoint value = chord's middle less 1/8
    of the bubble): a layer 20 times wider than its neighbours takes no trio whose weights'
    magnitudes sum above WEIGHT_LIMIT (the neighbours' gradient is not extrapolated across
    it: the one-layer interior of an edge zone leaked 0.9 % of the inflow so) and stays
    linear; ``flat`` keeps the first layers linear, the others as without it."""
    from hotroll.fem.extruded_mesh import WEIGHT_LIMIT, spine_bubbles

    def mid(z, v, **kw):
        return 0.5 * (v[:-1] + v[1:]) - 0.125 * spine_bubbles(z, v[:, None], **kw)[:, 0]

    w = np.array([0.0, 1.0, 1.05, 1.1])
    trio = [np.prod([(0.5 - w[j]) / (w[i] - w[j]) for j in range(3) if j != i])
            for i in range(3)]
    assert sum(abs(t) for t in trio) > WEIGHT_LIMIT
    f = np.array([0.0, 1.0, 1.3, 1.5])        # steep between the thin layers
    assert mid(w, f)[0] == pytest.approx(0.5, abs=1e-14)                 # linear
    assert mid(w, w ** 2)[1:] == pytest.approx((0.5 * (w[1:-1] + w[2:])) ** 2, rel=1e-13)
    z = np.array([0.0, 0.3, 0.5, 0.65, 0.75])
    zm = 0.5 * (z[:-1] + z[1:])
    assert mid(z, z ** 2) == pytest.approx(zm ** 2, rel=1e-13)
    flat = mid(z, z ** 2, flat=1)
    assert flat[0] == pytest.approx(0.5 * z[1] ** 2, rel=1e-14)
    assert flat[1:] == pytest.approx(zm[1:] ** 2, rel=1e-13)


def test_a_scalar_field_is_the_same_in_every_layer_h1_and_per_element():
    """[hand] ``LayerCopy.scalar``: a P2 field and a P0 one (each triangle its own value) carried
    onto the extrusion equal the 2D field at the same (x, y) in every layer (the prisms of
    layer k are numbered k * n_triangles + t); an H1 field of order 3 is refused by name."""
    import ngsolve as ng

    from hotroll.fem.extruded_mesh import LayerCopy
    from hotroll.fem.reproducible import fe_space

    m2 = structured_triangle_mesh(np.linspace(0.0, 2.0, 5), np.linspace(0.0, 1.0, 3))
    m3 = extrude(m2, np.array([0.0, 0.3, 0.5, 1.1]))
    copy = LayerCopy(m2, m3)
    p2 = ng.GridFunction(fe_space(ng.H1, m2, order=2))
    p2.Set(ng.sin(ng.x) * ng.y * ng.y + ng.x * ng.y)
    p0 = ng.GridFunction(fe_space(ng.L2, m2, order=0))
    p0.vec.FV().NumPy()[:] = 1.0 + np.arange(m2.ne) ** 2
    for g in (p2, p0):
        g3 = copy.scalar(g)
        for px, py in ((0.3, 0.2), (1.7, 0.65), (0.95, 0.9)):
            for pz in (0.1, 0.45, 0.8):
                assert g3(m3(px, py, pz)) == pytest.approx(g(m2(px, py)), rel=1e-12)
    with pytest.raises(ValueError, match="H1 of order 3"):
        copy.scalar(ng.GridFunction(fe_space(ng.H1, m2, order=3)))


def test_the_strain_transport_is_exact_on_the_prisms_for_a_strain_linear_in_x():
    """[analytic] the strain's steady transport (fem/strain.py, SUPG P1) on the extruded
    prisms: the flow u = (U, -a y, a z) (divergence free, its strain rate diag(0, -a, a),
    edot = 2a/sqrt(3) everywhere) carries eps = eps0 + edot (x - x_in) / U, which P1 holds
    and SUPG is consistent with, so the discrete strain is that to rounding (the inlet
    "left" at x_in = 0, eps0 = 0.1)."""
    import ngsolve as ng

    from hotroll.fem.strain import StrainField

    mesh = box(6, 3, width_axis(0.5, 0.1))
    U, a, eps0 = 2.0, 0.3, 0.1
    field = StrainField(mesh, eps0, inlet="left")
    u = ng.GridFunction(ng.VectorH1(mesh, order=1))        # linear: held exactly
    u.Set(ng.CF((U, -a * ng.y, a * ng.z)))
    change = field.transport(u)
    assert change > 0.0
    X = np.array([v.point for v in mesh.vertices])
    exact = eps0 + 2.0 * a / math.sqrt(3.0) * X[:, 0] / U
    assert np.max(np.abs(field.values - exact)) <= 1e-12
