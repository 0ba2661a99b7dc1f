"""Phase state of material points and its update over one time step (JMAK + additivity, Koistinen-Marburger).

Per time step the temperature of each point is taken linear in time between T_old and T_new; the
step is split into m equal sub-steps with |dT| <= ``Kinetics.substep_K`` (m is common to all points,
so everything stays vectorised over the points).

Diffusional reactions (Scheil additivity): the normalised JMAK progress xi_i of reaction i obeys,
along any T(t), q_i = -ln(1 - xi_i) = I_i^{n}, I_i = int dt / tau_i(T(t)) (the additivity integral);
exact for the isothermal law and for constant n (isokinetic reaction). With n(T) varying, each
sub-step converts q_i to the fictitious time I_i = q_i^{1/n} at the sub-step's n (Scheil-Hougardy).
The integral of 1/tau over a sub-step uses 2-point Gauss-Legendre quadrature.

Competition: during a sub-step reaction i alone would turn a share 1 - exp(-dq_i) of the austenite
left; together they turn f_A (1 - exp(-sum dq_i)), split in proportion to dq_i (exact when the rate
ratio is constant over the sub-step). Carbon enrichment of the austenite by bainite is not modelled:
Ms stays at its value for the dissolved composition.

Martensite (Koistinen-Marburger, incremental): below T_ref = min(Ms, lowest T reached so far), a fall
from T_ref to T turns the austenite left by 1 - exp(-alpha (T_ref - T)); this reproduces
f_M = f_A(Ms) (1 - exp(-alpha (Ms - T))) on cooling, never removes martensite on re-heating and forms
new martensite only below the previous lowest temperature.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from quenchsim.materials.properties import PHASES
from quenchsim.metallurgy.kinetics import Kinetics

MAYNIER_RATE_T_C = 700.0
"""Temperature at which Maynier et al. (1978) take the cooling rate V_r of their hardness equations."""

Q_MAX = 50.0
"""Cap on q_i = -ln(1 - xi_i): beyond it (xi_i > 1 - 2e-22) the reaction is complete; keeps q^n finite."""

_GAUSS = (0.5 - 0.5 / np.sqrt(3.0), 0.5 + 0.5 / np.sqrt(3.0))
"""2-point Gauss-Legendre abscissae on [0, 1] (equal weights 1/2)."""


@dataclass(frozen=True)
class PhaseState:
    """Metallurgical state of an array of material points (all arrays share one shape).

    fractions              the four PHASES (sum to one)
    additivity             q_i = -ln(1 - xi_i) per diffusional reaction (xi_i: normalised JMAK progress)
    T_min_C                lowest temperature reached (Koistinen-Marburger reference on re-cooling)
    cooling_rate_700_C_s   cooling rate when the point crossed 700 C (NaN before), for Maynier hardness
    """

    fractions: dict[str, np.ndarray]
    additivity: dict[str, np.ndarray]
    T_min_C: np.ndarray
    cooling_rate_700_C_s: np.ndarray


def initial_state(shape: tuple[int, ...], kin: Kinetics) -> PhaseState:
    """Fully austenitic points at the austenitising temperature."""
    zeros = np.zeros(shape)
    fractions = {p: zeros.copy() for p in PHASES}
    fractions["austenite"] = np.ones(shape)
    return PhaseState(fractions=fractions, additivity={r: zeros.copy() for r in kin.reactions},
                      T_min_C=np.full(shape, kin.T_aust_C), cooling_rate_700_C_s=np.full(shape, np.nan))


def advance(state: PhaseState, kin: Kinetics, T_old_C: np.ndarray, T_new_C: np.ndarray, dt_s: float) -> PhaseState:
    """The state after a step of dt_s during which T goes linearly from T_old_C to T_new_C (pure function)."""
    shape = state.T_min_C.shape
    T0 = np.broadcast_to(np.asarray(T_old_C, dtype=float), shape)
    T1 = np.broadcast_to(np.asarray(T_new_C, dtype=float), shape)
    if not (np.all(np.isfinite(T0)) and np.all(np.isfinite(T1))):
        raise ValueError("advance: temperatures must be finite")
    if not dt_s >= 0.0:
        raise ValueError(f"advance: dt_s = {dt_s} must be >= 0")
    dT = T1 - T0
    m = max(1, int(np.ceil(np.max(np.abs(dT), initial=0.0) / kin.substep_K)))
    h = dt_s / m

    fA = state.fractions["austenite"].copy()
    products = {p: state.fractions[p].copy() for p in PHASES[1:]}
    q = {r: state.additivity[r].copy() for r in kin.reactions}
    T_min = state.T_min_C.copy()
    for k in range(m):
        Ta = T0 + dT * (k / m)
        Tb = T0 + dT * ((k + 1) / m)
        if h > 0.0 and kin.reactions:
            dq = {}
            for r, reaction in kin.reactions.items():
                dI = 0.5 * h * sum(reaction.inverse_tau(Ta + (Tb - Ta) * g) for g in _GAUSS)
                n = reaction.exponent(0.5 * (Ta + Tb))
                q_new = np.minimum((q[r] ** (1.0 / n) + dI) ** n, Q_MAX)
                dq[r] = q_new - q[r]
                q[r] = q_new
            total = sum(dq.values())
            active = total > 0.0
            consumed = fA * -np.expm1(-total)
            for r, d in dq.items():
                products[r] += np.where(active, consumed * d / np.where(active, total, 1.0), 0.0)
            fA = fA - consumed
        T_ref = np.minimum(T_min, kin.Ms_C)
        below = Tb < T_ref
        converted = np.where(below, fA * -np.expm1(-kin.alpha_per_K * (T_ref - Tb)), 0.0)
        products["martensite"] += converted
        fA = fA - converted
        T_min = np.minimum(T_min, Tb)

    rate = state.cooling_rate_700_C_s.copy()
    if dt_s > 0.0:
        crossing = np.isnan(rate) & (T0 > MAYNIER_RATE_T_C) & (T1 <= MAYNIER_RATE_T_C)
        rate[crossing] = dT[crossing] / -dt_s
    fractions = {"austenite": np.maximum(fA, 0.0), **products}
    return PhaseState(fractions=fractions, additivity=q, T_min_C=T_min, cooling_rate_700_C_s=rate)
