"""The progress estimate's forecasts of what the kinetics still have to do (pearlite and bainite still to form, the
stress steps the martensite still needs), from the run's published state through metallurgy's public kinetics API
(:func:`quenchsim.metallurgy.advance`, the Koistinen-Marburger law). Observers: nothing here reaches a result."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from quenchsim.metallurgy import Kinetics, PhaseState, advance
from quenchsim.metallurgy.laws import koistinen_marburger
from quenchsim.thermal.steps import TARGET

FORECAST_CHUNKS_S = tuple(2.0 ** k for k in range(10))
"""The forecast's time chunks (1, 2, 4, ... 512 s: 1023 s in all): short first, where the temperatures move fastest."""
FORECAST_SUBSTEP_K = 20.0
"""The forecast's sub-step (the run's is ``Kinetics.substep_K``, 5 K): on ring A condition 1 its forecasts are
within 5 % of those at 5 K (every 16th point) and cost 6 ms instead of 21 ms (session 11, 39 forecasts)."""


def diffusional_fraction_to_come(state: PhaseState, kin: Kinetics, T_C: np.ndarray, cooling_rate_C_s: np.ndarray,
                                 ambient_C: float, every: int = 32) -> float:
    """The mean fraction of diffusional products (pearlite + bainite) still to form if each point went on cooling
    by Newton's law from ``T_C`` at its own rate now (``cooling_rate_C_s``, > 0 when cooling) towards
    ``ambient_C``: T(t) = T_a + (T - T_a) exp(-k t), k = rate / (T - T_a), integrated by :func:`advance` (the same
    kinetics as the run, sub-steps of :data:`FORECAST_SUBSTEP_K`) over :data:`FORECAST_CHUNKS_S`, on every
    ``every``-th point (a forecast for the progress estimate, not a result). A point that is not cooling
    is held at its temperature; that and the slower-than-linear Newton decay make the forecast err high where
    latent heat slows a point for now.

    >>> from quenchsim.materials import load_material
    >>> from quenchsim.metallurgy import initial_state, load_kinetics
    >>> kin = load_kinetics(load_material("SUJ2"), 850.0)
    >>> hot = initial_state((2,), kin)
    >>> round(diffusional_fraction_to_come(hot, kin, np.array([650.0, 650.0]), np.zeros(2), 25.0, every=1), 3)
    1.0
    >>> round(diffusional_fraction_to_come(hot, kin, np.array([650.0, 650.0]), np.full(2, 500.0), 25.0), 3)
    0.0
    """
    kin = replace(kin, substep_K=max(kin.substep_K, FORECAST_SUBSTEP_K))
    shape = state.T_min_C.shape

    def sample(a: np.ndarray | float) -> np.ndarray:
        return np.broadcast_to(np.asarray(a, dtype=float), shape).reshape(-1)[::every].copy()

    point = PhaseState(fractions={p: sample(v) for p, v in state.fractions.items()},
                       additivity={r: sample(v) for r, v in state.additivity.items()},
                       T_min_C=sample(state.T_min_C), cooling_rate_700_C_s=sample(state.cooling_rate_700_C_s))
    T = sample(T_C)
    k_per_s = np.maximum(sample(cooling_rate_C_s), 0.0) / np.maximum(T - ambient_C, 1.0)
    before = sum(point.fractions[r] for r in kin.reactions)
    for chunk_s in FORECAST_CHUNKS_S:
        T_next = ambient_C + (T - ambient_C) * np.exp(-k_per_s * chunk_s)
        point = advance(point, kin, T, T_next, chunk_s)
        T = T_next
    return float(np.mean(sum(point.fractions[r] for r in kin.reactions) - before))


MARTENSITE_FORECAST_GRID_K = 3.0
"""The martensite forecast's resolution: no point cools by more than this between two instants of its grid (a fall of
3 K turns at most 3 alpha ~ 0.03-0.05 of a point's austenite; at 2 K and on 4x the points the forecasts of the peer
race and ring A condition 2 differ by 1-5 %)."""
MARTENSITE_FORECAST_OWN_RATE_WEIGHT = 0.25
"""How far each point's own cooling rate, rather than the section's, sets its pace in the martensite forecast
(:func:`martensite_limit_steps_to_come`; 0: the section's profile keeps its shape, 1: each point keeps its own Newton
rate). Fitted, by eye, to the stress steps of two runs at the BDF2 limits (code of 2a14316): the water-quenched peer
race, ~500 left before its martensite starts, where 0 counts ~230 and 0.5 ~570; and ring A condition 2 in oil,
150-340, where 0 counts 100-150 and 0.5 220-340 (0.25: ~400 and 175-230)."""


