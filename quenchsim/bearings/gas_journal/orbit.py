"""Nonlinear rotor orbits: rigid rotor, 2 translational DOF, adaptive RK45 coupled with the
Crank-Nicolson film (reference section 1).

Dimensionless equations of motion (T = omega t / 2, displacement over the clearance):
    M d2e/dT2 = F_film(e, history) + F_ext,   M = m c omega^2 / (8 pa L r) = Mbar Lambda^2 / 144,
F = force / (pa L D). The rotor state (e, de/dT) is advanced by the Dormand-Prince 5(4) pair with
step-size control; every stage force comes from a Crank-Nicolson film step from the last accepted
film state to the stage time and position, so the accepted step's last stage (first-same-as-last)
is the film of the next step. Start at rest at a given position with P = 1 (reference).
"""

from __future__ import annotations

import math
import sys
import time as clock
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from tqdm import tqdm

from quenchsim.bearings.gas_journal.forces import attitude_deg, film_force
from quenchsim.bearings.gas_journal.geometry import Bearing, grid_for_level
from quenchsim.bearings.gas_journal.reynolds import check_inputs, operator_hierarchy, solve
from quenchsim.bearings.gas_journal.transient import CrankNicolsonFilm, FilmState, film_frame
from quenchsim.errors import InputError, SolverError, require

# Dormand & Prince (1980) RK5(4)7M coefficients (J. Comput. Appl. Math. 6, 19-26)
_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
_A = [
    [],
    [1 / 5],
    [3 / 40, 9 / 40],
    [44 / 45, -56 / 15, 32 / 9],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
    [35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84],
]
_B5 = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0.0])
_B4 = np.array([5179 / 57600, 0.0, 7571 / 16695, 393 / 640, -92097 / 339200, 187 / 2100, 1 / 40])

CONTACT_ECCENTRICITY = 0.95  # an orbit reaching this eccentricity is reported as unstable (touch-down)
STEPS_PER_GROOVE_PASSAGE = 4  # largest time step of a grooved-rotor orbit: 1/4 of a groove passage
CENTRE_WINDOW = 4.0 * math.pi  # two half-frequency whirl periods (the rotor turns 2 rad per unit T)


class WallTimeExceeded(SolverError):
    """An orbit stopped by its wall-time budget; ``time`` is the dimensionless time T it reached."""

    def __init__(self, time: float, duration: float, budget_s: float) -> None:
        self.time = time
        self.budget_s = budget_s
        super().__init__(f"orbit stopped at T = {time:.4g} of {duration:g}: wall-time budget of {budget_s:.3g} s "
                         "reached")


class OrbitProgress:
    """A tqdm bar on stderr over an orbit's dimensionless time T, used as a context manager: pass
    ``update`` as ``orbit(on_step=...)`` and set ``outcome``; on exit the bar is left as one line saying
    what the orbit gave (or where it stopped, when it raised)."""

    def __init__(self, duration: float, desc: str, enabled: bool = True) -> None:
        self.bar = tqdm(total=duration, desc=desc, unit="T", file=sys.stderr, disable=not enabled, mininterval=0.5,
                        bar_format="{desc}: {percentage:3.0f}%|{bar:20}| T {n:.1f}/{total:.0f} [{elapsed}]{postfix}")
        self.outcome = ""

    def update(self, time: float, steps: int) -> None:
        self.bar.update(time - self.bar.n)

    def __enter__(self) -> OrbitProgress:
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        self.bar.set_postfix_str(self.outcome if exc is None else f"stopped: {exc}", refresh=False)
        self.bar.close()


def mass_from_parameter(mass_parameter: float, bearing_number: float) -> float:
    """M = Mbar Lambda^2 / 144 (reference section 1)."""
    return mass_parameter * bearing_number ** 2 / 144.0


@dataclass
class OrbitResult:
    """Time history of the rotor centre (over the clearance) and the outcome of the run."""

    time: np.ndarray
    x: np.ndarray
    y: np.ndarray
    force: np.ndarray
    eccentricity: float
    attitude_deg: float
    centre: tuple[float, float]
    settled: bool
    stable: bool
    whirl_ratio: float
    growth_rate: float
    steps: int
    rejected: int

    def outcome(self) -> str:
        """One phrase for progress lines: stable/unstable with the growth rate, or the touch-down time."""
        if math.isinf(self.growth_rate):
            return f"UNSTABLE (touch-down at T = {self.time[-1]:.3g}), {self.steps} steps"
        return f"{'stable' if self.stable else 'UNSTABLE'}, growth {self.growth_rate:+.3g}/T, {self.steps} steps"

    def to_csv(self, path) -> None:
        """Write T, e_x, e_y, F_x, F_y columns."""
        data = np.column_stack([self.time, self.x, self.y, self.force])
        np.savetxt(path, data, delimiter=",", header="T,e_x,e_y,F_x,F_y", comments="")


