"""The 3D strip's flow solve over MPI ranks (issue 53; ``fem/mirror.py``).

Every rank holds the serial ``Spread3D`` (its mesh, surfaces, carried fields and figures: the
same on every rank); its Newton's residual, Jacobian and linear solves run on the strip's mesh
distributed over the ranks, a second form built there by ``Spread3D.make_form`` on mirrored
fields: the mesh's displacement, the contact indicator, the 2D pass's fields in every layer
that the flow stress reads, the carried strain and entry temperature. ``sync`` copies them
and the form's Parameters over after every update of the surfaces (``Spread3D._round``);
Newton's iterate crosses at every call (``fem/mirror.MirroredSystem``).
"""
from __future__ import annotations

from types import SimpleNamespace

from hotroll.fem import amg
from hotroll.fem.mirror import FieldMirror, MirroredSystem, distribute


class _MirroredCopy:
    """A ``LayerCopy`` whose 3D fields (``scalar``) are mirrored onto the distributed mesh."""

    def __init__(self, copy, fields: FieldMirror):
        self.copy, self.fields = copy, fields

    def scalar(self, gf2d):
        return self.fields.mirror(self.copy.scalar(gf2d))


class DistributedFlow:
    """The flow solve of the serial ``Spread3D`` ``s3`` over the ranks of ``comm`` (module
    docstring): ``system`` is Newton's."""

    def __init__(self, s3, comm):
        if amg.NAME in s3.form.nonlinear.linear_solvers[:1]:
            raise ValueError(f"linear_solver = {amg.NAME!r} does not run over MPI ranks (its "
                             "AMG is scipy's, on one process): a direct solver's name")
        self.s3, self.comm = s3, comm
        self.mesh = distribute(s3.mesh, comm)
        fields = self.fields = FieldMirror(s3.mesh, self.mesh, comm)
        self.disp = fields.mirror(s3.disp)
        self.mesh.SetDeformation(self.disp)

        def carried(field):
            return None if field is None else SimpleNamespace(gf=fields.mirror(field.gf))

        self.form = s3.make_form(self.mesh, _MirroredCopy(s3.copy, fields),
                                 carried(s3.strain), carried(s3.cooling))
        fields.mirror(s3.form.chi, self.form.chi)
        self.form.nonlinear.linear_solvers = s3.form.nonlinear.linear_solvers
        self.system = MirroredSystem(s3.form.nonlinear, self.form.nonlinear, comm)
        self.sync()

    def sync(self) -> None:
        """The serial form's data copied over: its Parameters, the mirrored fields, the
        displacement (the mesh's deformation set again)."""
        for name in self.form.PARAMETERS:
            getattr(self.form, name).Set(getattr(self.s3.form, name).Get())
        self.fields.sync()
        self.mesh.SetDeformation(self.disp)

    def restart(self) -> None:
        """The friction dual's restart (``FrictionDual.restart``) as the serial form's."""
        if self.form.friction_dual is not None:
            self.form.friction_dual.restart()
