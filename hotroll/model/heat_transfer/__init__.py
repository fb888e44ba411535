"""Heat-transfer laws at the strip's surface: the interface (``base.py``), one module per law
and the registry that the case file's ``[thermal] contact_law`` and ``surface_law`` select from
(``registry.py``). A new law: its module (the law and its ``register(HeatTransferSpec(...))``),
a line below, its test and a line in docs/theory.md."""
# registration order = the order the case file's help lists them (the default first)
from hotroll.model.heat_transfer import constant_conductance  # noqa: F401  # isort: skip
from hotroll.model.heat_transfer import convection_radiation  # noqa: F401  # isort: skip
from hotroll.model.heat_transfer.base import KINDS, HeatTransferLaw
from hotroll.model.heat_transfer.constant_conductance import ConstantConductance
from hotroll.model.heat_transfer.convection_radiation import SIGMA_SB, ConvectionRadiation
from hotroll.model.heat_transfer.registry import (
    HEAT_TRANSFER_LAWS,
    HeatTransferSpec,
    laws_of,
    register,
)

__all__ = ["HEAT_TRANSFER_LAWS", "KINDS", "SIGMA_SB", "ConstantConductance", "ConvectionRadiation",
           "HeatTransferLaw", "HeatTransferSpec", "laws_of", "register"]
