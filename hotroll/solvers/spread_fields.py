"""The flow stress a 3D strip takes from its solved 2D pass (issue 53): the strain and the
temperature are the 2D pass's, the same in every width layer (frozen across the width).

A strain- or temperature-dependent flow stress enters the form as its consistency
K(eps, T) / K_ref and, where the law's rate exponent depends on the temperature (Hensel-Spittel
m8), the offset m(T) - m_ref (``fem/rolling_form.py``). Here each 2D field they are made of (the
strain at the vertices, H1; the elements' mean temperature, the ratio and the offset per
element, L2 of order 0) is copied onto the extrusion exactly (``LayerCopy.scalar``) and the
same expression is built of the copies: with the edge held, the 3D form is the 2D one in every
layer (the consistency check). What this leaves out: near the free edge the strain and the
temperature differ from mid-width (more strain where the strip spreads, edge cooling with
``[thermal]``); the flow stress there is mid-width's.
"""
from __future__ import annotations


def frozen_flow_stress(run, copy) -> tuple:
    """(consistency, rate offset) for ``RollingForm3D`` on ``copy``'s extrusion (a float or a
    CoefficientFunction; None: the reference exponent) from the solved 2D ``SteadyRun``
    ``run``: its strain field (``run.strain``) and its temperature coupling
    (``run.thermal``, solvers/thermal_coupling.py), carried into every layer."""
    import ngsolve as ng

    problem, th = run.problem, run.thermal
    strain = None if run.strain is None else copy.scalar(run.strain.gf)
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
