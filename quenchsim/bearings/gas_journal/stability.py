"""Whirl stability threshold by bisection on nonlinear orbits, bounded in mass, orbits and wall time.

The critical mass parameter Mbar = m pa c^5 / (2 mu^2 L r^5) (reference section 1; M = Mbar Lambda^2 / 144)
separates rotors whose orbit about the equilibrium decays (stable) from those whose orbit grows into
a whirl (half-frequency whirl onset). Each trial releases the rotor at rest from ``start_eccentricity``
(vertical rotor: no external load unless given) and classifies the orbit by the growth rate of its
radius (orbit.whirl_analysis). With ``eccentricity`` the bearing is loaded instead: the load is the static
film force at that eccentricity on the same grid, and each trial releases the rotor from rest 5 % of the
eccentricity outward of that equilibrium, with the steady film of the held rotor -- the operating point a
linearised analysis (linear_stability.py) is taken about. An unloaded rotor is a different problem: its only
equilibrium is the concentric one, where a plain bearing's film carries no force in a half-frequency whirl
(linear threshold Mbar = 0), and a rotor released at some eccentricity without load whirls there at half
frequency instead of settling.

The search assumes one threshold in ``mass_range``: stable below, unstable above (a heavier rotor
whirls). It first runs the two ends of the range: when they do not bracket a threshold it stops there
-- e.g. an unloaded plain bearing, whose concentric state has the half-frequency whirl at every mass
(its growth rate falls towards 0 only as Mbar -> 0), is "unstable for every mass in range". Otherwise
the bracket [stable, unstable] is found from ``first_guess`` by factors of 4 (bounded by the ends)
and then halved in log(Mbar) until hi / lo <= 1 + rel_tol. The search stops with the bracket found
so far when it has run ``max_trials`` orbits or ``max_time_s`` seconds (an orbit running past the
deadline is abandoned), and says what it still needs: the bracket's geometric mean, the orbits to a
bracket within ``rel_tol`` (:func:`orbits_to_converge`) and their time at the seconds per orbit measured.
The threshold is that of the grid ``level``: the grid error is not estimated here (for a film that can be
linearised, converged_threshold.py gives it).

Default range MASS_PARAMETER_RANGE = [0.1, 100]: the light end is where the orbits get expensive
(the step size follows the rotor's natural period, ~ sqrt(M): 0.1 costs ~1600 steps at Lambda 1 over
T = 40), and a heavy rotor whirls slowly: rotor A-1 at Lambda 1 touches down by T = 21 at Mbar 100,
but at Mbar 1000 its orbit grows by only 1e-4 per unit T within T = 40, too close to zero to classify.
Search heavier rotors with a longer ``duration``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

from quenchsim.bearings.gas_journal.geometry import Bearing
from quenchsim.bearings.gas_journal.orbit import OrbitProgress, WallTimeExceeded, mass_from_parameter, orbit
from quenchsim.bearings.gas_journal.reynolds import check_inputs
from quenchsim.bearings.gas_journal.static import static_characteristics
from quenchsim.errors import require

START_OFFSET = 0.05  # loaded search: release 5 % of the eccentricity outward of the equilibrium
MASS_PARAMETER_RANGE = (0.1, 100.0)  # default Mbar range (rotor A-1 at Lambda 1: threshold 8.9 on level 3)

# status of a search: a threshold, no threshold in range (three ways), or a budget ran out first
BRACKETED = "bracketed"
UNSTABLE_IN_RANGE = "unstable_in_range"
STABLE_IN_RANGE = "stable_in_range"
INVERTED = "inverted"
TIME_BUDGET = "time_budget"
ITERATION_BUDGET = "iteration_budget"


@dataclass
class StabilityResult:
    """Outcome of the search: ``status`` (module constants), a one-line ``message``, the critical Mbar
    (NaN unless bracketed), the largest stable and smallest unstable Mbar found (None when none was),
    and every orbit run (Mbar, stable, growth rate, whirl ratio)."""

    critical_mass_parameter: float
    stable_below: float | None
    unstable_above: float | None
    whirl_ratio: float
    trials: list[tuple[float, bool, float, float]] = field(default_factory=list)
    status: str = BRACKETED
    message: str = ""
    mass_range: tuple[float, float] = MASS_PARAMETER_RANGE
    wall_time_s: float = 0.0
    seconds_needed: float = float("nan")
    """When a budget stopped the search: the estimated further wall time to a bracket within ``rel_tol``."""


class _Budget(Exception):
    """Internal: the search ran out of orbits or time (``status`` says which); ``orbit_fraction``: the share of
    an abandoned orbit that was run."""

    def __init__(self, status: str, detail: str, orbit_fraction: float = 0.0) -> None:
        super().__init__(detail)
        self.status = status
        self.detail = detail
        self.orbit_fraction = orbit_fraction


def orbits_to_converge(lo: float, hi: float, rel_tol: float) -> int:
    """Bisections in log(Mbar) that narrow the bracket [lo, hi] to hi / lo <= 1 + rel_tol.

    >>> orbits_to_converge(1.0, 4.0, 0.05)
    5
    """
    if hi / lo <= 1.0 + rel_tol:
        return 0
    return math.ceil(math.log2(math.log(hi / lo) / math.log1p(rel_tol)))


def loaded_start(bearing: Bearing, bearing_number: float, eccentricity: float, level: int,
                 offset: float = START_OFFSET) -> tuple[float, tuple[float, float], tuple[float, float]]:
    """(load, equilibrium, start) of a rotor loaded downwards (-90 deg) to sit at ``eccentricity``: the static
    film force at that eccentricity on grid ``level``, the equilibrium position (displaced by the attitude angle
    from the load line) and the release position ``offset`` x eccentricity further out on the line of centres."""
    probe = static_characteristics(bearing, bearing_number, eccentricity, -90.0, level)
    angle = math.radians(-90.0 + probe.attitude_deg)
    equilibrium = (eccentricity * math.cos(angle), eccentricity * math.sin(angle))
    out = 1.0 + offset
    return probe.load, equilibrium, (equilibrium[0] * out, equilibrium[1] * out)


def critical_mass_parameter(bearing: Bearing, bearing_number: float, level: int = 3, load: float = 0.0,
                            start_eccentricity: float = 0.1, duration: float = 40.0, first_guess: float = 1.0,
                            rel_tol: float = 0.05, max_trials: int = 24, method: str = "multigrid",
                            mass_range: tuple[float, float] = MASS_PARAMETER_RANGE,
                            max_time_s: float = math.inf, progress: bool = False,
                            eccentricity: float | None = None) -> StabilityResult:
    """Critical Mbar at ``bearing_number`` by bisection on orbits (see module docstring); ``progress``
    shows one tqdm bar per orbit on stderr (search stage, Mbar, dimensionless time, outcome).
    ``eccentricity`` (exclusive with ``load``): search the bearing loaded to sit at that eccentricity."""
    check_inputs(bearing_number, start_eccentricity)
    if eccentricity is not None:
        require(load == 0.0, "load", load, "must not be given with eccentricity (the eccentricity sets the load)")
        require(math.isfinite(eccentricity) and 0.0 < eccentricity < 0.9, "eccentricity", eccentricity,
                "must be in (0, 0.9) (the loaded operating point; 0 is the unloaded bearing)")
    require(bearing_number > 0.0, "bearing_number", bearing_number, "must be > 0 for a stability threshold")
    require(0.0 < rel_tol < 1.0, "rel_tol", rel_tol, "must be in (0, 1)")
    lo_end, hi_end = (float(m) for m in mass_range)
    require(0.0 < lo_end < hi_end, "mass_range", mass_range, "must be two mass parameters 0 < lo < hi")
    require(max_trials >= 2, "max_trials", max_trials, "must be >= 2 (the two ends of the mass range)")
    require(max_time_s > 0.0, "max_time_s", max_time_s, "must be > 0")
    started = time.perf_counter()
    if eccentricity is None:
        start, initial_film = (start_eccentricity, 0.0), "ambient"
    else:
        load, _, start = loaded_start(bearing, bearing_number, eccentricity, level)
        initial_film = "steady"
    trials: list[tuple[float, bool, float, float]] = []
    stable_at: dict[float, bool] = {}
    whirl_near: dict[float, float] = {}

    def bracket() -> tuple[float | None, float | None]:
        """Largest stable Mbar run so far and the smallest unstable one above it."""
        stable = [m for m, s in stable_at.items() if s]
        unstable = [m for m, s in stable_at.items() if not s and (not stable or m > max(stable))]
        return (max(stable) if stable else None), (min(unstable) if unstable else None)

    def is_stable(mbar: float, stage: str) -> bool:
        if mbar in stable_at:
            return stable_at[mbar]
        if len(trials) >= max_trials:
            raise _Budget(ITERATION_BUDGET, f"orbit budget of {max_trials} orbits reached")
        left = max_time_s - (time.perf_counter() - started)
        if left <= 0.0:
            raise _Budget(TIME_BUDGET, f"time budget of {max_time_s:g} s reached after {len(trials)} orbits")
        try:
            with OrbitProgress(duration, f"stability {stage} orbit {len(trials) + 1} Mbar {mbar:.4g}", progress) as bar:
                res = orbit(bearing, bearing_number, load, mass_from_parameter(mbar, bearing_number), level=level,
                            duration=duration, start=start, method=method, initial_film=initial_film,
                            stop_when_settled=False, on_step=bar.update, max_wall_time_s=left)
                bar.outcome = res.outcome()
        except WallTimeExceeded as exc:
            raise _Budget(TIME_BUDGET, f"time budget of {max_time_s:g} s reached during orbit {len(trials) + 1} "
                          f"(Mbar {mbar:.4g}, at T = {exc.time:.3g} of {duration:g})", exc.time / duration) from None
        trials.append((mbar, res.stable, res.growth_rate, res.whirl_ratio))
        stable_at[mbar] = res.stable
        whirl_near[mbar] = res.whirl_ratio
        return res.stable

    def result(status: str, message: str, lo: float | None, hi: float | None,
               seconds_needed: float = float("nan")) -> StabilityResult:
        if status == BRACKETED:
            assert lo is not None and hi is not None   # a bracket has both ends
            critical = math.sqrt(lo * hi)
        else:
            critical = float("nan")
        whirl = whirl_near[hi] if hi is not None and hi in whirl_near else float("nan")
        return StabilityResult(critical, lo, hi, whirl, trials, status, message, (lo_end, hi_end),
                               time.perf_counter() - started, seconds_needed)

    def tally() -> str:
        return f"{len(trials)} orbits in {time.perf_counter() - started:.0f} s"

    span = f"Mbar in [{lo_end:g}, {hi_end:g}]"
    try:
        hi_stable = is_stable(hi_end, "range end")
        lo_stable = is_stable(lo_end, "range end")
        if not lo_stable and not hi_stable:
            hint = ("; an unloaded rotor whirls about the concentric position, where a plain bearing's linear "
                    "threshold is Mbar = 0: give the eccentricity of a loaded operating point"
                    if load == 0.0 and (bearing.grooves is None or bearing.grooves.depth_ratio == 0.0) else "")
            return result(UNSTABLE_IN_RANGE, f"unstable for every mass in range: whirl at both ends of {span}, "
                          f"no threshold to bisect ({tally()}){hint}", None, lo_end)
        if lo_stable and hi_stable:
            return result(STABLE_IN_RANGE, f"stable for every mass in range: both ends of {span} stable, "
                          f"no threshold to bisect ({tally()})", hi_end, None)
        if hi_stable:
            return result(INVERTED, f"unstable at Mbar {lo_end:g} but stable at {hi_end:g}: {span} does not "
                          f"bracket a whirl onset (stable below, unstable above) ({tally()})", None, None)
        lo, hi = lo_end, hi_end
        mbar = min(max(first_guess, lo_end), hi_end)
        if is_stable(mbar, "bracket"):
            lo = mbar
            while mbar * 4.0 < hi_end:
                mbar *= 4.0
                if not is_stable(mbar, "bracket"):
                    hi = mbar
                    break
                lo = mbar
        else:
            hi = mbar
            while mbar / 4.0 > lo_end:
                mbar /= 4.0
                if is_stable(mbar, "bracket"):
                    lo = mbar
                    break
                hi = mbar
        while hi / lo > 1.0 + rel_tol:
            mid = math.sqrt(lo * hi)
            if is_stable(mid, "bisect"):
                lo = mid
            else:
                hi = mid
    except _Budget as stop:
        lo_so_far, hi_so_far = bracket()
        so_far = (f"stable at {lo_so_far:.4g}" if lo_so_far is not None else "no stable mass yet") + ", " + (
            f"unstable at {hi_so_far:.4g}" if hi_so_far is not None else "no unstable mass yet")
        if lo_so_far is not None and hi_so_far is not None:
            so_far += f" (Mbar ~ {math.sqrt(lo_so_far * hi_so_far):.4g} within a factor {hi_so_far / lo_so_far:.3g})"
            more = orbits_to_converge(lo_so_far, hi_so_far, rel_tol)
        else:   # the ends still to run, then the bisection of the whole range
            more = 2 - min(len(trials), 2) + orbits_to_converge(lo_end, hi_end, rel_tol) + 2
        per_orbit = (time.perf_counter() - started) / max(len(trials) + stop.orbit_fraction, 1e-9) \
            if trials or stop.orbit_fraction > 0.0 else float("nan")
        needed = more * per_orbit
        need = (f"; ~{more} more orbits to a bracket within {100 * rel_tol:g} %" +
                (f", ~{needed:.0f} s more at {per_orbit:.1f} s per orbit measured here" if math.isfinite(needed)
                 else ""))
        return result(stop.status, f"stopped: {stop.detail}; bracket so far: {so_far} ({span}){need}", lo_so_far,
                      hi_so_far, needed)
    return result(BRACKETED, f"critical Mbar = {math.sqrt(lo * hi):.4g} (stable at {lo:.4g}, unstable at "
                  f"{hi:.4g}; {tally()})", lo, hi)
