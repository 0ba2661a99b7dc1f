"""A quenchant's still-bath HTC(T_surface) from its ISO 9950 probe curve, by inverse heat conduction.

Method (whole-curve, regularised; Beck & Arnold, Parameter Estimation in Engineering and Science, 1977,
ch. 7; Tikhonov regularisation of the inverse heat conduction problem: Beck, Blackwell & St. Clair,
Inverse Heat Conduction, 1985, ch. 4):

* h(T_surface) is piecewise linear through nodes every ``node_spacing_K`` (default 50 K) from just above the
  bath temperature to the start temperature, constant beyond; the unknowns are p_j = ln h_j (so h > 0);
* the probe is quenched with that h(T) on quenchsim's thermal solver (:mod:`quenchsim.fitting.probe`), and
  the misfit is taken in the form the data were given: centre temperature at the measured times
  (time/temperature curve) or centre cooling rate at the measured temperatures (rate/temperature curve),
  each divided by its noise level ``sigma`` and by sqrt(N);
* a Tikhonov term ``alpha * D2 p`` (second difference of ln h over the nodes) is appended to the residual,
  which fixes the nodes the data cannot see (below the lowest surface temperature reached) by straight
  extrapolation of ln h and damps the oscillation that thermocouple noise excites near the peak;
* the residual is minimised by scipy.optimize.least_squares (trust-region reflective) from a quasi-steady
  estimate (:func:`quasi_steady_htc`), with a finite-difference Jacobian in which a node's column is
  re-simulated only from the first step at which the surface reaches that node's support (checkpoints of
  the base run) -- the run before is unchanged, so the column is exact and costs a fraction of a run.

The verification (tests/test_fitting_quenchant.py): a known h(T) drives a finer probe model, noise is added,
and the fit recovers h over 300-800 C.
"""

from __future__ import annotations

import copy
import csv
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, cast

import numpy as np
from scipy.optimize import least_squares

from quenchsim.bath.quenchant import STILL_BATH_KIND
from quenchsim.errors import InputError, require
from quenchsim.fitting.probe import ProbeCurve, ProbeModel, step_schedule
from quenchsim.fitting.probe_bounds import MAX_OIL_HTC_W_M2K, kelvin_hint
from quenchsim.materials import load_data_file

TIME_TEMPERATURE = "time_temperature"
RATE_TEMPERATURE = "rate_temperature"
HEATING_TOLERANCE_K = 2.0
"""A time/temperature curve may rise by this much above its running minimum (thermocouple noise); more is
heating, which a quenched probe's centre never does."""
LOWEST_REQUIRED_C = 300.0
"""A probe curve must reach 300 C: the data sheet's rate at 300 C and the start of the convection stage."""
REFERENCE_SPACING_K = 50.0
"""Node spacing at which ``alpha`` is the weight of the second difference of ln h (other spacings are scaled)."""
SURFACE_MARGIN_K = 20.0
"""A node's Jacobian column is re-simulated from the first step whose end has a surface point within this
margin of the node's support (the solver's iterates may dip a little below the converged step)."""


@dataclass(frozen=True)
class ProbeData:
    """A measured probe curve: centre temperature vs time, or centre cooling rate (>= 0) vs temperature."""

    kind: str
    temperature_C: np.ndarray
    time_s: np.ndarray | None = None
    rate_C_s: np.ndarray | None = None

    @property
    def times_s(self) -> np.ndarray:
        """``time_s`` of a time/temperature curve (always set for that kind)."""
        return cast(np.ndarray, self.time_s)

    @property
    def rates_C_s(self) -> np.ndarray:
        """``rate_C_s`` of a rate/temperature curve (always set for that kind)."""
        return cast(np.ndarray, self.rate_C_s)


def _column(rows: list[dict[str, str]], key: str, path: str) -> np.ndarray:
    values = []
    for i, row in enumerate(rows, start=2):
        try:
            values.append(float(row[key]))
        except (TypeError, ValueError):
            raise InputError(f"{path}: row {i} {key}", row[key], "must be a number") from None
    return np.asarray(values)


