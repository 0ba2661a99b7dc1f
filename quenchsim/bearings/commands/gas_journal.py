"""`quenchsim bearings gas-journal static | orbit | stability | linear | bench`: gas journal bearings.

Parses arguments and calls quenchsim.bearings.gas_journal; returns one JSON-serialisable dict.
"""

from __future__ import annotations

import argparse
import math
import pathlib
import sys
import time
from typing import Any

from quenchsim.bearings.gas_journal.benchmark import run_benchmark, sor_factor, warm_up
from quenchsim.bearings.gas_journal.converged_threshold import (ConvergedThreshold, LevelThreshold,
                                                                converged_linear_threshold)
from quenchsim.bearings.gas_journal.geometry import Bearing, Grooves, effective_ratios
from quenchsim.bearings.gas_journal.linear import LinearisedFilm
from quenchsim.bearings.gas_journal.linear_stability import linear_threshold
from quenchsim.bearings.gas_journal.orbit import OrbitProgress, mass_from_parameter, orbit
from quenchsim.bearings.gas_journal.reynolds import METHODS
from quenchsim.bearings.gas_journal.stability import MASS_PARAMETER_RANGE, critical_mass_parameter
from quenchsim.bearings.gas_journal.static import static_characteristics
from quenchsim.bearings.commands.ranges import Range
from quenchsim.errors import InputError, require

ACTIONS = ("static", "orbit", "stability", "linear", "bench")
STABILITY_METHODS = ("auto", "linear", "orbit")
# stability: default budgets. The linear ladder stops at level 7 or when the next level would not fit in the
# time budget, and then says how much more time it needs (rotor A-1 at Lambda 1 converges to 2 % on level 6 in
# ~7 s on an idle 2-core machine, Lambda 10 on level 7 in ~60 s); the orbit search is bounded by its number of
# orbits (an orbit of A-1 at level 3 takes ~9 s, a search 9-10 orbits), not by the clock, unless given one.
STABILITY_MAX_TIME_S = 300.0
STABILITY_MAX_ORBITS = 24
STABILITY_GRID_TOL = 0.02
STABILITY_MAX_LEVEL = 7
POSITIVE = Range(0.0, low_open=True)
LEVEL = Range(1, 10, integer=True)
"""Grid levels: level 10 is 5121 x 1025 nodes, beyond it a solve outgrows the memory of a workstation."""
RANGES = {"bearing_number": Range(0.0, 1e6), "eccentricity": Range(0.0, 1.0, high_open=True),
          "displacement_angle": Range(-360.0, 360.0, unit="deg"), "ld": Range(0.0, 20.0, low_open=True),
          "grooves": Range(1, 1000, integer=True),
          "groove_angle": Range(0.0, 90.0, low_open=True, high_open=True, unit="deg"),
          "groove_depth": Range(0.0, 100.0, low_open=True),
          "groove_width_ratio": Range(0.0, 1.0, low_open=True, high_open=True),
          "groove_length_ratio": Range(0.0, 1.0, low_open=True), "level": LEVEL, "levels": LEVEL,
          "sor_omega": Range(0.0, 2.0, low_open=True, high_open=True), "load": Range(-1e6, 1e6),
          "mass": POSITIVE, "mass_parameter": POSITIVE, "duration": Range(0.0, 1e6, low_open=True),
          "start_eccentricity": Range(0.0, 1.0, low_open=True, high_open=True), "mass_range": POSITIVE,
          "rel_tol": Range(0.0, 10.0, low_open=True), "max_time_s": POSITIVE,
          "max_iterations": Range(1, 10000, integer=True), "budget": POSITIVE,
          "whirl_ratio": Range(0.0, 10.0, low_open=True), "grid_tol": Range(0.0, 1.0, low_open=True, high_open=True),
          "max_level": Range(3, 10, integer=True)}
