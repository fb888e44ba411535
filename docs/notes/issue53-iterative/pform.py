from ngsolve import dx, ds, InnerProduct, specialcf, Preconditioner, BilinearForm
from hotroll.fem.forms import strain_rate
from hotroll.fem.primal_dual import symmetric_tensor, symmetric_components
def precond_form(f3, gf, cmul=1.0, cp=1.0, parts='vfbm'):
    (u, p, lam), (v, q, xi) = f3.fes.TnT()
    g = f3.tangent_points.gf
    a = symmetric_tensor([g[2 + k] for k in range(len(symmetric_components(3)))], 3)
    eu, ev = strain_rate(u), strain_rate(v)
    dual = f3._dual_cf
    rank = 0.5 * (InnerProduct(a, eu) * InnerProduct(dual, ev) + InnerProduct(dual, eu) * InnerProduct(a, ev))
    mu0 = f3.mu_ref if 'c' in parts else g[0]
    vol = mu0 * InnerProduct(eu, ev) + cp * p * q / g[0]
    if 't' in parts: vol = vol + g[1] * rank
    gu, gp, glam = gf.components
    kf = f3.chi * f3.friction_coefficient(gu, lam=glam)
    from hotroll.fem.penalties import _elements_on
    from ngsolve import FacetFESpace, GridFunction, BND
    ind = GridFunction(FacetFESpace(f3.mesh, order=0))
    for el in f3.mesh.Elements(BND):
        if el.mat in f3.MULTIPLIER_ON.split("|"):
            ind.vec[ind.space.GetDofNrs(el)[0]] = 1.0
    eb = dx(element_boundary=True, definedonelements=_elements_on(f3.mesh, f3.MULTIPLIER_ON))
    P = BilinearForm(f3.fes, symmetric=False)
    P += vol * dx(intrules=f3.dual.intrules)
    if 'f' not in parts: kf = 0
    if 'F' in parts:
        P += f3.friction_tangent(gu, u, v, None, glam) * eb
    else:
        P += kf * InnerProduct(f3.tangential(u), f3.tangential(v)) * eb
    if 'b' in parts:
        from ngsolve import IfPos, x as X
        def indicator(regions):
            import re
            pat = re.compile(f"^({regions})$")
            g = GridFunction(FacetFESpace(f3.mesh, order=0))
            for el in f3.mesh.Elements(BND):
                if pat.match(el.mat):
                    g.vec[g.space.GetDofNrs(el)[0]] = 1.0
            return g, dx(element_boundary=True, definedonelements=_elements_on(f3.mesh, regions))
        n, t = f3.roll_frame()
        gam_s = f3.penalties.surface(X, f3.rp.soft_zone)
        inlet = f3.inlet_penalty(gu, gu) * v[0]
        outlet = f3.outlet_penalty(gu, gu) * v[0]
        free_ = IfPos(X - f3.x_split, outlet, inlet)
        for reg, term in (("top|arc|exit", (1.0 - f3.chi) * free_), ("in", inlet), ("out", outlet + gam_s * gu[1] * v[1])):
            ind_r, eb_r = indicator(reg)
            P += (ind_r * term).Diff(gu, u) * eb_r
    if 'm' in parts: P += cmul * f3._lam * f3._lam * specialcf.mesh_size / f3.mu_ref * lam * xi * ind * eb
    return P