def read_probe_csv(path: str | Path) -> ProbeData:
    """Read a probe curve from CSV with a header ``time_s,temperature_C`` or ``temperature_C,rate_C_s``
    (lines starting with ``#`` are comments) and check it (:func:`check_probe_data`)."""
    p = Path(path)
    if not p.is_file():
        raise InputError("CURVE", str(p), "no such file")
    lines = [ln for ln in p.read_text().splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    rows = list(csv.DictReader(lines))
    header = set(rows[0]) if rows else set()
    if {"time_s", "temperature_C"} <= header:
        data = ProbeData(TIME_TEMPERATURE, _column(rows, "temperature_C", p.name), time_s=_column(rows, "time_s", p.name))
    elif {"temperature_C", "rate_C_s"} <= header:
        data = ProbeData(RATE_TEMPERATURE, _column(rows, "temperature_C", p.name), rate_C_s=_column(rows, "rate_C_s", p.name))
    else:
        raise InputError(f"{p.name}: header", sorted(header), "needs columns time_s,temperature_C or temperature_C,rate_C_s")
    return check_probe_data(data, p.name)


def check_probe_data(data: ProbeData, where: str = "curve") -> ProbeData:
    """One-line InputErrors for a curve the probe cannot have produced (field, value, rule)."""
    T = data.temperature_C
    require(T.size >= 5, f"{where}: temperature_C", T.size, "needs at least 5 points")
    require(bool(np.all(np.isfinite(T))), f"{where}: temperature_C", "non-finite", "values must be finite")
    if data.kind == TIME_TEMPERATURE:
        t = data.times_s
        bad = np.flatnonzero(np.diff(t) <= 0)
        if bad.size:
            i = int(bad[0]) + 1
            raise InputError(f"{where}: time_s (point {i + 1})", float(t[i]),
                             f"must increase strictly (previous {float(t[i - 1]):g} s)")
        require(t[0] >= 0, f"{where}: time_s (point 1)", float(t[0]), "must be >= 0 (0 = immersion)")
        rise = T - np.minimum.accumulate(T)
        i = int(np.argmax(rise))
        require(rise[i] <= HEATING_TOLERANCE_K, f"{where}: temperature_C (point {i + 1}, t = {float(t[i]):g} s)",
                float(T[i]), f"the probe heats up: {rise[i]:.1f} K above the lowest earlier value "
                             f"{float(T[i] - rise[i]):g} C (a quenched probe only cools; tolerance {HEATING_TOLERANCE_K:g} K)")
    else:
        rate = data.rates_C_s
        bad = np.flatnonzero(np.diff(T) >= 0)
        if bad.size:
            i = int(bad[0]) + 1
            raise InputError(f"{where}: temperature_C (point {i + 1})", float(T[i]),
                             f"must decrease strictly down a rate curve (previous {float(T[i - 1]):g} C)")
        neg = np.flatnonzero(rate < 0)
        if neg.size:
            i = int(neg[0])
            raise InputError(f"{where}: rate_C_s (point {i + 1}, T = {float(T[i]):g} C)", float(rate[i]),
                             "the probe heats up: a cooling rate must be >= 0")
    require(float(T.min()) <= LOWEST_REQUIRED_C, f"{where}: temperature_C (lowest)", float(T.min()),
            f"the curve never reaches {LOWEST_REQUIRED_C:g} C: record it down to 300 C or below{kelvin_hint(T)}")
    return data


def cooling_figures(time_s: np.ndarray, centre_C: np.ndarray) -> dict[str, float]:
    """The data-sheet figures of a centre curve: maximum cooling rate, its temperature, rate at 300 C, and
    the times to 600, 400 and 200 C (ISO 9950 reports)."""
    rate = -np.gradient(centre_C, time_s)
    i = int(np.clip(np.argmax(rate), 1, rate.size - 2))
    # vertex of the parabola through the three samples around the maximum (smooth in the curve's parameters)
    t3, r3 = time_s[i - 1:i + 2], rate[i - 1:i + 2]
    a, b, c = np.polyfit(t3 - t3[1], r3, 2)
    dt_peak = float(np.clip(-b / (2 * a), t3[0] - t3[1], t3[2] - t3[1])) if a < 0 else 0.0
    rate_max = float(c + b * dt_peak + a * dt_peak**2) if a < 0 else float(r3[1])
    T_at_max = float(np.interp(t3[1] + dt_peak, time_s, centre_C))
    return {"CRmax_C_s": rate_max, "T_CRmax_C": T_at_max,
            "CR300_C_s": _at_temperature(centre_C, rate, 300.0),
            **{f"t_to_{T:.0f}C_s": _at_temperature(centre_C, time_s, T) for T in (600.0, 400.0, 200.0)}}


def rate_figures(temperature_C: np.ndarray, rate_C_s: np.ndarray) -> dict[str, float]:
    """Maximum rate, its temperature and the rate at 300 C of a rate/temperature curve."""
    i = int(np.argmax(rate_C_s))
    return {"CRmax_C_s": float(rate_C_s[i]), "T_CRmax_C": float(temperature_C[i]),
            "CR300_C_s": _at_temperature(temperature_C, rate_C_s, 300.0)}


def _at_temperature(T_C: np.ndarray, values: np.ndarray, target_C: float) -> float:
    """``values`` where a falling curve first reaches ``target_C`` (linear; NaN if never)."""
    below = np.flatnonzero(T_C <= target_C)
    if below.size == 0:
        return float("nan")
    k = int(below[0])
    if k == 0:
        return float(values[0])
    w = (T_C[k - 1] - target_C) / (T_C[k - 1] - T_C[k])
    return float(values[k - 1] + w * (values[k] - values[k - 1]))


def time_of_rate_curve(temperature_C: np.ndarray, rate_C_s: np.ndarray, start_C: float) -> np.ndarray:
    """Times of a rate/temperature curve, t = integral dT / rate from the start temperature (trapezoids in
    1/rate; the rate is floored at 1 % of its maximum so the near-zero rate at the start stays finite).
    Used for the step schedule and the plots, not for the misfit."""
    rate = np.maximum(rate_C_s, 0.01 * float(np.max(rate_C_s)))
    T = np.concatenate([[start_C], temperature_C]) if temperature_C[0] < start_C else temperature_C
    r = np.concatenate([[rate[0]], rate]) if T.size > temperature_C.size else rate
    dt = 0.5 * (1.0 / r[1:] + 1.0 / r[:-1]) * -np.diff(T)
    t = np.concatenate([[0.0], np.cumsum(dt)])
    return t[-temperature_C.size:]


def default_nodes(bath_C: float, start_C: float, spacing_K: float = 50.0) -> np.ndarray:
    """Nodes of h(T_s): multiples of ``spacing_K`` above the bath (at least 30 K above it), up to the start."""
    lo = np.ceil((bath_C + 30.0) / spacing_K) * spacing_K
    nodes = np.arange(lo, start_C - 0.5 * spacing_K + 1e-9, spacing_K)
    return np.append(nodes, start_C)


def quasi_steady_htc(time_s: np.ndarray, centre_C: np.ndarray, model: ProbeModel,
                     nodes_C: np.ndarray) -> np.ndarray:
    """A first estimate of h(T_s) from the centre curve, in the regular (quasi-steady) regime of a long
    cylinder: every point cools at the centre's rate, so the surface flux is q = rho c_p (V/A) dT/dt and the
    parabolic profile gives T_s = T_c - q R / (2 k) (uniform heat sink in a cylinder). Properties at the
    centre temperature. Only the starting point of the fit, clipped to 50 W/m2K .. :data:`MAX_OIL_HTC_W_M2K`."""
    spec = model.spec
    R, L = spec.radius_m, spec.length_m
    v_over_a = R * L / (2.0 * (L + R))
    rate = np.maximum(-np.gradient(centre_C, time_s), 0.0)
    props = spec.properties
    rho_c = props.density_kg_m3(centre_C) * props.specific_heat_J_kgK(centre_C)
    q = rho_c * v_over_a * rate
    Ts = centre_C - q * R / (2.0 * props.conductivity_W_mK(centre_C))
    ok = (Ts - model.bath_C > 20.0) & (rate > 0)
    h = q[ok] / (Ts[ok] - model.bath_C)
    order = np.argsort(Ts[ok])
    h_nodes = np.interp(nodes_C, Ts[ok][order], h[order])
    return np.clip(h_nodes, 50.0, MAX_OIL_HTC_W_M2K)


@dataclass
class ProbeFit:
    """The fitted curve h(T_s) and how well it re-simulates the probe curve (``data``) or, for the data-sheet
    shortcut, the published figures (``data`` None, ``measured`` the figures)."""

    T_C: np.ndarray
    h_W_m2K: np.ndarray
    data: ProbeData | None
    bath_C: float
    curve: ProbeCurve
    residual_rms: float
    residual_max: float
    residual_unit: str
    h_std_W_m2K: np.ndarray
    identified_C: tuple[float, float]
    alpha: float
    sigma: float
    iterations: int
    simulations: float
    seconds: float
    measured: dict[str, float] = field(default_factory=dict)
    simulated: dict[str, float] = field(default_factory=dict)
    shape: "CurveShape | None" = None


class _Problem:
    """Residuals and Jacobian of the whole-curve fit (one probe model, one fixed step schedule)."""

    def __init__(self, data: ProbeData, model: ProbeModel, nodes_C: np.ndarray, alpha: float, sigma: float,
                 step_ends_s: np.ndarray) -> None:
        self.data, self.model, self.nodes = data, model, nodes_C
        self.step_ends = step_ends_s
        self.alpha, self.sigma = alpha, sigma
        n = nodes_C.size
        self.D2 = np.diff(np.eye(n), n=2, axis=0)
        self._cache: tuple[np.ndarray, list[Any], np.ndarray, np.ndarray] | None = None
        self.steps_run = 0

    def _simulate(self, p: np.ndarray) -> tuple[np.ndarray, np.ndarray, list[Any]]:
        solver = self.model.start()
        checkpoints: list[Any] = []
        centre, _ = self.model.march(solver, self.model.htc(self.nodes, np.exp(p)), self.step_ends, checkpoints)
        self.steps_run += self.step_ends.size
        surface_min = np.array([float(self.model.fe.at_facet_qp(c.T).min()) for c in checkpoints[1:]] +
                               [float(self.model.fe.at_facet_qp(solver.T).min())])
        return centre, surface_min, checkpoints

    def data_residual(self, centre: np.ndarray) -> np.ndarray:
        t = np.concatenate([[0.0], self.step_ends])
        Tc = np.concatenate([[self.model.start_C], centre])
        if self.data.kind == TIME_TEMPERATURE:
            misfit = np.interp(self.data.times_s, t, Tc) - self.data.temperature_C
        else:
            rate = -np.gradient(Tc, t)
            # the centre curve falls monotonically once it moves; interpolate the rate against -T
            down = np.maximum.accumulate(-Tc + 1e-9 * np.arange(Tc.size))
            misfit = np.interp(-self.data.temperature_C, down, rate) - self.data.rates_C_s
        return misfit / (self.sigma * np.sqrt(misfit.size))

    def residual(self, p: np.ndarray) -> np.ndarray:
        centre, surface_min, checkpoints = self._simulate(p)
        self._cache = (p.copy(), checkpoints, centre, surface_min)
        return np.concatenate([self.data_residual(centre), self.alpha * (self.D2 @ p)])

    def jacobian(self, p: np.ndarray, delta: float = 0.03) -> np.ndarray:
        if self._cache is None or not np.array_equal(self._cache[0], p):
            self.residual(p)
        assert self._cache is not None   # residual() has just filled it
        _, checkpoints, centre, surface_min = self._cache
        base = self.data_residual(centre)
        J = np.zeros((base.size + self.D2.shape[0], p.size))
        upper = np.append(self.nodes[1:], np.inf)  # top of each node's hat support
        for j in range(p.size):
            hit = np.flatnonzero(surface_min < upper[j] + SURFACE_MARGIN_K)
            if hit.size == 0:
                continue  # the surface never reaches this node: no sensitivity
            k = int(hit[0])
            q = p.copy()
            q[j] += delta
            solver = copy.copy(checkpoints[k])
            tail, _ = self.model.march(solver, self.model.htc(self.nodes, np.exp(q)), self.step_ends[k:])
            self.steps_run += self.step_ends.size - k
            J[:base.size, j] = (self.data_residual(np.concatenate([centre[:k], tail])) - base) / delta
        J[base.size:] = self.alpha * self.D2
        return J


def fit_probe_curve(data: ProbeData, *, bath_C: float | None = None, model: ProbeModel | None = None,
                    alpha: float = 0.2, sigma: float | None = None,
                    levels: tuple[tuple[float, float], ...] = ((100.0, 4.0), (50.0, 1.0))) -> ProbeFit:
    """Fit h(T_surface) so that the probe model reproduces ``data`` (see the module docstring).

    ``sigma``: noise level of the data (default 1 K for temperatures, 2 K/s for rates); ``alpha``: weight of
    the second-difference regularisation of ln h (set with the synthetic verification of
    tests/test_fitting_quenchant.py, never with an oil); ``levels``: (node spacing K, step-schedule limit K) of
    each stage -- the fit is solved with coarse nodes and steps first and finished with the last, finer ones,
    each stage starting from the previous solution interpolated onto its nodes."""
    model = model or ProbeModel(bath_temperature_C=bath_C)
    if bath_C is not None and model.bath_C != bath_C:
        model = ProbeModel(model.spec, model.mesh_settings, model.start_C, bath_C)
    sigma = (1.0 if data.kind == TIME_TEMPERATURE else 2.0) if sigma is None else sigma
    unit = "K" if data.kind == TIME_TEMPERATURE else "K/s"
    t_curve, T_curve = _time_curve(data, model.start_C)
    if data.kind == RATE_TEMPERATURE:
        # run 30 % past the integrated time of the lowest point so that the simulation reaches it
        t_curve, T_curve = np.append(t_curve, 1.3 * t_curve[-1]), np.append(T_curve, T_curve[-1])
    if t_curve[0] > 0:
        t_curve, T_curve = np.concatenate([[0.0], t_curve]), np.concatenate([[model.start_C], T_curve])
    t0 = time.perf_counter()
    nodes = default_nodes(model.bath_C, model.start_C, levels[0][0])
    p = np.log(quasi_steady_htc(t_curve, T_curve, model, nodes))
    steps_run, evaluations = 0.0, 0
    for spacing_K, centre_step_K in levels:
        p, nodes = np.interp(default_nodes(model.bath_C, model.start_C, spacing_K), nodes, p), \
            default_nodes(model.bath_C, model.start_C, spacing_K)
        # the same smoothing of ln h(T) whatever the node spacing: the penalty approximates
        # alpha^2 * 50 K^3 * integral (d2 ln h / dT2)^2 dT, i.e. alpha is the weight at the 50 K spacing
        alpha_nodes = alpha * (REFERENCE_SPACING_K / spacing_K) ** 1.5
        problem = _Problem(data, model, nodes, alpha_nodes, sigma,
                           step_schedule(t_curve, T_curve, centre_step_K=centre_step_K))
        sol = least_squares(problem.residual, p, jac=problem.jacobian, method="trf",
                            bounds=(np.log(20.0), np.log(5.0e4)), xtol=1e-3, ftol=1e-4, max_nfev=30)
        p = sol.x
        evaluations += int(sol.nfev)
        # linearised uncertainty of ln h (Gauss-Newton covariance; data residuals are scaled by sigma sqrt(N))
        J = problem.jacobian(p)
        steps_run += problem.steps_run / problem.step_ends.size
    assert problem._cache is not None   # jacobian() above ran the residual
    _, _, centre, surface_min = problem._cache
    ends = problem.step_ends
    curve = ProbeCurve(np.concatenate([[0.0], ends]), np.concatenate([[model.start_C], centre]), np.array([]))
    misfit = problem.data_residual(centre) * sigma * np.sqrt(data.temperature_C.size)
    cov = np.linalg.pinv(J.T @ J) / data.temperature_C.size
    h_std = np.exp(p) * np.sqrt(np.clip(np.diag(cov), 0.0, None))
    if data.kind == TIME_TEMPERATURE:
        measured = cooling_figures(data.times_s, data.temperature_C)
    else:
        measured = rate_figures(data.temperature_C, data.rates_C_s)
    return ProbeFit(T_C=nodes, h_W_m2K=np.exp(p), data=data, bath_C=model.bath_C, curve=curve,
                    residual_rms=float(np.sqrt(np.mean(misfit**2))), residual_max=float(np.max(np.abs(misfit))),
                    residual_unit=unit, h_std_W_m2K=h_std,
                    identified_C=(float(surface_min.min()), float(model.start_C)), alpha=alpha, sigma=sigma,
                    iterations=evaluations, simulations=steps_run, seconds=time.perf_counter() - t0,
                    measured=measured, simulated=cooling_figures(curve.time_s, curve.centre_C))


def _time_curve(data: ProbeData, start_C: float) -> tuple[np.ndarray, np.ndarray]:
    """The data as a time/temperature curve (rate curves integrated), starting at t = 0."""
    if data.kind == TIME_TEMPERATURE:
        return data.times_s, data.temperature_C
    return time_of_rate_curve(data.temperature_C, data.rates_C_s, start_C), data.temperature_C


# --- the data-sheet shortcut ------------------------------------------------------------------------------

FIGURES = ("CRmax_C_s", "T_CRmax_C", "CR300_C_s", "t_to_600C_s", "t_to_400C_s", "t_to_200C_s")
"""The ISO 9950 / ASTM D6200 report figures a data sheet prints (D6200 section 1.1 of materials/SOURCES.md)."""
SHAPE_PARAMETERS = ("h_film_W_m2K", "transition_K", "h_peak_W_m2K", "T_peak_C", "h_300_W_m2K", "h_low_W_m2K")


@dataclass(frozen=True)
class CurveShape:
    """h(T_s) of the data-sheet shortcut, piecewise linear through (T_low, h_low), (300 C, h_300),
    (T_peak, h_peak), (T_peak + transition, h_film) and constant h_film above: a film plateau, a transition
    up to the boiling peak, the fall through nucleate boiling to convection. T_low is 30 K above the bath."""

    h_film_W_m2K: float
    transition_K: float
    h_peak_W_m2K: float
    T_peak_C: float
    h_300_W_m2K: float
    h_low_W_m2K: float

    def nodes(self, bath_C: float, start_C: float) -> tuple[np.ndarray, np.ndarray]:
        T_low = bath_C + 30.0
        T_peak = float(np.clip(self.T_peak_C, 320.0, start_C - 60.0))
        T_top = min(T_peak + max(self.transition_K, 10.0), start_C - 5.0)
        T = [T_low, 300.0, T_peak, T_top, start_C]
        h = [self.h_low_W_m2K, self.h_300_W_m2K, self.h_peak_W_m2K, self.h_film_W_m2K, self.h_film_W_m2K]
        if T_low >= 300.0:  # hot oil: the bath is above 270 C -- no separate low node
            T, h = T[1:], h[1:]
        return np.asarray(T), np.asarray(h)


def fit_figures(figures: dict[str, float], *, bath_C: float, shape: CurveShape, model: ProbeModel | None = None,
                centre_step_K: float = 2.0) -> ProbeFit:
    """The data-sheet shortcut: fit the free parameters of ``shape`` so that the probe model reproduces the
    given report figures (at least CRmax_C_s, T_CRmax_C and CR300_C_s). With the three rate figures only,
    h_peak, T_peak and h_300 are fitted and the film level, transition width and low-temperature level keep
    the ratios of ``shape``; each time figure (t_to_600/400/200C_s) frees one more parameter (film level,
    transition width, low level, in that order). The result is an approximation stated as such."""
    for key in FIGURES[:3]:
        require(key in figures and np.isfinite(figures[key]), f"figures.{key}", figures.get(key),
                "the data-sheet shortcut needs CRmax_C_s, T_CRmax_C and CR300_C_s")
    for key, value in figures.items():
        require(key in FIGURES, f"figures.{key}", value, f"unknown figure; known: {', '.join(FIGURES)}")
        require(np.isfinite(value) and value > 0, f"figures.{key}", value, "must be a positive number")
    require(300.0 < figures["T_CRmax_C"] < 850.0, "figures.T_CRmax_C", figures["T_CRmax_C"], "must lie between 300 and 850 C")
    model = model or ProbeModel(bath_temperature_C=bath_C)
    if model.bath_C != bath_C:
        model = ProbeModel(model.spec, model.mesh_settings, model.start_C, bath_C)
    times = [k for k in FIGURES[3:] if k in figures]
    free = ["h_peak_W_m2K", "T_peak_C", "h_300_W_m2K"] + ["h_film_W_m2K", "transition_K", "h_low_W_m2K"][:len(times)]
    keys = list(FIGURES[:3]) + times
    target = np.array([figures[k] for k in keys])
    scale = np.array([10.0 if k == "T_CRmax_C" else 0.02 * figures[k] for k in keys])
    base = {f: getattr(shape, f) for f in SHAPE_PARAMETERS}

    def shape_of(x: np.ndarray) -> CurveShape:
        values = dict(base)
        for name, v in zip(free, x):
            values[name] = float(v) if name in ("T_peak_C", "transition_K") else float(np.exp(v))
        if "h_film_W_m2K" not in free:
            values["h_film_W_m2K"] = shape.h_film_W_m2K / shape.h_peak_W_m2K * values["h_peak_W_m2K"]
        if "h_low_W_m2K" not in free:
            values["h_low_W_m2K"] = shape.h_low_W_m2K / shape.h_300_W_m2K * values["h_300_W_m2K"]
        return CurveShape(**values)

    x0 = np.array([getattr(shape, f) if f in ("T_peak_C", "transition_K") else np.log(getattr(shape, f)) for f in free])
    t0 = time.perf_counter()
    # step schedule from a first run of the starting shape (fixed afterwards, so the residual is smooth)
    rough = model.cool(*shape.nodes(bath_C, model.start_C), np.arange(0.02, 300.0, 0.02))
    t_end = 1.3 * float(np.interp(-max(bath_C + 60.0, 150.0), -rough.centre_C, rough.time_s))
    keep = rough.time_s <= t_end
    ends = step_schedule(rough.time_s[keep], rough.centre_C[keep], centre_step_K=centre_step_K)
    runs = [0]

    def simulate(x: np.ndarray) -> ProbeCurve:
        runs[0] += 1
        return model.cool(*shape_of(x).nodes(bath_C, model.start_C), ends)

    def residual(x: np.ndarray) -> np.ndarray:
        curve = simulate(x)
        got = cooling_figures(curve.time_s, curve.centre_C)
        return (np.array([got[k] for k in keys]) - target) / scale

    lo = [np.log(20.0) if f not in ("T_peak_C", "transition_K") else (320.0 if f == "T_peak_C" else 10.0) for f in free]
    hi = [np.log(5.0e4) if f not in ("T_peak_C", "transition_K") else (model.start_C - 60.0 if f == "T_peak_C" else 300.0)
          for f in free]
    sol = least_squares(residual, np.clip(x0, lo, hi), bounds=(lo, hi), diff_step=1e-2, xtol=1e-4, max_nfev=60)
    fitted = shape_of(sol.x)
    T_nodes, h_nodes = fitted.nodes(bath_C, model.start_C)
    curve = simulate(sol.x)
    simulated = cooling_figures(curve.time_s, curve.centre_C)
    misfit = np.array([simulated[k] - figures[k] for k in keys])
    return ProbeFit(T_C=T_nodes, h_W_m2K=h_nodes, data=None, bath_C=bath_C, curve=curve,
                    residual_rms=float(np.sqrt(np.mean((misfit / scale) ** 2))),
                    residual_max=float(np.max(np.abs(misfit / scale))), residual_unit="figure scale",
                    h_std_W_m2K=np.full(T_nodes.size, np.nan), identified_C=(float(curve.surface_C.min()), model.start_C),
                    alpha=0.0, sigma=0.0, iterations=int(sol.nfev), simulations=float(runs[0]),
                    seconds=time.perf_counter() - t0, measured={k: float(figures[k]) for k in keys}, simulated=simulated,
                    shape=fitted)


SHORTCUT_SHAPE_OIL = "astm_d6200_fast_oil"
"""The library oil whose fitted shape (film/peak and low/300 C ratios, transition width) the three-number
shortcut keeps: the one oil fitted to all six published D6200 figures (materials/SOURCES.md)."""


def default_shape(name: str = SHORTCUT_SHAPE_OIL) -> CurveShape:
    """The ``[shape]`` table of a quenchant file (a data-sheet fit) or of a start-shape file (``quenchants/data/``,
    e.g. ``bt2013_start_shape``), by name or path."""
    data = load_data_file(name, ("quenchants", "quenchants/data"), "--shape-from")
    shape = data.get("shape")
    if not isinstance(shape, dict):
        raise InputError("--shape-from", name, "has no [shape] table (h_film_W_m2K, transition_K, h_peak_W_m2K, "
                                               "T_peak_C, h_300_W_m2K, h_low_W_m2K)")
    values = {}
    for key in SHAPE_PARAMETERS:
        spec = shape.get(key)
        value: Any = spec.get("value") if isinstance(spec, dict) else spec   # checked by require: a number
        require(isinstance(value, (int, float)) and value > 0, f"{name}.shape.{key}", value, "must be a positive number")
        values[key] = float(value)
    return CurveShape(**values)


# --- the quenchant file: a still-bath curve h(T_surface) ----------------------------------------------------


def quenchant_document(fit: ProbeFit, *, name: str, source: str, tag: str, agitation_m_s: float = 0.0,
                       description: str = "", data_file: str = "") -> dict[str, Any]:
    """The TOML document of a fitted quenchant (see materials/quenchants/README.md for the keys)."""
    require(source.strip() != "", "--source", source, "a quenchant file needs the source of its probe curve")
    if fit.data is None:
        method = ("data-sheet shortcut: the parameters of a five-node h(T_s) shape fitted so that the ISO 9950 probe "
                  "model reproduces the published figures -- an approximation, not an inverse of a measured curve")
    else:
        method = (f"whole-curve inverse heat conduction on the ISO 9950 probe model: piecewise-linear ln h(T_s), "
                  f"Tikhonov second difference alpha = {fit.alpha:g}, noise sigma = {fit.sigma:g} {fit.residual_unit}")
    doc: dict[str, Any] = {
        "name": name, "kind": STILL_BATH_KIND, "description": description, "source": source,
        "test": {"probe": "iso9950_probe_inconel600", "bath_temperature_C": float(fit.bath_C),
                 "agitation_m_s": float(agitation_m_s), "start_temperature_C": float(fit.curve.centre_C[0])},
        "htc": {"T_C": [round(float(v), 2) for v in fit.T_C], "h_W_m2K": [round(float(v), 1) for v in fit.h_W_m2K],
                "identified_T_C": [round(fit.identified_C[0], 1), round(fit.identified_C[1], 1)],
                "method": method, "source": f"fitted by quenchsim quenchant from the probe data of: {source}"},
        "fit": {"residual_rms": fit.residual_rms, "residual_max": fit.residual_max, "residual_unit": fit.residual_unit,
                "evaluations": fit.iterations, "seconds": round(fit.seconds, 1),
                "measured": fit.measured, "simulated": {k: round(v, 3) for k, v in fit.simulated.items()}},
    }
    if np.all(np.isfinite(fit.h_std_W_m2K)):
        doc["htc"]["h_std_W_m2K"] = [round(float(v), 1) for v in fit.h_std_W_m2K]
    curve: dict[str, Any] = {"tag": tag, "data_file": data_file}
    if fit.data is None:
        curve["kind"] = "figures"
    elif fit.data.kind == TIME_TEMPERATURE:
        t = fit.data.times_s
        curve.update(kind=TIME_TEMPERATURE, time_s=t.tolist(), temperature_C=fit.data.temperature_C.tolist(),
                     resimulated_C=np.round(np.interp(t, fit.curve.time_s, fit.curve.centre_C), 2).tolist())
    else:
        sim_rate = -np.gradient(fit.curve.centre_C, fit.curve.time_s)
        down = np.maximum.accumulate(-fit.curve.centre_C + 1e-9 * np.arange(fit.curve.centre_C.size))
        curve.update(kind=RATE_TEMPERATURE, temperature_C=fit.data.temperature_C.tolist(),
                     rate_C_s=fit.data.rates_C_s.tolist(),
                     resimulated_rate_C_s=np.round(np.interp(-fit.data.temperature_C, down, sim_rate), 3).tolist())
    doc["curve"] = curve
    if fit.shape is not None:
        doc["shape"] = {k: round(float(getattr(fit.shape, k)), 2) for k in SHAPE_PARAMETERS}
    doc["resimulated"] = {"time_s": np.round(fit.curve.time_s, 4).tolist(),
                          "centre_C": np.round(fit.curve.centre_C, 3).tolist()}
    return doc


def write_quenchant(path: str | Path, doc: dict[str, Any]) -> Path:
    import tomli_w

    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(tomli_w.dumps(doc))
    return p
