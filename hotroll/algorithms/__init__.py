"""Algorithms: nonlinear solvers (Picard (3.8), Newton), explicit time stepping (3.7)."""
