"""The rolling process: roll and plate geometry, contact detection."""
from .geometry import RollPass

__all__ = ["RollPass"]
