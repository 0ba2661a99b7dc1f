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
from typing import Any

import numpy as np
from scipy.optimize import least_squares

from quenchsim.errors import InputError, require
from quenchsim.fitting.probe import ProbeCurve, ProbeModel, step_schedule
from quenchsim.materials import load_data_file, materials_dir

TIME_TEMPERATURE = "time_temperature"
RATE_TEMPERATURE = "rate_temperature"
HEATING_TOLERANCE_K = 2.0
"""A time/temperature curve may rise by this much above its running minimum (thermocouple noise); more is
heating, which a quenched probe's centre never does."""
LOWEST_REQUIRED_C = 300.0
"""A probe curve must reach 300 C: the data sheet's rate at 300 C and the start of the convection stage."""
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
        t = data.time_s
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
        rate = data.rate_C_s
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
            f"the curve never reaches {LOWEST_REQUIRED_C:g} C: record it down to 300 C or below")
    return data


def cooling_figures(time_s: np.ndarray, centre_C: np.ndarray) -> dict[str, float]:
    """The data-sheet figures of a centre curve: maximum cooling rate, its temperature, rate at 300 C, and
    the times to 600, 400 and 200 C (ISO 9950 reports)."""
    rate = -np.gradient(centre_C, time_s)
    i = int(np.argmax(rate))
    return {"CRmax_C_s": float(rate[i]), "T_CRmax_C": float(centre_C[i]),
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
    centre temperature. Only the starting point of the fit."""
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
    return np.clip(h_nodes, 50.0, 2.0e4)


@dataclass
class ProbeFit:
    """The fitted curve h(T_s) and how well it re-simulates the probe curve."""

    T_C: np.ndarray
    h_W_m2K: np.ndarray
    data: ProbeData
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
            misfit = np.interp(self.data.time_s, t, Tc) - self.data.temperature_C
        else:
            rate = -np.gradient(Tc, t)
            # the centre curve falls monotonically once it moves; interpolate the rate against -T
            down = np.maximum.accumulate(-Tc + 1e-9 * np.arange(Tc.size))
            misfit = np.interp(-self.data.temperature_C, down, rate) - self.data.rate_C_s
        return misfit / (self.sigma * np.sqrt(misfit.size))

    def residual(self, p: np.ndarray) -> np.ndarray:
        centre, surface_min, checkpoints = self._simulate(p)
        self._cache = (p.copy(), checkpoints, centre, surface_min)
        return np.concatenate([self.data_residual(centre), self.alpha * (self.D2 @ p)])

    def jacobian(self, p: np.ndarray, delta: float = 0.03) -> np.ndarray:
        if self._cache is None or not np.array_equal(self._cache[0], p):
            self.residual(p)
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
        problem = _Problem(data, model, nodes, alpha, sigma, step_schedule(t_curve, T_curve, centre_step_K=centre_step_K))
        sol = least_squares(problem.residual, p, jac=problem.jacobian, method="trf",
                            bounds=(np.log(20.0), np.log(5.0e4)), xtol=1e-3, ftol=1e-4, max_nfev=30)
        p = sol.x
        evaluations += int(sol.nfev)
        # linearised uncertainty of ln h (Gauss-Newton covariance; data residuals are scaled by sigma sqrt(N))
        J = problem.jacobian(p)
        steps_run += problem.steps_run / problem.step_ends.size
    _, _, centre, surface_min = problem._cache
    ends = problem.step_ends
    curve = ProbeCurve(np.concatenate([[0.0], ends]), np.concatenate([[model.start_C], centre]), np.array([]))
    misfit = problem.data_residual(centre) * sigma * np.sqrt(data.temperature_C.size)
    cov = np.linalg.pinv(J.T @ J) / data.temperature_C.size
    h_std = np.exp(p) * np.sqrt(np.clip(np.diag(cov), 0.0, None))
    if data.kind == TIME_TEMPERATURE:
        measured = cooling_figures(data.time_s, data.temperature_C)
    else:
        measured = rate_figures(data.temperature_C, data.rate_C_s)
    return ProbeFit(T_C=nodes, h_W_m2K=np.exp(p), data=data, bath_C=model.bath_C, curve=curve,
                    residual_rms=float(np.sqrt(np.mean(misfit**2))), residual_max=float(np.max(np.abs(misfit))),
                    residual_unit=unit, h_std_W_m2K=h_std,
                    identified_C=(float(surface_min.min()), float(model.start_C)), alpha=alpha, sigma=sigma,
                    iterations=evaluations, simulations=steps_run, seconds=time.perf_counter() - t0,
                    measured=measured, simulated=cooling_figures(curve.time_s, curve.centre_C))


def _time_curve(data: ProbeData, start_C: float) -> tuple[np.ndarray, np.ndarray]:
    """The data as a time/temperature curve (rate curves integrated), starting at t = 0."""
    if data.kind == TIME_TEMPERATURE:
        return data.time_s, data.temperature_C
    return time_of_rate_curve(data.temperature_C, data.rate_C_s, start_C), data.temperature_C