"""Physical ranges of the numeric options (checked before any work, see :mod:`quenchsim.bearings.commands.ranges`):
an eccentricity ratio below 1 (the journal inside its clearance), groove ratios within the land, SOR's
over-relaxation in (0, 2)."""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("action", choices=ACTIONS, help="static characteristics, orbit, stability threshold "
                        "(orbits), linearised coefficients and threshold, or solver benchmark")
    parser.add_argument("--bearing-number", type=float, nargs="+", required=True,
                        help="Lambda = 6 mu omega r^2 / (pa c^2) (bench: several)")
    parser.add_argument("--eccentricity", type=float, help="static: eccentricity ratio e / c; stability, linear: "
                        "the loaded operating point (stability default: unloaded rotor; linear default 0)")
    parser.add_argument("--displacement-angle", type=float, default=-90.0,
                        help="static: direction of the rotor displacement, deg (default -90)")
    parser.add_argument("--ld", type=float, default=1.0, help="length-to-diameter ratio L/D (default 1)")
    parser.add_argument("--grooves", type=int, help="number of herringbone grooves (omit: plain bearing)")
    parser.add_argument("--groove-angle", type=float, default=30.0, help="groove angle, deg (default 30)")
    parser.add_argument("--groove-depth", type=float, default=1.0, help="groove depth / clearance (default 1)")
    parser.add_argument("--groove-width-ratio", type=float, default=0.5, help="groove / (groove + ridge) width")
    parser.add_argument("--groove-length-ratio", type=float, default=0.5, help="grooved / bearing length")
    parser.add_argument("--grooved", choices=("sleeve", "rotor"), default="sleeve", help="grooved member")
    parser.add_argument("--level", type=int, default=None,
                        help="grid level m: (10 2^(m-1)+1) x (2 2^(m-1)+1) nodes (default: static 5, orbit 3; "
                        "stability: the orbit grid, or with --by linear one level instead of the convergence ladder)")
    parser.add_argument("--method", choices=METHODS, default="multigrid", help="static: solver")
    parser.add_argument("--sor-omega", type=float, help="static --method sor: over-relaxation factor")
    parser.add_argument("--load", type=float, help="orbit: load W / (pa L D) (downward); stability: "
                        "optional, default 0 (vertical rotor)")
    mass = parser.add_mutually_exclusive_group()
    mass.add_argument("--mass", type=float, help="orbit: M = m c omega^2 / (8 pa L r)")
    mass.add_argument("--mass-parameter", type=float, help="orbit: Mbar = m pa c^5 / (2 mu^2 L r^5)")
    parser.add_argument("--duration", type=float, default=None, help="orbit/stability: T = omega t / 2 span")
    parser.add_argument("--start-eccentricity", type=float, default=0.1, help="stability: release eccentricity")
    parser.add_argument("--mass-range", type=float, nargs=2, default=list(MASS_PARAMETER_RANGE),
                        metavar=("LO", "HI"), help="stability: Mbar range searched, its ends are run first "
                        f"(default {MASS_PARAMETER_RANGE[0]:g} {MASS_PARAMETER_RANGE[1]:g})")
    parser.add_argument("--rel-tol", type=float, default=0.05, help="stability: bracket width hi/lo - 1 (default 0.05)")
    parser.add_argument("--by", choices=STABILITY_METHODS, default="auto",
                        help="stability: linear = the linearised film's threshold on successively finer grids until "
                        "Richardson's grid error is within --grid-tol; orbit = bisection on nonlinear orbits at "
                        "--level; auto (default) = linear wherever the film can be linearised (no --load), else orbit")
    parser.add_argument("--grid-tol", type=float, default=STABILITY_GRID_TOL,
                        help=f"stability (linear): relative grid error to stop at (default {STABILITY_GRID_TOL:g})")
    parser.add_argument("--max-level", type=int, default=STABILITY_MAX_LEVEL,
                        help=f"stability (linear): finest grid level tried (default {STABILITY_MAX_LEVEL})")
    parser.add_argument("--max-time-s", type=float, default=None,
                        help=f"stability: wall-time budget, s (linear: default {STABILITY_MAX_TIME_S:g}, then it "
                        "says how much more the next level needs; orbit: none); orbit: optional")
    parser.add_argument("--max-iterations", type=int, default=STABILITY_MAX_ORBITS,
                        help=f"stability (orbit): orbit budget (default {STABILITY_MAX_ORBITS})")
    parser.add_argument("--orbit-csv", default="gas_journal_orbit.csv", help="orbit: CSV output path")
    parser.add_argument("--whirl-ratio", type=float, nargs="+", help="linear: whirl frequency / rotor speed of the "
                        "coefficients (default: the threshold's)")
    parser.add_argument("--levels", type=int, nargs="+", default=[3, 4, 5, 6], help="bench: grid levels")
    parser.add_argument("--methods", choices=METHODS, nargs="+", default=list(METHODS), help="bench: methods")
    parser.add_argument("--budget", type=float, default=60.0,
                        help="bench: seconds per Gauss-Seidel/SOR run before extrapolation")


