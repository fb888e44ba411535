"""Run one sweep case and print the 3D pass's fluxes through the entry, the exit and the
lateral faces (m^3/s, whole strip) that the summary folds into spread_mass_flux_error.
usage: PYTHONPATH=. .venv/bin/python docs/notes/issue53-sweep/fluxes.py CASE.toml OUT"""
import sys
from pathlib import Path

import hotroll.results.run_summary as rs
from hotroll.api import solve
from hotroll.config.case import load_case

_orig = rs.spread_figures


def _dump(case, sp, roll_force):
    fin, fout, fedge = sp.flux_in, sp.flux_out, sp.flux_edge
    print(f"FLUX in {fin:.9e} out {fout:.9e} edge {fedge:.9e} | (out-in)/in {(fout - fin) / fin:.3e}"
          f" edge/in {fedge / fin:.3e} (out+edge-in)/in {(fout + fedge - fin) / fin:.3e}", flush=True)
    return _orig(case, sp, roll_force)


rs.spread_figures = _dump
solve(load_case(sys.argv[1]), Path(sys.argv[2]))
