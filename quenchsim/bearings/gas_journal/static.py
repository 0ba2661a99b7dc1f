"""Static characteristics (load capacity, attitude angle, pressure field) and the inverse problem.

Load capacity F = W / (pa L D) and attitude angle (load line to line of centres, positive in the
direction of rotation) at a given bearing number and eccentricity (reference section 1). A grooved
rotor has no steady film: its static characteristics are the average over one groove passage of the
periodic film at a fixed rotor position (Crank-Nicolson in the rotor frame).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from quenchsim.bearings.gas_journal.forces import attitude_deg, film_force
from quenchsim.bearings.gas_journal.geometry import Bearing, Grid, grid_for_level
from quenchsim.bearings.gas_journal.reynolds import check_inputs, operator_hierarchy, solve
from quenchsim.bearings.gas_journal.transient import CrankNicolsonFilm, FilmState, film_frame
from quenchsim.errors import SolverError, require

# Crank-Nicolson steps per groove passage and passages simulated for a grooved rotor's static point
STEPS_PER_GROOVE = 16
MAX_GROOVE_PASSAGES = 40
PERIODIC_TOLERANCE = 1e-5  # change of the passage-averaged force between passages


@dataclass
class StaticResult:
    """Static solution: dimensionless load, attitude, film force (F_x, F_y) and pressure field."""

    load: float
    attitude_deg: float
    force: tuple[float, float]
    displacement: tuple[float, float]
    p: np.ndarray
    grid: Grid
    iterations: int
    residual: float
    wall_time_s: float
    work_units: float


def _displacement(eccentricity: float, angle_deg: float) -> tuple[float, float]:
    a = math.radians(angle_deg)
    return (eccentricity * math.cos(a), eccentricity * math.sin(a))


def _steady(bearing: Bearing, grid: Grid, bearing_number: float, disp: tuple[float, float], method: str,
            p0: np.ndarray | None, sor_omega: float) -> StaticResult:
    """Steady film (plain bearing or grooved sleeve; for a grooved rotor: the film frozen at T = 0)."""
    start = time.perf_counter()
    frame = film_frame(bearing, 0.0)
    ops = operator_hierarchy(bearing, grid, bearing_number, disp, frame)
    res = solve(ops, method, p0=p0, omega=sor_omega)
    if not res.converged:
        raise SolverError(f"{method} did not reach ||R||_2 <= 1e-5 (stopped at {res.residual:.3g} after "
                          f"{res.iterations} iterations)")
    force = film_force(grid, res.p, frame)
    return StaticResult(float(np.hypot(*force)), attitude_deg(np.array(disp), force), (force[0], force[1]), disp,
                        res.p, grid, res.iterations, res.residual, time.perf_counter() - start, res.work_units)


def _grooved_rotor(bearing: Bearing, grid: Grid, bearing_number: float, disp: tuple[float, float],
                   method: str) -> StaticResult:
    start = time.perf_counter()
    first = _steady(bearing, grid, bearing_number, disp, method, None, 1.0)
    film = CrankNicolsonFilm(bearing, grid, bearing_number, method)
    assert bearing.grooves is not None   # called for a grooved rotor only
    period = math.pi / bearing.grooves.count  # rotor turns 2 pi / N_g when T advances pi / N_g
    dt = period / STEPS_PER_GROOVE
    state = FilmState(0.0, disp, first.p)
    previous = None
    for passage in range(MAX_GROOVE_PASSAGES):
        forces = []
        for _ in range(STEPS_PER_GROOVE):
            state = film.step(state, state.time + dt, disp)
            forces.append(film_force(grid, state.p, film_frame(bearing, state.time)))
        mean = np.mean(forces, axis=0)
        if previous is not None and np.max(np.abs(mean - previous)) < PERIODIC_TOLERANCE:
            break
        previous = mean
    else:
        raise SolverError(f"grooved-rotor film not periodic after {MAX_GROOVE_PASSAGES} groove passages")
    steps = (passage + 1) * STEPS_PER_GROOVE
    return StaticResult(float(np.hypot(*mean)), attitude_deg(np.array(disp), mean), (mean[0], mean[1]), disp,
                        state.p, grid, steps, first.residual, time.perf_counter() - start, first.work_units)


def static_characteristics(bearing: Bearing, bearing_number: float, eccentricity: float,
                           displacement_angle_deg: float = -90.0, level: int = 4, method: str = "multigrid",
                           p0: np.ndarray | None = None, sor_omega: float = 1.0) -> StaticResult:
    """Load capacity, attitude angle and pressure at eccentricity ratio ``eccentricity`` with the rotor
    displaced towards ``displacement_angle_deg`` (sleeve frame, rotation counter-clockwise)."""
    check_inputs(bearing_number, eccentricity)
    grid = grid_for_level(level, bearing)
    disp = _displacement(eccentricity, displacement_angle_deg)
    if bearing.grooved_rotor:
        return _grooved_rotor(bearing, grid, bearing_number, disp, method)
    return _steady(bearing, grid, bearing_number, disp, method, p0, sor_omega)


def equilibrium(bearing: Bearing, bearing_number: float, load: float, load_angle_deg: float = -90.0,
                level: int = 4, method: str = "multigrid", tol: float = 1e-5,
                max_iterations: int = 30) -> StaticResult:
    """Inverse problem: the rotor position where the film force balances the load ``load`` (= W/(pa L D))
    acting towards ``load_angle_deg``. Damped Newton iteration on the displacement (e_x, e_y) with a
    finite-difference Jacobian; warm-started pressure fields."""
    require(np.isfinite(load) and load > 0.0, "load", load, "must be > 0 (W / (pa L D))")
    check_inputs(bearing_number, 0.0)
    w = load * np.array([math.cos(math.radians(load_angle_deg)), math.sin(math.radians(load_angle_deg))])
    probe = static_characteristics(bearing, bearing_number, 0.3, load_angle_deg + 45.0, level, method)
    eps = min(0.3 * load / probe.load, 0.9)
    e = eps * np.array([math.cos(math.radians(load_angle_deg + 45.0)), math.sin(math.radians(load_angle_deg + 45.0))])
    p = probe.p
    total = probe.iterations
    h = 1e-4
    for _ in range(max_iterations):
        base = _static_at(bearing, bearing_number, e, level, method, p)
        p = base.p
        total += base.iterations
        g = np.array(base.force) + w
        if np.max(np.abs(g)) < tol * max(load, 1.0):
            base.iterations = total
            return base
        jac = np.empty((2, 2))
        for k in range(2):
            de = e.copy()
            de[k] += h
            jac[:, k] = (np.array(_static_at(bearing, bearing_number, de, level, method, p).force) - base.force) / h
        step = np.linalg.solve(jac, -g)
        alpha = 1.0
        while np.hypot(*(e + alpha * step)) >= 0.98:
            alpha *= 0.5
        e = e + alpha * step
    raise SolverError(f"no equilibrium found for load {load} within {max_iterations} Newton steps "
                      f"(last eccentricity {np.hypot(*e):.4f})")


def _static_at(bearing: Bearing, bearing_number: float, e: np.ndarray, level: int, method: str,
               p0: np.ndarray) -> StaticResult:
    eps = float(np.hypot(*e))
    angle = math.degrees(math.atan2(e[1], e[0]))
    return static_characteristics(bearing, bearing_number, eps, angle, level, method,
                                  None if bearing.grooved_rotor else p0)