def _bearing(args: argparse.Namespace) -> Bearing:
    if args.grooves is None:
        return Bearing(args.ld)
    return Bearing(args.ld, Grooves(args.grooves, args.groove_angle, args.groove_depth, args.groove_width_ratio,
                                    args.groove_length_ratio, args.grooved))


def _single(args: argparse.Namespace) -> float:
    require(len(args.bearing_number) == 1, "--bearing-number", args.bearing_number,
            f"{args.action} takes exactly one value")
    return args.bearing_number[0]


def _static(args: argparse.Namespace) -> dict:
    if args.eccentricity is None:
        raise InputError("--eccentricity", None, "required for static")
    lam = _single(args)
    level = args.level or 5
    omega = args.sor_omega if args.sor_omega is not None else sor_factor(level, lam)
    jit = warm_up()
    res = static_characteristics(_bearing(args), lam, args.eccentricity, args.displacement_angle, level,
                                 args.method, sor_omega=omega)
    out = {"load": res.load, "attitude_deg": res.attitude_deg, "grid": [res.grid.n_xi + 1, res.grid.n_eta + 1],
           "iterations": res.iterations, "residual": res.residual, "wall_time_s": res.wall_time_s,
           "jit_warm_up_s": jit}
    bearing = _bearing(args)
    if bearing.grooves is not None:
        # groove edges snap to grid lines: the ratios actually represented on this grid
        out["groove_width_length_ratio_on_grid"] = list(effective_ratios(res.grid, bearing.grooves))
    return out


def _orbit(args: argparse.Namespace) -> dict:
    lam = _single(args)
    if args.eccentricity is not None:
        raise InputError("--eccentricity", args.eccentricity, "not used by orbit: give --load (W / (pa L D))")
    if args.load is None:
        raise InputError("--load", None, "required for orbit (W / (pa L D))")
    if args.mass is None and args.mass_parameter is None:
        raise InputError("--mass", None, "give --mass M or --mass-parameter MBAR")
    if args.mass is not None:
        mass = args.mass
    else:
        require(args.mass_parameter > 0.0, "--mass-parameter", args.mass_parameter, "must be > 0")
        mass = mass_from_parameter(args.mass_parameter, lam)
    if args.max_time_s is not None:
        require(args.max_time_s > 0.0, "--max-time-s", args.max_time_s, "must be > 0")
    duration = args.duration or 100.0
    with OrbitProgress(duration, f"orbit M {mass:.4g}") as bar:
        res = orbit(_bearing(args), lam, args.load, mass, level=args.level or 3, duration=duration,
                    on_step=bar.update, max_wall_time_s=math.inf if args.max_time_s is None else args.max_time_s)
        bar.outcome = res.outcome()
    path = pathlib.Path(args.orbit_csv)
    res.to_csv(path)
    return {"eccentricity": res.eccentricity, "attitude_deg": res.attitude_deg, "stable": bool(res.stable),
            "settled": bool(res.settled), "whirl_ratio": res.whirl_ratio, "orbit_csv": str(path)}


def _finite(value: float | None) -> float | None:
    """JSON has no NaN/Infinity: non-finite numbers become null."""
    return value if value is not None and math.isfinite(value) else None


def _linear_applies(args: argparse.Namespace) -> bool:
    """The film can be linearised about a steady state: no external load other than the one an --eccentricity
    sets, and a grooved rotor only concentric (off centre its film is periodic, not steady)."""
    return args.load is None and not (args.grooves is not None and args.grooved == "rotor"
                                      and args.eccentricity is not None)


