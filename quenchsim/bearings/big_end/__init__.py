"""Planar dynamics of a connecting-rod big-end needle roller bearing (reference section 6).

Public API: :func:`load_case`, :func:`simulate`, :func:`run_statistics`, :func:`write_csv`,
:func:`plot_run`; contact laws in :mod:`contact`, :mod:`ehl`, :mod:`journal`; mechanism in :mod:`engine`.
"""

from quenchsim.bearings.big_end.case import BigEndCase, load_case
from quenchsim.bearings.big_end.output import plot_run, write_csv
from quenchsim.bearings.big_end.simulate import RunResult, simulate
from quenchsim.bearings.big_end.statistics import run_statistics

__all__ = ["BigEndCase", "RunResult", "load_case", "plot_run", "run_statistics", "simulate", "write_csv"]
