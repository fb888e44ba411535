"""Temperature of the strip (issue 16; beyond the report: Touloupoulos 2020 has no temperature).

``properties``: the thermal data and their validation; ``field``: the steady (Eulerian) and the
moving-mesh (Lagrangian) heat equation on the strip mesh, the heat balance and face means;
``interpass``: the strip's cooling through its thickness between two stands (issue 17).
"""
from .field import SIGMA_SB, SolveInfo, TemperatureField
from .properties import ThermalBoundary, ThermalInputError, ThermalProperties

__all__ = ["SIGMA_SB", "SolveInfo", "TemperatureField", "ThermalBoundary", "ThermalInputError",
           "ThermalProperties"]