def whirl_analysis(time: np.ndarray, x: np.ndarray, y: np.ndarray, centre: tuple[float, float]) -> tuple[float, float]:
    """Growth rate of the orbit about ``centre`` and the whirl frequency ratio.

    Growth rate = ln(max radius over the last whirl period / max radius over the second one) divided
    by the time between them (whirl period 2 pi in T: half-frequency whirl, the rotor turns 2 rad per
    unit T); negative = decaying orbit. Window maxima make it insensitive to the groove-passage ripple.
    Whirl ratio = mean angular speed of the orbit over the second half / 2 (0.5 = half-frequency whirl).
    """
    period = 2.0 * math.pi
    rx, ry = x - centre[0], y - centre[1]
    radius = np.hypot(rx, ry)
    half = time >= 0.5 * time[-1]
    phase = np.unwrap(np.arctan2(ry, rx))
    span = time[half][-1] - time[half][0]
    whirl = float((phase[half][-1] - phase[half][0]) / span / 2.0) if span > 0 else 0.0
    if time[-1] < 3.0 * period:
        raise InputError("duration", float(time[-1]), f"must be >= 3 whirl periods (3 * 2 pi = {3 * period:.1f}) "
                         "to classify an orbit")
    early = radius[(time >= period) & (time <= 2.0 * period)].max()
    late = radius[time >= time[-1] - period].max()
    growth = float(math.log(max(late, 1e-300) / max(early, 1e-300)) / (time[-1] - 2.0 * period))
    return growth, whirl


