"""quenchsim: oil-quench simulation of steel bearing rings and bearing-analysis solvers."""

import os

# The solvers work on arrays of ~1e3-1e5 values where a threaded BLAS costs more in thread start-up
# than it gains (measured: a 14k dot product 2.2 ms threaded vs 3.4 us single-threaded on 2 loaded
# cores). Users who want threads can still set these before importing quenchsim.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

__version__ = "0.1.0"
