"""hotroll: finite-element simulation of hot flat rolling (Touloupoulos 2020 scheme and beyond)."""

__version__ = "0.1.0"