def martensite_limit_steps_to_come(state: PhaseState, kin: Kinetics, T_C: np.ndarray, cooling_rate_C_s: np.ndarray,
                                   bath_C: float, end_C: float, max_dX: float, every: int = 32) -> float:
    """How many steps a limit of ``max_dX`` on the martensite any point forms per step still needs (steps at 90 % of
    it), for the progress estimate: the sum over the rest of the cooling of the largest martensite increment of any
    point, over 0.9 ``max_dX``.

    A point's martensite is a function of its lowest temperature (Koistinen-Marburger on the austenite it has now),
    so the count depends on the order and overlap in which the points cool through Ms, not on the clock. Each point
    is taken to cool on by Newton's law towards ``bath_C``, at a rate between the section's (the sum of
    ``cooling_rate_C_s`` over the sum of the excesses; the profile keeps its shape) and its own, their geometric
    mean weighted by :data:`MARTENSITE_FORECAST_OWN_RATE_WEIGHT` (the own rate clipped to 0.1-10x the section's);
    then, where ``end_C`` is colder, all together from the bath to ``end_C`` (the part equalised in the bath). Where
    a martensite front crosses the section, the points one after the other, this is many times the mean martensite
    still to form over the limit: ~8x on the water-quenched peer race. Pearlite and bainite still to form are not
    taken from the austenite (the caller scales by them); the forecast is on every ``every``-th point. NaN where the
    section is not cooling (its rate is not positive).

    >>> from quenchsim.materials import load_material
    >>> from quenchsim.metallurgy import initial_state, load_kinetics
    >>> kin = load_kinetics(load_material("SUJ2"), 850.0)
    >>> hot = initial_state((2,), kin)
    >>> together = martensite_limit_steps_to_come(hot, kin, np.array([300.0, 300.0]), np.full(2, 10.0), 20.0, 20.0,
    ...                                           0.02, every=1)
    >>> final = 1.0 - np.exp(-kin.alpha_per_K * (kin.Ms_C - 20.0))  # K-M from Ms to the bath
    >>> round(float(together / (final / (0.9 * 0.02))), 3)          # points alike: the martensite one forms
    1.0
    >>> in_turn = martensite_limit_steps_to_come(hot, kin, np.array([300.0, 600.0]), np.full(2, 10.0), 20.0, 20.0,
    ...                                          0.02, every=1)
    >>> bool(1.2 * together < in_turn < 2.0 * together)              # the hotter point later: partly in turn
    True
    """
    shape = state.T_min_C.shape

    def sample(a: np.ndarray | float) -> np.ndarray:
        return np.broadcast_to(np.asarray(a, dtype=float), shape).reshape(-1)[::every]

    T, austenite = sample(T_C), sample(state.fractions["austenite"])
    excess = np.maximum(T - bath_C, 1.0)
    rate = np.maximum(sample(cooling_rate_C_s), 0.0)
    section_per_s = float(np.sum(rate)) / float(np.sum(excess))
    if not section_per_s > 0.0:
        return math.nan
    pace = np.clip(rate / excess / section_per_s, 0.1, 10.0) ** MARTENSITE_FORECAST_OWN_RATE_WEIGHT
    reference_C = np.minimum(sample(state.T_min_C), kin.Ms_C)
    # time in units of the section's decay time, tau: the excess of point i is excess_i exp(-pace_i tau); from the
    # first point reaching its martensite start to the last within a grid interval of the bath
    below_C = np.maximum(reference_C - bath_C, MARTENSITE_FORECAST_GRID_K)
    start = float(np.min(np.log(np.maximum(excess / below_C, 1.0)) / pace))
    end = float(np.max(np.log(np.maximum(excess / MARTENSITE_FORECAST_GRID_K, 1.0)) / pace))
    dtau = MARTENSITE_FORECAST_GRID_K / float(np.max(np.minimum(excess, below_C) * pace))
    tau = np.append(np.arange(start, end, dtau), end)

    def martensite(T_path_C: np.ndarray) -> np.ndarray:
        return austenite * koistinen_marburger(T_path_C, reference_C, kin.alpha_per_K)

    increments, last = 0.0, martensite(bath_C + excess * np.exp(-pace * tau[0]))
    for block in np.array_split(tau[1:], max(len(tau) // 256, 1)) if len(tau) > 1 else ():
        path = martensite(bath_C + excess * np.exp(-np.outer(block, pace)))
        increments += float(np.sum(np.max(np.diff(np.vstack([last, path]), axis=0), axis=1)))
        last = path[-1]
    at_bath = martensite(np.full_like(excess, bath_C))      # the last grid interval to the bath itself
    increments, last = increments + float(np.max(at_bath - last)), at_bath
    if end_C < bath_C:        # then all together, from the bath on
        austenite, reference_C = austenite - last, np.minimum(reference_C, bath_C)
        together = np.linspace(bath_C, end_C, max(int(math.ceil((bath_C - end_C) / MARTENSITE_FORECAST_GRID_K)), 1) + 1)
        increments += float(np.sum(np.max(np.diff(martensite(together[:, None]), axis=0), axis=1)))
    return increments / (TARGET * max_dX)
