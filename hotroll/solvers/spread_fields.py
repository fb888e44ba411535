"""The flow stress a 3D strip takes from its solved 2D pass (issue 53): the temperature is the
2D pass's in every width layer, plus the entry temperature's difference across the width
where one is given (``cooled_flow_stress``); the strain is the 2D pass's in every layer
(``frozen_flow_stress``) or carried through the 3D flow (``strain_3d``: the edge's own).

A strain- or temperature-dependent flow stress enters the form as its consistency
K(eps, T) / K_ref and, where the law's rate exponent depends on the temperature (Hensel-Spittel
m8), the offset m(T) - m_ref (``fem/rolling_form.py``). Here each 2D field they are made of (the
strain at the vertices, H1; the elements' mean temperature, the ratio and the offset per
element, L2 of order 0) is copied onto the extrusion exactly (``LayerCopy.scalar``) and the
same expression is built of the copies: with the edge held, the 3D form is the 2D one in every
layer (the consistency check). With a free edge the strain is transported through the 3D
strip (``Spread3D(strain="transported")``, the default). What this leaves out: the bite's own
cooling through the lateral face (the flow stress there takes the 2D pass's temperature plus
the entry's difference across the width, carried).
"""
from __future__ import annotations

from hotroll.solvers.thermal_feedback import rate_exponent_varies


def strain_3d(run, copy, mesh3d):
    """The strain carried through the 3D strip (``fem/strain.py``: v . grad eps = edot, SUPG
    P1, the inlet's strain the 2D pass's), its start the 2D pass's strain in every layer; None
    where the flow stress takes no strain (the 2D thermal coupling's per-element ratio is
    that case: it exists only without a strain field)."""
    from hotroll.fem.strain import StrainField

    if run.strain is None:
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


def cooled_flow_stress(run, copy, theta, strain3d=None) -> tuple:
    """(consistency, rate offset) as ``frozen_flow_stress``, the temperature the 2D pass's
    plus ``theta`` (a ``fem/strain.CarriedField``: the entry temperature's difference across
    the width from mid-width's, carried through the bite): K(eps, T + theta) / K_ref and
    m(T + theta) - m_ref (None where the law's exponent does not depend on T). T: the
    plate's (isothermal) or the 2D pass's elements' mean (``[thermal]``)."""
    problem, th = run.problem, run.thermal
    if th is None:
        flow, K_ref, m_ref = problem.flow_stress, problem.material.K, problem.material.m
        T, entry = problem.temperature + theta.gf, problem.entry_strain
    else:
        flow, K_ref, m_ref = th.flow, th.K_ref, th.m_ref
        T, entry = copy.scalar(th.T_mean) + theta.gf, th.entry_strain
    if flow is None:
        raise ValueError("an entry temperature across the width needs a temperature-dependent "
                         "flow stress law (a grade's)")
    if strain3d is not None:
        eps = strain3d.gf
    elif run.strain is not None:
        eps = copy.scalar(run.strain.gf)
    else:
        eps = entry
    return flow.consistency(eps, T) / K_ref, (flow.rate_exponent(T) - m_ref
                                              if rate_exponent_varies(flow) else None)
