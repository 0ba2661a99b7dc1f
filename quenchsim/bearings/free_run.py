"""Friction torque of a rolling-bearing spindle from its free run (coast-down).

During free run the friction torque decelerates the rotor: T_s = I_eq |d omega_r / dt|
(free-run paper, reference sec. 5). One reflective mark gives one pulse per revolution; the
period of revolution k gives omega_k = 2 pi / (t_k - t_(k-1)), assigned here to the middle of
that period (exact when omega is linear in time). Time zero is the first pulse (start of the
record = start of free run).

Deceleration at the start of free run, three ways:

* ``t-omega`` (published): omega'(t_k) = (omega_(k+1) - omega_k) / (tau_(k+1) - tau_k) at the
  earlier sample time; least-squares line through all points; its value at t = 0.
* ``n-omega`` (published): omega'(n) = slope of the least-squares line through the first n
  samples, n = 2..N; D(n) = omega'(n) - omega'(n-1), n = 3..N; from the large-n end include index
  i while |D(i+1) - C_(i+2)| <= |C_alpha,(i+1)| alpha/100 (C_(i+2) = mean of D(n), n = i+2..N;
  C_alpha,(i+1) = mean of omega'(n), n = i+1..N), stop at the first failure; fit a line to the
  retained omega'(n) versus n and take its value at n = 1.
* ``model`` (this module's own): a torque law T(omega) = I_eq g(omega) from two families,
  g = c0 + c1 omega + c2 omega^2 (Coulomb, viscous, quadratic drag; c_i >= 0) and
  g = c0 + c1 omega^p (Coulomb + power law, e.g. Palmgren's (nu n)^(2/3) viscous torque),
  integrated exactly in speed,
      t(omega) = int_omega^omega0 dw / g(w),  theta(omega) = int_omega^omega0 w dw / g(w),
  each fitted by nonlinear least squares to ALL pulse times (unknowns omega0, the three law
  parameters and the time of the first pulse); the family with the smaller residual is kept and
  the start torque is I_eq g(omega0). Unlike the linear-fit methods it is unbiased when the
  torque depends on speed (within the families).

Equivalent inertia of rotor, cage/ball orbit and ball spin (no slip: omega_c / omega_r =
(1 - gamma)/2, |omega_a / omega_r| = (d_m/D)(1 - gamma^2)/2, gamma = D cos(alpha)/d_m):

* ``energy`` (default, from the kinetic energy): I_eq = I_r + I_c (omega_c/omega_r)^2 + I_a (omega_a/omega_r)^2
* ``published`` (as printed in the reference): I_eq = I_r + I_c (omega_c/omega_r) + I_a |omega_a/omega_r|.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Literal

import numpy as np
from scipy.integrate import solve_ivp
from scipy.interpolate import CubicHermiteSpline
from scipy.optimize import least_squares

from quenchsim.bearings.kinematics import BearingGeometry, steel_properties
from quenchsim.errors import InputError, SolverError, require

Method = Literal["n-omega", "t-omega", "model"]
METHODS: tuple[str, ...] = ("n-omega", "t-omega", "model")
MIN_PULSES = 5

# Gauss-Legendre rule (4 points) for the speed integrals of the model; with the speed grid below
# the model reproduces independently integrated coast-downs to ~3e-9 s over ~17 s (test_free_run.py).
_GL_X, _GL_W = np.polynomial.legendre.leggauss(4)
_GRID_PER_PULSE = 3
_GRID_MIN = 600
# Evaluation budget of one family's least-squares fit (converged fits of ~400-pulse records take 20-80).
_MAX_NFEV = 400


@dataclass(frozen=True)
class SpeedSamples:
    """Angular speed from pulse periods: omega_k = 2 pi / period_k at the middle of each period (s
    after the first pulse)."""

    t_s: np.ndarray
    omega_rad_s: np.ndarray


@dataclass(frozen=True)
class Deceleration:
    """Deceleration (positive, rad/s^2) and speed at the start of free run by one method, with what
    the plots need: the per-method slope series and the retained window."""

    method: str
    decel_rad_s2: float
    omega0_rad_s: float
    n_used: int
    slope_x: np.ndarray = field(repr=False)        # t (t-omega) or n (n-omega) of each slope
    slope_rad_s2: np.ndarray = field(repr=False)   # omega' (negative while slowing down)
    retained: np.ndarray = field(repr=False)       # bool mask over slope_x used in the final line fit
    line: tuple[float, float] = (0.0, 0.0)         # intercept, slope of the final line fit
    law: TorqueLaw | None = None                    # model only: the fitted deceleration law


@dataclass(frozen=True)
class FreeRunResult:
    """Friction torque at the start of free run (N m) and how it was obtained."""

    method: str
    torque_Nm: float
    omega0_rad_s: float
    decel_rad_s2: float
    n_used: int
    inertia_kg_m2: float
    detail: Deceleration = field(repr=False)


# ---------------------------------------------------------------------------------------- input

def validate_pulse_times(pulse_times_s: np.ndarray) -> np.ndarray:
    """Checked pulse times (s): finite, strictly increasing, at least ``MIN_PULSES``."""
    t = np.asarray(pulse_times_s, dtype=float).ravel()
    require(t.size >= MIN_PULSES, "pulses", int(t.size), f"need at least {MIN_PULSES} pulse times")
    require(bool(np.all(np.isfinite(t))), "pulses", "non-finite value", "all pulse times must be finite")
    steps = np.diff(t)
    if np.any(steps <= 0.0):
        k = int(np.argmax(steps <= 0.0))
        raise InputError(f"pulses[{k + 1}]", float(t[k + 1]),
                         f"pulse times must increase strictly (previous = {float(t[k])!r})")
    return t


def read_pulses(path: str | Path, clock_hz: float | None = None, periods: bool = False) -> np.ndarray:
    """Pulse times (s) from a CSV file with one value per line (first column; a non-numeric first
    line is taken as a header). Values are times in s, or clock counts when ``clock_hz`` is given;
    with ``periods`` they are the period of each revolution (cumulated, first pulse at 0)."""
    p = Path(path)
    if not p.is_file():
        raise InputError("pulses_csv", str(path), "file not found")
    values: list[float] = []
    with p.open(newline="") as fh:
        for i, row in enumerate(csv.reader(fh)):
            if not row or not row[0].strip() or row[0].lstrip().startswith("#"):
                continue
            try:
                values.append(float(row[0]))
            except ValueError:
                if i == 0 and not values:
                    continue  # header line
                raise InputError(f"{p.name} line {i + 1}", row[0], "must be a number") from None
    v = np.asarray(values, dtype=float)
    if clock_hz is not None:
        require(math.isfinite(clock_hz) and clock_hz > 0.0, "clock_hz", clock_hz, "must be a positive frequency")
        v = v / clock_hz
    if periods:
        require(bool(np.all(v > 0.0)), "periods", "non-positive value", "every period must be positive")
        v = np.concatenate(([0.0], np.cumsum(v)))
    return validate_pulse_times(v)


def speed_samples(pulse_times_s: np.ndarray) -> SpeedSamples:
    """omega_k = 2 pi / (t_k - t_(k-1)) at (t_k + t_(k-1))/2 - t_0 (one pulse per revolution)."""
    t = validate_pulse_times(pulse_times_s)
    period = np.diff(t)
    return SpeedSamples(t_s=0.5 * (t[1:] + t[:-1]) - t[0], omega_rad_s=2.0 * math.pi / period)


# ------------------------------------------------------------------------- published methods

def _line(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Least-squares line y = p + q x -> (p, q)."""
    q, p = np.polyfit(x, y, 1)
    return float(p), float(q)


