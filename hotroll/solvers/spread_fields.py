"""The flow stress a 3D strip takes from its solved 2D pass (issue 53): the temperature is the
2D pass's, the same in every width layer (frozen across the width); the strain too
(``frozen_flow_stress``), or carried through the 3D flow (``strain_3d``: the edge's own).

A strain- or temperature-dependent flow stress enters the form as its consistency
K(eps, T) / K_ref and, where the law's rate exponent depends on the temperature (Hensel-Spittel
m8), the offset m(T) - m_ref (``fem/rolling_form.py``). Here each 2D field they are made of (the
strain at the vertices, H1; the elements' mean temperature, the ratio and the offset per
element, L2 of order 0) is copied onto the extrusion exactly (``LayerCopy.scalar``) and the
same expression is built of the copies: with the edge held, the 3D form is the 2D one in every
layer (the consistency check). With a free edge the strain is transported through the 3D
strip (``Spread3D(strain="transported")``, the default). What this leaves out: near the free
edge the temperature differs from mid-width (edge cooling with ``[thermal]``); the flow stress
there takes mid-width's temperature, and with the 2D thermal coupling's per-element ratio
its strain too.
"""
from __future__ import annotations


def strain_3d(run, copy, mesh3d):
    """The strain carried through the 3D strip (``fem/strain.py``: v . grad eps = edot, SUPG
    P1, the inlet's strain the 2D pass's), its start the 2D pass's strain in every layer; None
    where the flow stress takes no strain, or takes it inside the 2D thermal coupling's
    per-element ratio (then frozen across the width)."""
    import ngsolve as ng

    from hotroll.fem.strain import StrainField

    if run.strain is None:
        return None
    if run.thermal is not None and isinstance(run.thermal.consistency(), ng.GridFunction):
        return None
    p = run.problem
    field = StrainField(mesh3d, p.entry_strain, profile=p.strain_profile)
    copy.copy(run.strain.space, run.strain.values, field.space, field.values)
    return field


def frozen_flow_stress(run, copy, strain3d=None) -> tuple:
    """(consistency, rate offset) for ``RollingForm3D`` on ``copy``'s extrusion (a float or a
    CoefficientFunction; None: the reference exponent) from the solved 2D ``SteadyRun``
    ``run``: its strain field (``run.strain``) and its temperature coupling
    (``run.thermal``, solvers/thermal_coupling.py), carried into every layer; ``strain3d``:
    the strain carried through the 3D strip (``strain_3d``) in place of the 2D one."""
    import ngsolve as ng

    problem, th = run.problem, run.thermal
    strain = None if run.strain is None else copy.scalar(run.strain.gf)
    if strain3d is not None:
        strain = strain3d.gf
    if th is None:
        if strain is None:
            return 1.0, None
        return problem.flow_stress.consistency(strain, problem.temperature) / problem.material.K, None
    k = th.consistency()
    if isinstance(k, ng.GridFunction):          # the ratio per element
        k = copy.scalar(k)
    elif th.flow is not None:                   # K(eps, T_mean) of the strain field
        eps = strain if strain is not None else th.entry_strain
        k = th.flow.consistency(eps, copy.scalar(th.T_mean)) / th.K_ref
    offset = th.rate_offset()
    return k, (None if offset is None else copy.scalar(offset))
