"""Taylor-Hood P2/P1 spaces (report (3.4), l = k - 1 for inf-sup stability)."""
from __future__ import annotations


def taylor_hood(mesh, dirichletx: str = "", dirichlety: str = "sym", order: int = 2):
    """Velocity VectorH1(order) x pressure H1(order - 1), component-wise Dirichlet regions."""
    from ngsolve import H1, VectorH1

    V = VectorH1(mesh, order=order, dirichletx=dirichletx, dirichlety=dirichlety)
    Q = H1(mesh, order=order - 1)
    return V * Q