def t_omega_method(samples: SpeedSamples) -> Deceleration:
    """(t - omega') method (reference sec. 5): forward differences of successive samples, one
    least-squares line through all of them, value at t = 0."""
    t, w = samples.t_s, samples.omega_rad_s
    require(t.size >= 3, "pulses", t.size + 1, "the t-omega method needs at least 4 pulses")
    slope = np.diff(w) / np.diff(t)
    x = t[:-1]
    p, q = _line(x, slope)
    return Deceleration(method="t-omega", decel_rad_s2=-p, omega0_rad_s=float(w[0] - p * t[0]),
                        n_used=int(slope.size), slope_x=x, slope_rad_s2=slope,
                        retained=np.ones(slope.size, dtype=bool), line=(p, q))


def cumulative_slopes(samples: SpeedSamples) -> np.ndarray:
    """omega'(n), n = 2..N: slope of the least-squares line through the first n samples (O(N),
    cumulative sums of the time-centred data)."""
    t = samples.t_s - samples.t_s[0]
    w = samples.omega_rad_s - samples.omega_rad_s[0]
    n = np.arange(1, t.size + 1, dtype=float)
    St, Sw, Stt, Stw = np.cumsum(t), np.cumsum(w), np.cumsum(t * t), np.cumsum(t * w)
    num = n * Stw - St * Sw
    den = n * Stt - St * St
    return num[1:] / den[1:]


