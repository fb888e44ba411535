"""Friction laws on the roll contact: the interface (``base.py``), one module per law and the
registry the case file's ``[friction] law`` selects from (``registry.py``). A new law: its
module (the law and its ``register(FrictionSpec(...))``), a line below, its test and a line in
docs/theory.md."""
# registration order = the order the case file's help lists them: the report's law first
from hotroll.model.friction import viscoplastic  # noqa: F401  # isort: skip
from hotroll.model.friction import coulomb, tresca  # noqa: F401  # isort: skip
from hotroll.model.friction.base import (
    FrictionLaw,
    is_cf,
    smooth_minimum,
    smooth_minimum_partials,
    smooth_positive_part,
    smooth_positive_part_partials,
)
from hotroll.model.friction.coulomb import CoulombFriction
from hotroll.model.friction.registry import FRICTION_LAWS, FrictionSpec, register
from hotroll.model.friction.tresca import TrescaFriction
from hotroll.model.friction.viscoplastic import ViscoplasticFriction

__all__ = ["FRICTION_LAWS", "CoulombFriction", "FrictionLaw", "FrictionSpec", "TrescaFriction",
           "ViscoplasticFriction", "is_cf", "register", "smooth_minimum", "smooth_minimum_partials",
           "smooth_positive_part", "smooth_positive_part_partials"]
