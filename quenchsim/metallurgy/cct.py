"""Continuous-cooling-transformation (CCT) curves implied by a steel's kinetics.

Each cooling rate is one point of a vectorised :func:`quenchsim.metallurgy.advance` run:
T_i(t) = max(T_start - rate_i t, T_end) on a geometric time grid (every point sees steps that are a
small fraction of its own cooling time). Lines as on a catalogue CCT diagram: a product's start is
where it reaches 1 % of the volume, its finish where it reaches 99 % of the amount it ends with
(drawn only where that amount exceeds 2 %); martensite starts at Ms on every rate that keeps austenite.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from quenchsim.materials.properties import PHASES
from quenchsim.metallurgy.hardness import hardness_HV, hv_to_hrc
from quenchsim.metallurgy.kinetics import Kinetics
from quenchsim.metallurgy.transform import advance, initial_state

START_FRACTION = 0.01
"""Volume fraction that marks a product's start line (the usual 1 % of TTT/CCT diagrams)."""
FINISH_SHARE = 0.99
"""Share of a product's final amount that marks its finish line."""
MIN_FINISH_AMOUNT = 0.02
"""Smallest final amount of a product for which a finish line is drawn."""


@dataclass(frozen=True)
class CCTDiagram:
    """CCT curves: for each cooling rate (C/s) the start/finish time (s from T_start) and temperature (C) of each
    diffusional product (NaN where none), the final phase fractions and the as-quenched hardness."""

    material: str
    T_aust_C: float
    T_start_C: float
    T_end_C: float
    Ms_C: float
    rates_C_s: np.ndarray
    start_time_s: dict[str, np.ndarray]
    start_T_C: dict[str, np.ndarray]
    finish_time_s: dict[str, np.ndarray]
    finish_T_C: dict[str, np.ndarray]
    final_fractions: dict[str, np.ndarray]
    hardness_HV: np.ndarray
    hardness_HRC: np.ndarray


def crossing_time(t: np.ndarray, X: np.ndarray, level: np.ndarray) -> np.ndarray:
    """First time each column of X (steps x points) reaches ``level`` (linear between grid times; NaN if never)."""
    reached = X >= level
    k = np.argmax(reached, axis=0)
    ok = reached[k, np.arange(X.shape[1])] & (k > 0)
    cols = np.arange(X.shape[1])
    k0 = np.maximum(k - 1, 0)
    X0, X1 = X[k0, cols], X[k, cols]
    w = np.where(X1 > X0, (level - X0) / np.where(X1 > X0, X1 - X0, 1.0), 1.0)
    return np.where(ok, t[k0] + w * (t[k] - t[k0]), np.nan)


def cct_diagram(kin: Kinetics, rates_C_s: np.ndarray, T_start_C: float, T_end_C: float = 20.0,
                growth: float = 1.02) -> CCTDiagram:
    """CCT curves of ``kin`` for linear cooling from T_start_C to T_end_C at each rate (C/s).

    ``growth`` is the ratio of successive time-grid steps (1.02: each point's temperature steps are
    at most ~2 % of the drop so far, refined further by the sub-stepping of advance()).
    """
    rates = np.atleast_1d(np.asarray(rates_C_s, dtype=float))
    if rates.ndim != 1 or np.any(~np.isfinite(rates)) or np.any(rates <= 0):
        raise ValueError("cct_diagram: rates must be positive and finite")
    if not T_end_C < T_start_C:
        raise ValueError("cct_diagram: T_end_C must be below T_start_C")
    drop = T_start_C - T_end_C
    t_first, t_last = 0.05 / rates.max(), drop / rates.min()
    n_steps = int(np.ceil(np.log(t_last / t_first) / np.log(growth))) + 1
    times = np.concatenate([[0.0], t_first * growth ** np.arange(n_steps)])
    state = initial_state(rates.shape, kin)
    history = {p: [np.zeros_like(rates)] for p in PHASES[1:]}
    T_prev = np.full_like(rates, T_start_C)
    for k in range(1, times.size):
        T_now = np.maximum(T_start_C - rates * times[k], T_end_C)
        state = advance(state, kin, T_prev, T_now, times[k] - times[k - 1])
        for p in history:
            history[p].append(state.fractions[p])
        T_prev = T_now
    start_t, start_T, finish_t, finish_T = {}, {}, {}, {}
    for p in kin.reactions:
        X = np.array(history[p])
        final = X[-1]
        start_t[p] = crossing_time(times, X, np.full_like(final, START_FRACTION))
        finish_t[p] = np.where(final > MIN_FINISH_AMOUNT, crossing_time(times, X, FINISH_SHARE * final), np.nan)
        start_T[p] = np.maximum(T_start_C - rates * start_t[p], T_end_C)
        finish_T[p] = np.maximum(T_start_C - rates * finish_t[p], T_end_C)
    hv = hardness_HV(state, kin)
    return CCTDiagram(material=kin.material, T_aust_C=kin.T_aust_C, T_start_C=T_start_C, T_end_C=T_end_C,
                      Ms_C=kin.Ms_C, rates_C_s=rates, start_time_s=start_t, start_T_C=start_T, finish_time_s=finish_t,
                      finish_T_C=finish_T, final_fractions={p: state.fractions[p].copy() for p in PHASES},
                      hardness_HV=hv, hardness_HRC=hv_to_hrc(hv))


def critical_rate_C_s(kin: Kinetics, max_diffusional: float, T_start_C: float, T_end_C: float = 20.0,
                      bounds_C_s: tuple[float, float] = (0.01, 3000.0), rel_tol: float = 0.01) -> float:
    """Slowest linear cooling rate that leaves at most ``max_diffusional`` pearlite + bainite (bisection in log rate).

    Returns ``bounds_C_s[1]`` if even that rate exceeds the limit and ``bounds_C_s[0]`` if even that rate stays below.
    """
    def products(rate: float) -> float:
        d = cct_diagram(kin, np.array([rate]), T_start_C, T_end_C)
        return float(sum(d.final_fractions[p][0] for p in kin.reactions))

    lo, hi = np.log(bounds_C_s[0]), np.log(bounds_C_s[1])
    if products(np.exp(hi)) > max_diffusional:
        return bounds_C_s[1]
    if products(np.exp(lo)) <= max_diffusional:
        return bounds_C_s[0]
    while hi - lo > rel_tol:
        mid = 0.5 * (lo + hi)
        if products(np.exp(mid)) > max_diffusional:
            lo = mid
        else:
            hi = mid
    return float(np.exp(hi))