def n_omega_window(slopes: np.ndarray, alpha_percent: float) -> int:
    """First retained index (into ``slopes``, whose entry j is omega'(n = j + 2)) of the published
    n-omega window: walk down from the large-n end while |D(i+1) - C_(i+2)| <= |C_alpha,(i+1)| alpha/100."""
    N = slopes.size + 1                      # samples; slopes hold n = 2..N
    D = np.diff(slopes)                      # D[j] = D(n = j + 3)
    Dn = lambda n: D[n - 3]                  # noqa: E731
    # suffix means: mean of D(n), n = m..N and of omega'(n), n = m..N
    D_suffix = np.cumsum(D[::-1])[::-1] / np.arange(D.size, 0, -1)
    s_suffix = np.cumsum(slopes[::-1])[::-1] / np.arange(slopes.size, 0, -1)
    first = N - 1                            # a line needs two points: n = N-1, N
    for i in range(N - 2, 1, -1):
        C = D_suffix[i + 2 - 3]
        C_alpha = s_suffix[i + 1 - 2]
        if abs(Dn(i + 1) - C) <= abs(C_alpha) * alpha_percent / 100.0:
            first = i
        else:
            break
    return first - 2


def n_omega_method(samples: SpeedSamples, alpha_percent: float = 1.0) -> Deceleration:
    """(n - omega') method (reference sec. 5), alpha in per cent (published default 1 %)."""
    require(math.isfinite(alpha_percent) and 0.0 < alpha_percent <= 100.0, "alpha_percent", alpha_percent,
            "must lie in (0, 100]")
    require(samples.t_s.size >= 4, "pulses", samples.t_s.size + 1, "the n-omega method needs at least 5 pulses")
    slopes = cumulative_slopes(samples)
    n = np.arange(2, slopes.size + 2, dtype=float)
    j0 = n_omega_window(slopes, alpha_percent)
    retained = np.zeros(slopes.size, dtype=bool)
    retained[j0:] = True
    p, q = _line(n[retained], slopes[retained])
    at_one = p + q
    t, w = samples.t_s, samples.omega_rad_s
    return Deceleration(method="n-omega", decel_rad_s2=-at_one, omega0_rad_s=float(w[0] - at_one * t[0]),
                        n_used=int(retained.sum()), slope_x=n, slope_rad_s2=slopes, retained=retained,
                        line=(p, q))


# ------------------------------------------------------------------------------- model method

def _speed_grid(omega0: float, omega_min: float, n: int) -> np.ndarray:
    return np.linspace(omega0, omega_min, n)


@dataclass(frozen=True)
class TorqueLaw:
    """Deceleration law g(omega) = T(omega) / I_eq (rad/s^2) of one model family:
    ``polynomial``: g = c0 + c1 omega + c2 omega^2 (params c0, c1, c2 >= 0);
    ``power``: g = c0 + c1 omega^p (params c0, c1 >= 0, p in [0.1, 4])."""

    family: str
    params: tuple[float, ...]

    def __call__(self, omega: np.ndarray | float) -> np.ndarray | float:
        if self.family == "polynomial":
            c0, c1, c2 = self.params
            return c0 + c1 * omega + c2 * omega * omega
        c0, c1, p = self.params
        return c0 + c1 * np.power(omega, p)


MODEL_FAMILIES: tuple[str, ...] = ("polynomial", "power")
_POWER_RANGE = (0.1, 4.0)


