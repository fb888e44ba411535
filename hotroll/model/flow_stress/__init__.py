"""Flow-stress laws sigma_f(strain, strain rate, temperature): the interface (``base.py``), one
module per law, and the registry the case file's ``[material] law`` selects from
(``registry.py``). A new law: its module (the law and its ``register(LawSpec(...))``), a line
below, its test and a line in docs/theory.md."""
# registration order = the order the case file's help lists them: the report's law first
from hotroll.model.flow_stress import norton_hoff  # noqa: F401  # isort: skip
from hotroll.model.flow_stress import hensel_spittel, misaka  # noqa: F401  # isort: skip
from hotroll.model.flow_stress.base import (
    CELSIUS_OFFSET,
    DEFAULT_EPS0,
    DEFAULT_STRAIN_MIN,
    LN3,
    SQRT3,
    FlowStressLaw,
    ValidityRange,
    finite,
)
from hotroll.model.flow_stress.hensel_spittel import HenselSpittel
from hotroll.model.flow_stress.misaka import Misaka
from hotroll.model.flow_stress.norton_hoff import NortonHoffStress
from hotroll.model.flow_stress.registry import FLOW_STRESS_LAWS, LAWS, LawSpec, Parameter, register

__all__ = ["CELSIUS_OFFSET", "DEFAULT_EPS0", "DEFAULT_STRAIN_MIN", "FLOW_STRESS_LAWS", "LAWS",
           "LN3", "SQRT3", "FlowStressLaw", "HenselSpittel", "LawSpec", "Misaka", "NortonHoffStress", "Parameter",
           "ValidityRange", "finite", "register"]
