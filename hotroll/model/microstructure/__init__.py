"""Austenite microstructure through a schedule (issue 33): the interface (``base.py``), one
module per published parameter set, the registry (``registry.py``), the JMAK integration along
a temperature history (``jmak.py``) and the softening between two passes (``softening.py``).
A new set: its module (the set and its ``register``), a line below, its test and a line in
docs/theory.md 1g."""
from hotroll.model.microstructure import hodgson_gibbs  # noqa: F401  # isort: skip
from hotroll.model.microstructure.base import GrowthLaw, PowerTerm, RecrystallisationSet
from hotroll.model.microstructure.registry import SETS, UnknownSet, get_set, register, sets_for

__all__ = ["SETS", "GrowthLaw", "PowerTerm", "RecrystallisationSet", "UnknownSet", "get_set",
           "register", "sets_for"]
