"""Solid-contact laws of the big-end bearing (pure functions, numba-compiled; float64 scalars or arrays).

Line contact (roller-race, roller-pocket bar, cage land-outer ring): Palmgren's elastic approach
    delta [mm] = 1.36 eta^0.9 Q^0.9 / l^0.8,   eta = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 = 2/E' [mm^2/N]
(Palmgren, Ball and Roller Bearing Engineering, 1959; Harris & Kotzalas, Rolling Bearing Analysis,
5th ed. 2007, vol. 1 ch. 6: delta = 3.84e-5 Q^0.9 / l^0.8 for steel), inverted for the force.
Damping: linear viscous term with the tangent stiffness, c = 2 zeta sqrt(m_eff dQ/ddelta)
(critical-damping fraction zeta given in the case file), so the force stays continuous at delta = 0.
Friction: Coulomb law regularised with tanh(v / v_reg).
"""

from __future__ import annotations

from typing import Any, TypeAlias

import numpy as np
from numba import njit

FloatOrArray: TypeAlias = Any
"""A float64 scalar or array: the laws (here and in :mod:`.ehl`) are numba kernels, called with scalars by the
dynamics' per-roller loop and with arrays by the tests, and return the arguments' kind. That is a
TypeVar(float, ndarray), but numba's ``Dispatcher`` stub cannot carry a TypeVar through (calls then expect
``Never``), so it is spelt Any."""

PALMGREN_COEFFICIENT = 1.36  # Palmgren 1959 / Harris & Kotzalas 2007, mm, N units
PALMGREN_FORCE_EXPONENT = 0.9
PALMGREN_LENGTH_EXPONENT = 0.8


@njit(cache=True)
def palmgren_compliance(length_m: FloatOrArray, e_star_pa: float) -> FloatOrArray:
    """C [m/N^0.9] in delta = C Q^0.9 (Palmgren line contact; l in m, E' in Pa)."""
    eta_mm2_n = 2.0 / e_star_pa * 1e6
    return 1e-3 * PALMGREN_COEFFICIENT * eta_mm2_n**PALMGREN_FORCE_EXPONENT / (
        (length_m * 1e3) ** PALMGREN_LENGTH_EXPONENT)


@njit(cache=True)
def line_contact_force(approach_m: FloatOrArray, length_m: FloatOrArray, e_star_pa: float) -> FloatOrArray:
    """Normal force Q [N] of a line contact with elastic approach delta [m] (0 where delta <= 0).

    Q = (delta / C)^(1/0.9), C from :func:`palmgren_compliance`.
    """
    c = palmgren_compliance(length_m, e_star_pa)
    d = np.maximum(approach_m, 0.0)
    return (d / c) ** (1.0 / PALMGREN_FORCE_EXPONENT)


@njit(cache=True)
def damped_contact_force(approach_m: FloatOrArray, approach_rate_m_s: FloatOrArray, length_m: FloatOrArray,
                         e_star_pa: float, mass_kg: FloatOrArray, damping_ratio: float) -> FloatOrArray:
    """Q = Q_el(delta) + c delta_dot, c = 2 zeta sqrt(m dQ/ddelta), dQ/ddelta = Q_el / (0.9 delta);
    clipped at 0 (a contact only pushes)."""
    q = line_contact_force(approach_m, length_m, e_star_pa)
    d = np.maximum(approach_m, 1e-15)
    stiffness = q / (PALMGREN_FORCE_EXPONENT * d)
    c = 2.0 * damping_ratio * np.sqrt(mass_kg * stiffness)
    return np.maximum(q + c * approach_rate_m_s, 0.0) * (approach_m > 0.0)


@njit(cache=True)
def coulomb_friction(normal_force_n: FloatOrArray, sliding_velocity_m_s: FloatOrArray, mu: float,
                     regularisation_m_s: float) -> FloatOrArray:
    """Friction force magnitude with sign of the sliding velocity: mu Q tanh(v / v_reg)."""
    return mu * normal_force_n * np.tanh(sliding_velocity_m_s / regularisation_m_s)