def model_pulse_times(theta: np.ndarray, omega0: float, law: Callable[[np.ndarray], np.ndarray | float],
                      omega_min: float, grid: int) -> np.ndarray:
    """Times (s, from the first pulse) at which the model rotor has turned ``theta`` (rad), for
    d omega/dt = -law(omega) starting at omega0.

    t(omega) and theta(omega) are integrated over a uniform speed grid from omega0 down to omega_min
    with 4-point Gauss-Legendre per cell; t(theta) is then the cubic Hermite interpolant with
    dt/dtheta = 1/omega at the nodes. Angles beyond theta(omega_min) continue at omega_min, so an
    over-braked trial model gives large, smooth residuals instead of failing.
    """
    w = _speed_grid(omega0, omega_min, grid)
    a, b = w[:-1, None], w[1:, None]
    x = 0.5 * (a + b) + 0.5 * (b - a) * _GL_X[None, :]      # (b - a) < 0: integrating downwards
    g = law(x)
    half = 0.5 * (a - b)[:, 0]
    dt = half * np.sum(_GL_W / g, axis=1)
    dth = half * np.sum(_GL_W * x / g, axis=1)
    t_nodes = np.concatenate(([0.0], np.cumsum(dt)))
    th_nodes = np.concatenate(([0.0], np.cumsum(dth)))
    spline = CubicHermiteSpline(th_nodes, t_nodes, 1.0 / w)
    inside = theta <= th_nodes[-1]
    out = np.empty_like(theta, dtype=float)
    out[inside] = spline(theta[inside])
    out[~inside] = t_nodes[-1] + (theta[~inside] - th_nodes[-1]) / omega_min
    return out


def _initial_guess(samples: SpeedSamples) -> tuple[float, np.ndarray]:
    """omega0 and (c0, c1, c2) >= 0 from a linear regression of the finite-difference deceleration
    on [1, omega, omega^2] (all samples)."""
    t, w = samples.t_s, samples.omega_rad_s
    decel = -np.diff(w) / np.diff(t)
    wm = 0.5 * (w[1:] + w[:-1])
    A = np.column_stack([np.ones_like(wm), wm, wm * wm])
    coef, *_ = np.linalg.lstsq(A, decel, rcond=None)
    coef = np.where(np.isfinite(coef) & (coef > 0.0), coef, 0.0)
    if float(np.min(A @ coef)) <= 0.0:  # regression useless (noise): start from constant torque
        coef = np.array([float(np.mean(decel)), 0.0, 0.0])
    omega0 = float(w[0] + (A[0] @ coef) * t[0])
    return omega0, coef


def _fit_family(family: str, t_rel: np.ndarray, samples: SpeedSamples) -> tuple[float, TorqueLaw, float, bool]:
    """Least-squares fit of one family to all pulse times -> (omega0, law, sum of squared residuals
    in s^2, converged). Unknowns are scaled by the start speed w_s, the mean deceleration d_s and the median
    period T_s; the time of the first pulse is an unknown too (its own timing noise)."""
    theta = 2.0 * math.pi * np.arange(t_rel.size, dtype=float)
    omega0, coef = _initial_guess(samples)
    omega_min = 0.5 * float(np.min(samples.omega_rad_s))
    grid = max(_GRID_MIN, _GRID_PER_PULSE * t_rel.size)
    w_s = float(samples.omega_rad_s[0])
    d_s = float(np.mean(-np.diff(samples.omega_rad_s) / np.diff(samples.t_s)))
    require(d_s > 0.0, "pulses", "speed not decreasing", "a free run must slow down on average")
    T_s = float(np.median(np.diff(t_rel)))

    if family == "polynomial":
        def law_of(q: np.ndarray) -> TorqueLaw:
            return TorqueLaw("polynomial", (float(q[0] * d_s), float(q[1] * d_s / w_s), float(q[2] * d_s / w_s**2)))
        q0 = [coef[0] / d_s, coef[1] * w_s / d_s, coef[2] * w_s**2 / d_s]
        q_lo, q_hi = [0.0, 0.0, 0.0], [np.inf, np.inf, np.inf]
    else:
        def law_of(q: np.ndarray) -> TorqueLaw:
            return TorqueLaw("power", (float(q[0] * d_s), float(q[1] * d_s / w_s ** q[2]), float(q[2])))
        start = coef[0] + coef[1] * w_s + coef[2] * w_s**2
        q0 = [coef[0] / d_s, (start - coef[0]) / d_s, 1.0]
        q_lo, q_hi = [0.0, 0.0, _POWER_RANGE[0]], [np.inf, np.inf, _POWER_RANGE[1]]

    def residual(x: np.ndarray) -> np.ndarray:
        law = law_of(x[2:])
        return (x[1] * T_s + model_pulse_times(theta, x[0] * w_s, law, omega_min, grid) - t_rel) / T_s

    x0 = np.array([omega0 / w_s, 0.0, *q0])
    x0[2:4] = np.maximum(x0[2:4], 1e-6)
    lower = np.array([omega_min / w_s * 1.01, -1.0, *q_lo])
    upper = np.array([np.inf, 1.0, *q_hi])
    x0 = np.clip(x0, lower, np.minimum(upper, 1e6))
    fit = least_squares(residual, x0, bounds=(lower, upper), method="trf", x_scale="jac",
                        xtol=1e-12, ftol=1e-12, gtol=1e-12, max_nfev=_MAX_NFEV)
    return float(fit.x[0] * w_s), law_of(fit.x[2:]), float(np.sum(fit.fun**2)) * T_s**2, bool(fit.success)


