# source me: MPI for hotroll's venv without touching it
export PYTHONPATH=/tmp/mpiprefix/lib/python3.11/site-packages
export LD_LIBRARY_PATH=/tmp/mpiprefix/lib
export PATH=/tmp/mpiprefix/bin:$PATH
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
PY=/work/main/.venv/bin/python