def orbit(bearing: Bearing, bearing_number: float, load: float, mass: float, level: int = 3,
          duration: float = 60.0, start: tuple[float, float] = (0.0, 0.0), load_angle_deg: float = -90.0,
          method: str = "multigrid", rtol: float = 1e-4, atol: float = 1e-6, max_step: float = 0.5,
          settle_tolerance: float = 1e-5, stop_when_settled: bool = True,
          initial_film: str = "ambient", on_step: Callable[[float, int], None] | None = None,
          max_wall_time_s: float = math.inf) -> OrbitResult:
    """Integrate the rotor orbit under the constant load ``load`` (= W/(pa L D), towards
    ``load_angle_deg``) with dimensionless mass M = ``mass`` from rest at ``start`` with P = 1
    (``initial_film="ambient"``, the reference's start) or with the steady film of the held rotor
    (``"steady"``: released from a held position, avoids a touch-down while a stiff gas film is
    still building up at high Lambda).

    Stops at ``duration``, at touch-down (eccentricity >= CONTACT_ECCENTRICITY) or, with
    ``stop_when_settled``, when the rotor has settled: either the speed and the net force stay below
    ``settle_tolerance`` (times max(load, 1)) for one unit of T, or (lightly damped whirl) the mean
    position over the last CENTRE_WINDOW moved less than 10 * settle_tolerance from the window before
    while the orbit shrinks. ``eccentricity``/``attitude_deg`` are those of the final position when
    settled at rest, else of the orbit centre (mean position over the last window).

    ``on_step(T, accepted_steps)`` is called after every accepted step (progress display); past
    ``max_wall_time_s`` seconds of wall time the orbit raises :class:`WallTimeExceeded`.
    """
    check_inputs(bearing_number, float(np.hypot(*start)))
    require(np.isfinite(mass) and mass > 0.0, "mass", mass, "must be > 0 (M = m c omega^2 / (8 pa L r))")
    require(np.isfinite(load) and load >= 0.0, "load", load, "must be >= 0 (W / (pa L D))")
    grid = grid_for_level(level, bearing)
    if bearing.grooved_rotor:
        assert bearing.grooves is not None   # a grooved rotor has grooves
        max_step = min(max_step, math.pi / bearing.grooves.count / STEPS_PER_GROOVE_PASSAGE)
    film = CrankNicolsonFilm(bearing, grid, bearing_number, method)
    f_ext = load * np.array([math.cos(math.radians(load_angle_deg)), math.sin(math.radians(load_angle_deg))])
    require(initial_film in ("ambient", "steady"), "initial_film", initial_film, "must be 'ambient' or 'steady'")
    start = (float(start[0]), float(start[1]))
    p0 = np.ones(grid.shape)
    if initial_film == "steady":
        ops = operator_hierarchy(bearing, grid, bearing_number, start, film_frame(bearing, 0.0))
        p0 = solve(ops, method).p
    state = FilmState(0.0, start, p0)

    def rhs(y: np.ndarray, fs: FilmState) -> tuple[np.ndarray, np.ndarray]:
        force = film_force(grid, fs.p, film_frame(bearing, fs.time))
        return np.array([y[2], y[3], *((force + f_ext) / mass)]), force

    y = np.array([start[0], start[1], 0.0, 0.0])
    k_first, force = rhs(y, state)
    t = 0.0
    h = min(max_step, 1e-3)
    times, xs, ys, forces = [0.0], [y[0]], [y[1]], [force]
    steps = rejected = 0
    quiet_since = None
    settled = False
    touched = False
    started = clock.perf_counter()
    while t < duration - 1e-12:
        if clock.perf_counter() - started > max_wall_time_s:
            raise WallTimeExceeded(t, duration, max_wall_time_s)
        h = min(h, duration - t)
        ks = [k_first]
        stage_states = [state]
        for s in range(1, 7):
            ys_ = y + h * sum(a * k for a, k in zip(_A[s], ks))
            if np.hypot(ys_[0], ys_[1]) >= 0.999:
                break
            fs = film.step(state, t + _C[s] * h, (float(ys_[0]), float(ys_[1])))
            k, f_s = rhs(ys_, fs)
            ks.append(k)
            stage_states.append(fs)
        if len(ks) < 7:
            h *= 0.25
            rejected += 1
            if h < 1e-9:
                raise SolverError(f"orbit step size underflow at T = {t:.6g}")
            continue
        y_new = y + h * sum(b * k for b, k in zip(_B5, ks))
        err = h * sum((b5 - b4) * k for b5, b4, k in zip(_B5, _B4, ks))
        scale = atol + rtol * np.maximum(np.abs(y), np.abs(y_new))
        norm = float(np.max(np.abs(err) / scale))
        if norm <= 1.0:
            t += h
            y = y_new
            state = stage_states[6]
            k_first = ks[6]
            force = f_s
            steps += 1
            times.append(t)
            xs.append(y[0])
            ys.append(y[1])
            forces.append(force)
            if on_step is not None:
                on_step(t, steps)
            if np.hypot(y[0], y[1]) >= CONTACT_ECCENTRICITY:
                touched = True
                break
            quiet = (np.hypot(y[2], y[3]) < settle_tolerance * max(load, 1.0)
                     and np.hypot(*(force + f_ext)) < settle_tolerance * max(load, 1.0))
            if quiet:
                quiet_since = t if quiet_since is None else quiet_since
                if t - quiet_since >= 1.0:
                    settled = True
                    if stop_when_settled:
                        break
            else:
                quiet_since = None
            if stop_when_settled and t >= 3.0 * CENTRE_WINDOW and _centre_converged(times, xs, ys, settle_tolerance):
                settled = True
                break
        else:
            rejected += 1
        factor = 5.0 if norm == 0.0 else min(5.0, max(0.2, 0.9 * norm ** -0.2))
        h = min(h * factor, max_step)
    time_arr, x_arr, y_arr = np.array(times), np.array(xs), np.array(ys)
    force_arr = np.array(forces)
    last = time_arr >= time_arr[-1] - CENTRE_WINDOW
    centre = (float(np.mean(x_arr[last])), float(np.mean(y_arr[last])))
    if touched:
        growth, whirl = float("inf"), float("nan")
    elif time_arr[-1] >= 3.0 * CENTRE_WINDOW / 2.0:
        growth, whirl = whirl_analysis(time_arr, x_arr, y_arr, centre)
    else:
        growth, whirl = float("nan"), float("nan")
    stable = (not touched) and (settled or growth < 0.0)
    at_rest = quiet_since is not None
    disp = np.array([x_arr[-1], y_arr[-1]]) if at_rest else np.array(centre)
    return OrbitResult(time_arr, x_arr, y_arr, force_arr, float(np.hypot(*disp)),
                       attitude_deg(disp, -f_ext) if load > 0.0 else float("nan"), centre,
                       settled, stable, whirl, growth, steps, rejected)


def _centre_converged(times: list[float], xs: list[float], ys: list[float], tol: float) -> bool:
    """Mean positions over the last two CENTRE_WINDOWs agree within 10 tol and the orbit shrinks."""
    t = np.asarray(times)
    x = np.asarray(xs)
    y = np.asarray(ys)
    w1 = t >= t[-1] - CENTRE_WINDOW
    w0 = (t >= t[-1] - 2.0 * CENTRE_WINDOW) & ~w1
    c1 = np.array([x[w1].mean(), y[w1].mean()])
    c0 = np.array([x[w0].mean(), y[w0].mean()])
    r1 = np.max(np.hypot(x[w1] - c1[0], y[w1] - c1[1]))
    r0 = np.max(np.hypot(x[w0] - c1[0], y[w0] - c1[1]))
    return bool(np.hypot(*(c1 - c0)) < 10.0 * tol and r1 < r0)