def _level_row(r: LevelThreshold) -> dict:
    return {"level": r.level, "critical_mass_parameter": _finite(r.mass_parameter),
            "whirl_ratio": _finite(r.whirl_ratio), "seconds": r.seconds}


def _ladder(args: argparse.Namespace, lam: float, max_time_s: float, progress: bool) -> ConvergedThreshold:
    """The grid-converged linear threshold (one level when --level is given); progress lines on stderr."""
    def report(r: LevelThreshold) -> None:
        if progress:
            print(f"stability linear level {r.level}: Mbar {r.mass_parameter:.4g} (whirl ratio "
                  f"{r.whirl_ratio:.3f}, {r.seconds:.1f} s)", file=sys.stderr)

    first, last = (args.level, args.level) if args.level is not None else (3, args.max_level)
    return converged_linear_threshold(_bearing(args), lam, args.eccentricity or 0.0, first_level=first,
                                      max_level=last, rel_tol=args.grid_tol, max_time_s=max_time_s,
                                      on_level=report)


def _linear_answer(res: ConvergedThreshold) -> dict:
    return {"method": "linear", "status": res.status, "message": res.message,
            "critical_mass_parameter": _finite(res.mass_parameter), "grid_error": _finite(res.grid_error),
            "relative_grid_error": _finite(res.relative_grid_error) if math.isfinite(res.grid_error) else None,
            "observed_order": _finite(res.observed_order), "whirl_ratio": _finite(res.whirl_ratio),
            "levels": [_level_row(r) for r in res.levels], "next_level_seconds": _finite(res.next_level_seconds),
            "wall_time_s": res.wall_time_s}


def _stability(args: argparse.Namespace) -> dict:
    low, high = args.mass_range
    require(low < high, "--mass-range", args.mass_range, "LO must be below HI")
    lam = _single(args)
    require(lam > 0.0, "--bearing-number", lam, "must be > 0 for a stability threshold")
    if args.eccentricity is not None:
        require(args.load is None, "--load", args.load, "not with --eccentricity (the eccentricity sets the load)")
        require(0.0 < args.eccentricity < 0.9, "--eccentricity", args.eccentricity,
                "must be in (0, 0.9) for stability (omit it for the unloaded rotor)")
    linear_ok = _linear_applies(args)
    method = args.by if args.by != "auto" else ("linear" if linear_ok else "orbit")
    require(method != "linear" or linear_ok, "--by", "linear", "needs a steady film: no --load (give "
            "--eccentricity for a loaded bearing), and no --eccentricity for grooves on the rotor; use --by orbit")
    if args.level is not None and method == "linear":
        require(args.level >= 2, "--level", args.level, "must be >= 2 for --by linear")
    if method == "linear":
        ladder = _ladder(args, lam, STABILITY_MAX_TIME_S if args.max_time_s is None else args.max_time_s, args.json)
        if args.json:
            print(ladder.message, file=sys.stderr)
        return _linear_answer(ladder)
    started = time.perf_counter()
    res = critical_mass_parameter(_bearing(args), lam, level=args.level or 3, load=args.load or 0.0,
                                  eccentricity=args.eccentricity,
                                  start_eccentricity=args.start_eccentricity, duration=args.duration or 40.0,
                                  rel_tol=args.rel_tol, max_trials=args.max_iterations,
                                  mass_range=tuple(args.mass_range),
                                  max_time_s=math.inf if args.max_time_s is None else args.max_time_s,
                                  progress=True)
    message = res.message
    if res.status == "time_budget" and math.isfinite(res.seconds_needed):
        message += f"; give it more time with --max-time-s {math.ceil(res.wall_time_s + res.seconds_needed):d}"
    out: dict[str, Any] = {"method": "orbit", "status": res.status,
           "critical_mass_parameter": _finite(res.critical_mass_parameter), "stable_below": res.stable_below,
           "unstable_above": res.unstable_above, "whirl_ratio": _finite(res.whirl_ratio),
           "mass_range": list(res.mass_range), "orbits": len(res.trials), "wall_time_s": res.wall_time_s,
           "seconds_needed": _finite(res.seconds_needed),
           "trials": [{"mass_parameter": m, "stable": bool(s), "growth_rate": _finite(g), "whirl_ratio": _finite(w)}
                      for m, s, g, w in res.trials]}
    if linear_ok and math.isfinite(res.critical_mass_parameter):
        grid = _orbit_grid_error(args, lam, res.critical_mass_parameter, args.level or 3, time.perf_counter() - started)
        out["grid_error"] = grid
        message += "; " + grid["message"]
    out["message"] = message
    if args.json:
        print(message, file=sys.stderr)
    return out


