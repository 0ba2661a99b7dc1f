"""Whirl stability threshold by bisection on nonlinear orbits.

The critical mass parameter Mbar = m pa c^5 / (2 mu^2 L r^5) (reference section 1; M = Mbar Lambda^2 / 144)
separates rotors whose orbit about the equilibrium decays (stable) from those whose orbit grows into
a whirl (half-frequency whirl onset). Each trial releases the rotor at rest from ``start_eccentricity``
(vertical rotor: no external load unless given) and classifies the orbit by the growth rate of its
radius (orbit.whirl_analysis); the bracket [stable, unstable] is first found by factors of 4 and then
halved in log(Mbar) until hi / lo <= 1 + rel_tol.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from quenchsim.bearings.gas_journal.geometry import Bearing
from quenchsim.bearings.gas_journal.orbit import OrbitResult, mass_from_parameter, orbit
from quenchsim.bearings.gas_journal.reynolds import check_inputs
from quenchsim.errors import SolverError, require


@dataclass
class StabilityResult:
    """Critical mass parameter with its final bracket and every trial (Mbar, stable, growth, whirl ratio)."""

    critical_mass_parameter: float
    stable_below: float
    unstable_above: float
    whirl_ratio: float
    trials: list[tuple[float, bool, float, float]] = field(default_factory=list)


def critical_mass_parameter(bearing: Bearing, bearing_number: float, level: int = 3, load: float = 0.0,
                            start_eccentricity: float = 0.1, duration: float = 40.0, first_guess: float = 1.0,
                            rel_tol: float = 0.05, max_trials: int = 24, method: str = "multigrid") -> StabilityResult:
    """Critical Mbar at ``bearing_number`` by bisection on orbits (see module docstring)."""
    check_inputs(bearing_number, start_eccentricity)
    require(bearing_number > 0.0, "bearing_number", bearing_number, "must be > 0 for a stability threshold")
    require(0.0 < rel_tol < 1.0, "rel_tol", rel_tol, "must be in (0, 1)")
    trials: list[tuple[float, bool, float, float]] = []
    last_unstable: list[OrbitResult] = []

    def is_stable(mbar: float) -> bool:
        if len(trials) >= max_trials:
            raise SolverError(f"stability bisection used {max_trials} orbits without a bracket "
                              f"(trials: {[(round(m, 4), s) for m, s, _, _ in trials]})")
        res = orbit(bearing, bearing_number, load, mass_from_parameter(mbar, bearing_number), level=level,
                    duration=duration, start=(start_eccentricity, 0.0), method=method, stop_when_settled=False)
        trials.append((mbar, res.stable, res.growth_rate, res.whirl_ratio))
        if not res.stable:
            last_unstable.append(res)
        return res.stable

    lo = hi = None
    mbar = first_guess
    if is_stable(mbar):
        lo = mbar
        while hi is None:
            mbar *= 4.0
            if is_stable(mbar):
                lo = mbar
            else:
                hi = mbar
    else:
        hi = mbar
        while lo is None:
            mbar /= 4.0
            if is_stable(mbar):
                lo = mbar
            else:
                hi = mbar
    while hi / lo > 1.0 + rel_tol:
        mid = math.sqrt(lo * hi)
        if is_stable(mid):
            lo = mid
        else:
            hi = mid
    whirl = last_unstable[-1].whirl_ratio if last_unstable else float("nan")
    return StabilityResult(math.sqrt(lo * hi), lo, hi, whirl, trials)
