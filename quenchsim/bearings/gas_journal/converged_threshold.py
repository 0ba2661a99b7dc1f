"""Grid-converged linear whirl threshold: the linear threshold on successively finer grids, Richardson's estimate.

The threshold of one grid carries that grid's discretisation error, and for grooved members it is large: rotor
A-1 (20 grooves) at Lambda 1 gives Mbar 8.82 / 10.54 / 11.30 / 11.61 on levels 3 / 4 / 5 / 6
(reports/bearings_gas_stability.md). :func:`converged_linear_threshold` computes the linear threshold
(linear_stability.linear_threshold) on levels ``first_level``, ``first_level + 1``, ... (each level halves the
spacing) and, from the last three, Richardson's extrapolation (L. F. Richardson, Phil. Trans. R. Soc. A 210
(1911) 307; with the observed order, as in P. J. Roache, J. Fluids Eng. 116 (1994) 405):

    r = (M_k-1 - M_k-2) / (M_k - M_k-1),  p = log2 r,  M_inf ~ M_k + (M_k - M_k-1) / (r - 1)

and takes |M_inf - M_k| as the grid error of the estimate (the size of the correction: conservative, the
estimate's own error is of higher order). It stops when that error is within ``rel_tol`` of the estimate with
an observed order in (``ORDER_RANGE``), at ``max_level``, or when the next level would not finish within
``max_time_s`` (its time predicted from the growth of the last levels' times): then it reports the estimate so
far and how many more seconds the next level needs. A finer level's scan looks only near the coarser level's
neutral whirls (``near``), a third of the film solves of a full scan.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from quenchsim.bearings.gas_journal.geometry import Bearing
from quenchsim.bearings.gas_journal.linear import LinearisedFilm
from quenchsim.bearings.gas_journal.linear_stability import linear_threshold
from quenchsim.errors import require

ORDER_RANGE = (0.5, 4.0)  # observed orders accepted as asymptotic (the solver is second order on smooth films)
TIME_GROWTH_DEFAULT = 5.0  # time of level m+1 / level m before two levels were timed (4x nodes, sparse LU)

CONVERGED = "converged"
MAX_LEVEL = "max_level"
TIME_BUDGET = "time_budget"
NO_THRESHOLD = "no_threshold"


@dataclass(frozen=True)
class LevelThreshold:
    """The linear threshold of one grid level: Mbar (NaN: no neutral whirl found), whirl ratio, seconds taken."""

    level: int
    mass_parameter: float
    whirl_ratio: float
    seconds: float
    crossings: tuple[tuple[float, float], ...] = ()


@dataclass
class ConvergedThreshold:
    """Outcome of :func:`converged_linear_threshold`: the estimate of the grid-converged Mbar and its grid error
    (absolute; NaN when fewer than three levels were run), the observed order, every level's threshold, a
    ``status`` (module constants), a one-line ``message`` and, when a budget stopped it, the predicted seconds
    of the next level."""

    mass_parameter: float
    grid_error: float
    observed_order: float
    whirl_ratio: float
    levels: list[LevelThreshold] = field(default_factory=list)
    status: str = CONVERGED
    message: str = ""
    next_level_seconds: float = math.nan
    wall_time_s: float = 0.0

    @property
    def relative_grid_error(self) -> float:
        return self.grid_error / abs(self.mass_parameter) if self.mass_parameter else 0.0


def richardson(values: list[float]) -> tuple[float, float, float]:
    """(estimate, |estimate - last|, observed order) from the last three values of a sequence on grids halved
    each time; (last, NaN, NaN) with fewer than three values, (last, |last - previous|, NaN) when the last two
    differences do not shrink with one sign (no asymptotic order: the last change is the error estimate).

    >>> est, err, p = richardson([8.0, 10.0, 11.0])
    >>> round(est, 6), round(err, 6), round(p, 6)
    (12.0, 1.0, 1.0)
    """
    if len(values) < 3:
        return values[-1], math.nan, math.nan
    m2, m1, m0 = values[-3:]
    d1, d0 = m1 - m2, m0 - m1
    if d0 == 0.0:
        return m0, 0.0, math.inf
    ratio = d1 / d0
    if ratio <= 1.0:
        return m0, abs(d0), math.nan
    correction = d0 / (ratio - 1.0)
    return m0 + correction, abs(correction), math.log2(ratio)


def converged_linear_threshold(bearing: Bearing, bearing_number: float, eccentricity: float = 0.0,
                               first_level: int = 3, max_level: int = 7, rel_tol: float = 0.02,
                               max_time_s: float = math.inf,
                               on_level: Callable[[LevelThreshold], None] | None = None) -> ConvergedThreshold:
    """Linear threshold on levels ``first_level``..``max_level`` until Richardson's grid error is within
    ``rel_tol`` (see module docstring); ``on_level`` is called after each level (progress)."""
    require(1 <= first_level <= max_level <= 10, "max_level", max_level,
            f"must be an integer in [{first_level}, 10] (levels from {first_level})")
    require(0.0 < rel_tol < 1.0, "rel_tol", rel_tol, "must be in (0, 1)")
    require(max_time_s > 0.0, "max_time_s", max_time_s, "must be > 0")
    started = time.perf_counter()
    runs: list[LevelThreshold] = []
    near: tuple[float, ...] = ()
    status, next_seconds = MAX_LEVEL, math.nan
    for level in range(first_level, max_level + 1):
        if runs:
            growth = (runs[-1].seconds / runs[-2].seconds if len(runs) >= 2 and runs[-2].seconds > 0.0
                      else TIME_GROWTH_DEFAULT)
            next_seconds = runs[-1].seconds * min(max(growth, 2.0), 16.0)
            if time.perf_counter() - started + next_seconds > max_time_s:
                status = TIME_BUDGET
                break
        t0 = time.perf_counter()
        film = LinearisedFilm(bearing, bearing_number, eccentricity, level=level)
        th = linear_threshold(film, near=near)
        run = LevelThreshold(level, th.critical_mass_parameter, th.whirl_ratio, time.perf_counter() - t0,
                             tuple(th.crossings))
        runs.append(run)
        if on_level is not None:
            on_level(run)
        near = tuple(g for g, _ in th.crossings)
        finite = [r.mass_parameter for r in runs if math.isfinite(r.mass_parameter)]
        if not math.isfinite(run.mass_parameter) or len(finite) < 3:
            continue
        estimate, error, order = richardson(finite)
        if error <= rel_tol * abs(estimate) and (estimate == 0.0 or ORDER_RANGE[0] < order < ORDER_RANGE[1]):
            status = CONVERGED
            break
    else:
        next_seconds = math.nan
    return _outcome(runs, status, next_seconds, rel_tol, max_time_s, time.perf_counter() - started)


def _outcome(runs: list[LevelThreshold], status: str, next_seconds: float, rel_tol: float, max_time_s: float,
             seconds: float) -> ConvergedThreshold:
    finite = [r for r in runs if math.isfinite(r.mass_parameter)]
    levels = ", ".join(f"level {r.level}: {r.mass_parameter:.4g}" for r in runs)
    if not finite or not math.isfinite(runs[-1].mass_parameter):
        return ConvergedThreshold(math.nan, math.nan, math.nan, math.nan, runs, NO_THRESHOLD,
                                  f"no neutral whirl on the finest level run ({levels}): no linear threshold",
                                  next_seconds, seconds)
    estimate, error, order = richardson([r.mass_parameter for r in finite])
    whirl = finite[-1].whirl_ratio
    span = f"levels {finite[max(0, len(finite) - 3)].level}-{finite[-1].level}"
    if math.isnan(error):
        head = (f"Mbar = {estimate:.4g} on level {finite[-1].level}, grid error not estimated (Richardson needs "
                f"three levels)")
    elif math.isnan(order):
        head = (f"Mbar = {estimate:.4g} +- {error:.2g} (grid error: the last change, {span} not in the asymptotic "
                f"range)")
    else:
        head = (f"Mbar = {estimate:.4g} +- {error:.2g} ({100 * error / abs(estimate) if estimate else 0.0:.1f} %; "
                f"grid error of Richardson's estimate from {span}, observed order {order:.2f})")
    if status == CONVERGED:
        tail = f"converged to {100 * rel_tol:g} %"
    elif status == MAX_LEVEL:
        tail = f"not converged to {100 * rel_tol:g} % by level {runs[-1].level}"
    else:
        tail = (f"stopped by the time budget of {max_time_s:g} s: level {runs[-1].level + 1} needs ~{next_seconds:.0f} s "
                f"more (give --max-time-s {math.ceil(seconds + next_seconds):d} or more)")
    return ConvergedThreshold(estimate, error, order, whirl, runs, status,
                              f"{head}; whirl ratio {whirl:.3f}; {tail} ({levels})", next_seconds, seconds)