def model_method(pulse_times_s: np.ndarray) -> Deceleration:
    """Fit of both model families (polynomial, power; equal numbers of unknowns) to all pulse
    times; the family with the smaller residual is kept; deceleration at the first pulse = g(omega0)."""
    t = validate_pulse_times(pulse_times_s)
    samples = speed_samples(t)
    fits = [f for f in (_fit_family(family, t - t[0], samples) for family in MODEL_FAMILIES) if f[3]]
    if not fits:
        raise SolverError(f"free-run model fit did not converge within {_MAX_NFEV} evaluations for any family "
                          f"({', '.join(MODEL_FAMILIES)}); use --method n-omega")
    w0, law, _, _ = min(fits, key=lambda f: f[2])
    x_s = samples.t_s
    return Deceleration(method="model", decel_rad_s2=float(law(w0)), omega0_rad_s=w0, n_used=int(t.size),
                        slope_x=x_s, slope_rad_s2=-np.asarray(law(samples.omega_rad_s)),
                        retained=np.ones(x_s.size, dtype=bool), law=law)


# ----------------------------------------------------------------------------------- inertia

def speed_ratios(geometry: BearingGeometry) -> tuple[float, float]:
    """(omega_c / omega_r, |omega_a / omega_r|) = ((1 - gamma)/2, (d_m/D)(1 - gamma^2)/2) for a
    rotating inner ring and a fixed outer ring without slip (reference sec. 5)."""
    g = geometry.gamma
    return 0.5 * (1.0 - g), 0.5 * geometry.pitch_diameter_m / geometry.ball_diameter_m * (1.0 - g * g)


def ball_inertias_kg_m2(geometry: BearingGeometry, bearings: int = 1,
                        density_kg_m3: float | None = None) -> tuple[float, float]:
    """Inertias of the balls of ``bearings`` identical bearings: about the axis from their orbit,
    Z m (d_m/2)^2, and about their own axes, Z (2/5) m (D/2)^2, with m = rho pi D^3 / 6 (rho of
    bearing steel from data/bearing_steel.toml unless given)."""
    require(isinstance(bearings, int) and bearings >= 1, "bearings", bearings, "must be an integer >= 1")
    rho = steel_properties()["density_kg_m3"] if density_kg_m3 is None else density_kg_m3
    require(math.isfinite(rho) and rho > 0.0, "density_kg_m3", rho, "must be positive")
    D = geometry.ball_diameter_m
    m = rho * math.pi * D**3 / 6.0
    z = bearings * geometry.balls
    return z * m * (geometry.pitch_diameter_m / 2.0) ** 2, z * 0.4 * m * (D / 2.0) ** 2


def equivalent_inertia(rotor_kg_m2: float, cage_kg_m2: float, ball_spin_kg_m2: float,
                       geometry: BearingGeometry, form: Literal["energy", "published"] = "energy") -> float:
    """I_eq of rotor + cage/ball orbit (``cage_kg_m2``, about the axis) + ball spin
    (``ball_spin_kg_m2``, about the balls' own axes); module docstring for the two forms."""
    for name, value in (("rotor_inertia_kg_m2", rotor_kg_m2), ("cage_inertia_kg_m2", cage_kg_m2),
                        ("ball_spin_inertia_kg_m2", ball_spin_kg_m2)):
        require(math.isfinite(value) and value >= 0.0, name, value, "must be a finite inertia >= 0")
    require(rotor_kg_m2 > 0.0, "rotor_inertia_kg_m2", rotor_kg_m2, "must be positive")
    rc, ra = speed_ratios(geometry)
    if form == "energy":
        return rotor_kg_m2 + cage_kg_m2 * rc * rc + ball_spin_kg_m2 * ra * ra
    if form == "published":
        return rotor_kg_m2 + cage_kg_m2 * rc + ball_spin_kg_m2 * ra
    raise InputError("inertia_form", form, "must be 'energy' or 'published'")