def _orbit_grid_error(args: argparse.Namespace, lam: float, orbit_mbar: float, level: int, spent_s: float) -> dict:
    """The orbit grid's discretisation error, from the linear threshold on that grid and the grid-converged one
    (both methods share the discretisation: they agree within ~1 % on one grid, reports/bearings_gas_stability.md)."""
    budget = STABILITY_MAX_TIME_S if args.max_time_s is None else max(args.max_time_s - spent_s, 1.0)
    ladder = converged_linear_threshold(_bearing(args), lam, args.eccentricity or 0.0, first_level=min(level, 3),
                                        max_level=max(args.max_level, level), rel_tol=args.grid_tol,
                                        max_time_s=budget)
    on_level = [r for r in ladder.levels if r.level == level and math.isfinite(r.mass_parameter)]
    if not on_level or not math.isfinite(ladder.mass_parameter) or ladder.mass_parameter == 0.0:
        return {"message": f"grid error of level {level} not estimated ({ladder.message})"}
    error = on_level[0].mass_parameter / ladder.mass_parameter - 1.0
    corrected = orbit_mbar / (1.0 + error)
    return {"relative_error_of_level": error, "linear_on_level": on_level[0].mass_parameter,
            "linear_converged": ladder.mass_parameter, "linear_converged_error": _finite(ladder.grid_error),
            "orbit_corrected": corrected,
            "message": (f"grid error of level {level}: {100 * error:+.1f} % (linear threshold {on_level[0].mass_parameter:.4g} "
                        f"there against grid-converged {ladder.mass_parameter:.4g} +- {ladder.grid_error:.2g}); "
                        f"orbit threshold corrected by it: Mbar ~ {corrected:.4g}")}


def _linear(args: argparse.Namespace) -> dict:
    lam = _single(args)
    require(lam > 0.0, "--bearing-number", lam, "must be > 0 for linear")
    eps = args.eccentricity or 0.0
    film = LinearisedFilm(_bearing(args), lam, eps, level=args.level or 4)
    threshold = linear_threshold(film)
    load_angle = math.degrees(math.atan2(-film.force[1], -film.force[0])) if eps > 0.0 else 0.0
    ratios = args.whirl_ratio or ([threshold.whirl_ratio] if math.isfinite(threshold.whirl_ratio) else [0.5])
    coefficients = []
    for gamma in ratios:
        c = film.coefficients(gamma, load_angle)
        coefficients.append({"whirl_ratio": gamma, "stiffness": c.stiffness.tolist(), "damping": c.damping.tolist()})
    return {"load": film.load, "attitude_deg": _finite(film.attitude_deg), "eccentricity": eps,
            "grid": [film.grid.n_xi + 1, film.grid.n_eta + 1],
            "axes": "x along the load, y 90 deg ahead in the direction of rotation" if eps > 0.0 else "sleeve x, y",
            "critical_mass": _finite(threshold.critical_mass),
            "critical_mass_parameter": _finite(threshold.critical_mass_parameter),
            "whirl_ratio": _finite(threshold.whirl_ratio),
            "neutral_whirls": [{"whirl_ratio": g, "mass": m} for g, m in threshold.crossings],
            "coefficients": coefficients}


def _bench(args: argparse.Namespace) -> dict:
    for lam in args.bearing_number:
        require(lam >= 0.0, "--bearing-number", lam, "must be >= 0")
    return run_benchmark(args.levels, args.bearing_number, args.methods, args.budget, progress=True)


def run(args: argparse.Namespace) -> dict:
    return {"static": _static, "orbit": _orbit, "stability": _stability, "linear": _linear,
            "bench": _bench}[args.action](args)
