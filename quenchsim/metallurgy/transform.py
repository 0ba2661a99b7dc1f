"""Phase state of material points and its update over one time step (JMAK + additivity, Koistinen-Marburger).

Per time step the temperature of each point is taken linear in time between T_old and T_new; the
step of each point is split into m_i equal sub-steps with |dT| <= ``Kinetics.substep_K`` (the loop runs
over sub-step indices, each vectorised over the points that still need it).

Diffusional reactions (Scheil additivity): the normalised JMAK progress xi_i of reaction i obeys,
along any T(t), q_i = -ln(1 - xi_i) = I_i^{n}, I_i = int dt / tau_i(T(t)) (the additivity integral);
exact for the isothermal law and for constant n (isokinetic reaction). With n(T) varying, each
sub-step converts q_i to the fictitious time I_i = q_i^{1/n} at the sub-step's n (Scheil-Hougardy).
The integral of 1/tau over a sub-step uses 2-point Gauss-Legendre quadrature on the part of the
sub-step below the reaction's upper temperature (Ae1, Bs), where 1/tau may jump.

Competition: during a sub-step reaction i alone would turn a share 1 - exp(-dq_i) of the austenite
left; together they turn f_A (1 - exp(-sum dq_i)), split in proportion to dq_i (exact when the rate
ratio is constant over the sub-step). Carbon enrichment of the austenite by bainite is not modelled:
Ms stays at its value for the dissolved composition.

Martensite (Koistinen-Marburger, incremental): below T_ref = min(Ms, lowest T reached so far), a fall
from T_ref to T turns the austenite left by 1 - exp(-alpha (T_ref - T)); this reproduces
f_M = f_A(Ms) (1 - exp(-alpha (Ms - T))) on cooling, never removes martensite on re-heating and forms
new martensite only below the previous lowest temperature.

:func:`advance` runs this per point in a compiled kernel (:mod:`quenchsim.metallurgy.kernels`);
:func:`advance_reference` is the same algorithm in NumPy, vectorised over the points per sub-step, the reference
the kernel is tested against.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from quenchsim.materials.properties import PHASES
from quenchsim.metallurgy import kernels
from quenchsim.metallurgy.kinetics import Kinetics
from quenchsim.metallurgy.laws import koistinen_marburger

MAYNIER_RATE_T_C = 700.0
"""Temperature at which Maynier et al. (1978) take the cooling rate V_r of their hardness equations."""

Q_MAX = 50.0
"""Cap on q_i = -ln(1 - xi_i): beyond it (xi_i > 1 - 2e-22) the reaction is complete; keeps q^n finite."""

Q_START = -np.log(0.99)
"""q_i = -ln(1 - xi_i) at the 1 % start of a reaction (xi_i = 0.01)."""

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


def incubation_share(state: PhaseState, kin: Kinetics, T_C: np.ndarray) -> float:
    """How far the diffusional reactions are from starting: the largest share of its incubation that any point has
    run for any reaction, the additivity integral I_i = q_i^(1/n_i) (at the point's exponent at ``T_C``) over its
    value at the 1 % start, q = -ln(0.99); capped at 1 (a point that has started), 0 for a steel without diffusional
    reactions.

    >>> from quenchsim.materials import load_material
    >>> from quenchsim.metallurgy.kinetics import load_kinetics
    >>> kin = load_kinetics(load_material("SUJ2"), 850.0)
    >>> incubation_share(initial_state((3,), kin), kin, np.full(3, 850.0))
    0.0
    """
    share = 0.0
    for r, reaction in kin.reactions.items():
        q = state.additivity[r]
        if np.max(q, initial=0.0) >= Q_START:
            return 1.0
        running = q > 0.0
        if running.any():
            n = reaction.exponent(np.asarray(T_C)[running])
            share = max(share, float(np.max((q[running] / Q_START) ** (1.0 / n))))
    return share


def initial_state(shape: tuple[int, ...], kin: Kinetics) -> PhaseState:
    """Fully austenitic points at the austenitising temperature."""
    zeros = np.zeros(shape)
    fractions = {p: zeros.copy() for p in PHASES}
    fractions["austenite"] = np.ones(shape)
    return PhaseState(fractions=fractions, additivity={r: zeros.copy() for r in kin.reactions},
                      T_min_C=np.full(shape, kin.T_aust_C), cooling_rate_700_C_s=np.full(shape, np.nan))


def _diffusional_increments(kin: Kinetics, q: dict[str, np.ndarray], Ta: np.ndarray, Tb: np.ndarray,
                            h: np.ndarray) -> dict[str, np.ndarray]:
    """Increments dq_i of q_i = -ln(1 - xi_i) of each reaction over sub-steps [Ta, Tb] of length h (updates q in place).

    Only points whose sub-step reaches below the reaction's upper temperature are evaluated.
    """
    dq = {}
    for r, reaction in kin.reactions.items():
        cold = np.minimum(Ta, Tb) < reaction.T_upper_C
        d = np.zeros_like(Ta)
        if cold.any():
            sel = slice(None) if cold.all() else np.flatnonzero(cold)
            ta, tb, hs, qs = Ta[sel], Tb[sel], h[sel], q[r][sel]
            # integrate only over the part of the sub-step below T_upper (1/tau may jump there, e.g. at Bs)
            T_up = reaction.T_upper_C
            hot_end = np.maximum(ta, tb) > T_up
            if hot_end.any():
                share = np.where(hot_end, (T_up - np.minimum(ta, tb)) / np.where(hot_end, np.abs(tb - ta), 1.0), 1.0)
                ta, tb = np.where(hot_end & (ta > tb), T_up, ta), np.where(hot_end & (tb > ta), T_up, tb)
                hs = hs * share
            dI = 0.5 * hs * (reaction.inverse_tau(ta + (tb - ta) * _GAUSS[0])
                             + reaction.inverse_tau(ta + (tb - ta) * _GAUSS[1]))
            n = reaction.exponent(0.5 * (ta + tb))
            q_new = np.minimum((qs ** (1.0 / n) + dI) ** n, Q_MAX)
            d[sel] = q_new - qs
            q[r][sel] = q_new
        dq[r] = d
    return dq


def _step_temperatures(state: PhaseState, T_old_C: np.ndarray, T_new_C: np.ndarray, dt_s: float
                       ) -> tuple[np.ndarray, np.ndarray]:
    """The step's start and end temperatures as flat arrays of the state's points (checked finite, dt_s >= 0)."""
    shape = state.T_min_C.shape
    T0 = np.broadcast_to(np.asarray(T_old_C, dtype=float), shape).reshape(-1)
    T1 = np.broadcast_to(np.asarray(T_new_C, dtype=float), shape).reshape(-1)
    if not (np.all(np.isfinite(T0)) and np.all(np.isfinite(T1))):
        raise ValueError("advance: temperatures must be finite")
    if not dt_s >= 0.0:
        raise ValueError(f"advance: dt_s = {dt_s} must be >= 0")
    return T0, T1


def advance(state: PhaseState, kin: Kinetics, T_old_C: np.ndarray, T_new_C: np.ndarray, dt_s: float) -> PhaseState:
    """The state after a step of dt_s during which T goes linearly from T_old_C to T_new_C (pure function).

    Each point takes m_i = ceil(|T_new - T_old| / substep_K) equal sub-steps (at least one); a sub-step level (the
    k-th sub-step of every point that has one) is a few compiled passes (:mod:`quenchsim.metallurgy.kernels`) and the
    laws on compact arrays of the sub-steps that need them. The same numbers as :func:`advance_reference`.
    """
    shape = state.T_min_C.shape
    T0, T1 = _step_temperatures(state, T_old_C, T_new_C, dt_s)
    T0, T1 = np.ascontiguousarray(T0), np.ascontiguousarray(T1)
    dT = T1 - T0
    m = np.maximum(np.ceil(np.abs(dT) / kin.substep_K), 1.0)
    n = T0.size
    fA = np.array(state.fractions["austenite"], dtype=float).reshape(-1)
    X = np.stack([np.asarray(state.fractions[p], dtype=float).reshape(-1) for p in PHASES])   # products in rows 1..
    q = {r: np.array(state.additivity[r], dtype=float).reshape(-1) for r in kin.reactions}
    T_min = np.array(state.T_min_C, dtype=float).reshape(-1)
    reactions = list(kin.reactions.items()) if dt_s > 0.0 else []
    rows = np.array([PHASES.index(r) for r, _ in reactions], dtype=np.int64)
    Ta, Tb, h, f, T_mid, hs, total, x = (np.empty(n) for _ in range(8))
    T_gauss, tasks, d = np.empty(2 * n), np.empty(n, dtype=np.int64), np.zeros((len(reactions), n))
    everyone = np.arange(n)
    for k in range(int(m.max(initial=1.0))):
        points = everyone if k == 0 else np.flatnonzero(m > k)   # points still sub-stepping
        count = points.size
        kernels.substep_temperatures(T0, dT, m, k, points, float(dt_s), fA, Ta, Tb, h, f)
        if reactions:
            for r, (name, reaction) in enumerate(reactions):
                d[r, :count] = 0.0
                c = kernels.cold_substeps(Ta, Tb, h, count, reaction.T_upper_C, _GAUSS[0], _GAUSS[1], tasks, T_gauss,
                                          T_mid, hs)
                if c:
                    rate = reaction.inverse_tau(T_gauss[:2 * c])
                    dI = 0.5 * hs[:c] * (rate[:c] + rate[c:])
                    exponent = reaction.exponent(T_mid[:c])
                    qs = q[name][points[tasks[:c]]]
                    q_new = np.minimum((qs ** (1.0 / exponent) + dI) ** exponent, Q_MAX)
                    kernels.scatter_increments(q[name], points, tasks, c, q_new, d[r])
            kernels.total_increments(d, count, total)
            kernels.share_out(X, rows, points, d, total, np.expm1(-total[:count]), f, count)
        kernels.martensite_exponent(points, T_min, kin.Ms_C, kin.alpha_per_K, Tb, count, x)
        kernels.form_martensite(points, f, np.expm1(x[:count]), Tb, count, X[PHASES.index("martensite")], fA, T_min)

    rate_700 = np.array(state.cooling_rate_700_C_s, dtype=float).reshape(-1)
    if dt_s > 0.0:
        crossing = np.isnan(rate_700) & (T0 > MAYNIER_RATE_T_C) & (T1 <= MAYNIER_RATE_T_C)
        rate_700[crossing] = dT[crossing] / -dt_s
    fractions = {"austenite": np.maximum(fA, 0.0).reshape(shape), **{p: X[i].reshape(shape)
                                                                    for i, p in enumerate(PHASES) if i > 0}}
    return PhaseState(fractions=fractions, additivity={r: v.reshape(shape) for r, v in q.items()},
                      T_min_C=T_min.reshape(shape), cooling_rate_700_C_s=rate_700.reshape(shape))


def advance_reference(state: PhaseState, kin: Kinetics, T_old_C: np.ndarray, T_new_C: np.ndarray, dt_s: float
                      ) -> PhaseState:
    """:func:`advance` in NumPy, each sub-step vectorised over the points that still need it (the reference of the
    compiled kernel; the same arithmetic per point, tests/test_metallurgy_kernels.py)."""
    shape = state.T_min_C.shape
    T0, T1 = _step_temperatures(state, T_old_C, T_new_C, dt_s)
    dT = T1 - T0
    m = np.maximum(np.ceil(np.abs(dT) / kin.substep_K), 1.0)

    fA = state.fractions["austenite"].reshape(-1).copy()
    products = {p: state.fractions[p].reshape(-1).copy() for p in PHASES[1:]}
    q = {r: state.additivity[r].reshape(-1).copy() for r in kin.reactions}
    T_min = state.T_min_C.reshape(-1).copy()
    for k in range(int(m.max(initial=1.0))):
        # points still sub-stepping (all of them in the first sub-step)
        sel = slice(None) if k == 0 else np.flatnonzero(m > k)
        ms, t0, dts = m[sel], T0[sel], dT[sel]
        Ta = t0 + dts * (k / ms)
        Tb = t0 + dts * ((k + 1) / ms)
        f = fA[sel]
        if dt_s > 0.0 and kin.reactions:
            qs = {r: q[r][sel] for r in q}
            dq = _diffusional_increments(kin, qs, Ta, Tb, dt_s / ms)
            total = sum(dq.values())
            active = total > 0.0
            consumed = f * -np.expm1(-total)
            for r, d in dq.items():
                products[r][sel] += np.where(active, consumed * d / np.where(active, total, 1.0), 0.0)
                q[r][sel] = qs[r]
            f = f - consumed
        T_ref = np.minimum(T_min[sel], kin.Ms_C)
        converted = f * koistinen_marburger(Tb, T_ref, kin.alpha_per_K)
        products["martensite"][sel] += converted
        fA[sel] = f - converted
        T_min[sel] = np.minimum(T_min[sel], Tb)

    rate = state.cooling_rate_700_C_s.reshape(-1).copy()
    if dt_s > 0.0:
        crossing = np.isnan(rate) & (T0 > MAYNIER_RATE_T_C) & (T1 <= MAYNIER_RATE_T_C)
        rate[crossing] = dT[crossing] / -dt_s
    fractions = {"austenite": np.maximum(fA, 0.0).reshape(shape), **{p: v.reshape(shape) for p, v in products.items()}}
    return PhaseState(fractions=fractions, additivity={r: v.reshape(shape) for r, v in q.items()},
                      T_min_C=T_min.reshape(shape), cooling_rate_700_C_s=rate.reshape(shape))
