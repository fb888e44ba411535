"""The algorithms: Newton and Picard, the direct steady solver, the report's time stepping,
the couplings (a_f, free surface, strain, temperature), warm starts. Imports: fem and below."""
