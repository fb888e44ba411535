"""What a solved pass becomes: summary figures with their units, profiles, the run directory
(CSV, JSON, VTK, NPZ), figures and the HTML report. Imports: solvers and below."""
