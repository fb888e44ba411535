"""Physics: the material law, friction laws and the a_f estimate (report Sections 2.4, 2.6, 3.5)."""
from .friction import ViscoplasticFriction
from .friction_estimate import estimate_a_f
from .material import NortonHoff, edot_squared

__all__ = ["NortonHoff", "edot_squared", "ViscoplasticFriction", "estimate_a_f"]