# ------------------------------------------------------------------------------- main entry

def deceleration(pulse_times_s: np.ndarray, method: Method = "n-omega", alpha_percent: float = 1.0) -> Deceleration:
    """Deceleration at the start of free run by one of ``METHODS``."""
    t = validate_pulse_times(pulse_times_s)
    if method == "n-omega":
        return n_omega_method(speed_samples(t), alpha_percent)
    if method == "t-omega":
        return t_omega_method(speed_samples(t))
    if method == "model":
        return model_method(t)
    raise InputError("method", method, f"must be one of {', '.join(METHODS)}")


def friction_torque(pulse_times_s: np.ndarray, inertia_kg_m2: float, method: Method = "n-omega",
                    alpha_percent: float = 1.0) -> FreeRunResult:
    """T_s = I_eq |omega'| at the start of free run (reference sec. 5)."""
    require(math.isfinite(inertia_kg_m2) and inertia_kg_m2 > 0.0, "inertia_kg_m2", inertia_kg_m2,
            "must be a positive inertia")
    d = deceleration(pulse_times_s, method, alpha_percent)
    require(d.decel_rad_s2 > 0.0, "pulses", f"deceleration {d.decel_rad_s2:.4g} rad/s^2 ({d.method})",
            "the speed must decrease during a free run")
    return FreeRunResult(method=d.method, torque_Nm=inertia_kg_m2 * d.decel_rad_s2, omega0_rad_s=d.omega0_rad_s,
                         decel_rad_s2=d.decel_rad_s2, n_used=d.n_used, inertia_kg_m2=inertia_kg_m2, detail=d)


# ----------------------------------------------------------------------- synthetic coast-down

def simulate_pulse_times(inertia_kg_m2: float, torque_Nm: Callable[[float], float], omega0_rad_s: float,
                         omega_end_rad_s: float, clock_hz: float | None = None, jitter_s: float = 0.0,
                         rng: np.random.Generator | None = None) -> np.ndarray:
    """Pulse times (s) of a coast-down I d omega/dt = -T(omega) from omega0 (first pulse at t = 0)
    down to omega_end, one pulse per revolution, integrated in time independently of the model
    method (DOP853, rtol 1e-12, pulse instants by Newton on the dense output). Timing noise:
    Gaussian trigger jitter (s) and quantisation to a counter of ``clock_hz`` with a random phase."""
    require(inertia_kg_m2 > 0.0, "inertia_kg_m2", inertia_kg_m2, "must be positive")
    require(omega0_rad_s > omega_end_rad_s > 0.0, "omega_end_rad_s", omega_end_rad_s,
            f"must lie in (0, omega0 = {omega0_rad_s})")
    rng = np.random.default_rng() if rng is None else rng

    def rhs(_t: float, y: np.ndarray) -> list[float]:
        return [y[1], -torque_Nm(y[1]) / inertia_kg_m2]

    def slow(_t: float, y: np.ndarray) -> float:
        return y[1] - omega_end_rad_s
    slow.terminal = True  # type: ignore[attr-defined]
    t_guess = 10.0 * inertia_kg_m2 * omega0_rad_s / max(torque_Nm(omega_end_rad_s), 1e-300)
    sol = solve_ivp(rhs, (0.0, t_guess), [0.0, omega0_rad_s], method="DOP853", rtol=1e-12, atol=1e-12,
                    dense_output=True, events=slow)
    require(sol.status == 1, "torque_Nm", "law", "the coast-down did not reach omega_end (torque too small?)")
    t_stop = float(sol.t_events[0][0])
    theta_stop = float(sol.sol(t_stop)[0])
    targets = 2.0 * math.pi * np.arange(int(theta_stop / (2.0 * math.pi)) + 1, dtype=float)
    grid = np.linspace(0.0, t_stop, 20 * targets.size + 100)
    t = np.interp(targets, sol.sol(grid)[0], grid)
    for _ in range(4):
        th, om = sol.sol(t)
        t = t - (th - targets) / om
    t = t + jitter_s * rng.standard_normal(t.size) if jitter_s > 0.0 else t
    if clock_hz is not None:
        t = np.floor(t * clock_hz + rng.uniform()) / clock_hz
    return t
