"""A case run to its files, and what is built of runs: sweeps, slab comparisons, pass
schedules, studies on dask, the resource estimate. Imports: results and below."""
