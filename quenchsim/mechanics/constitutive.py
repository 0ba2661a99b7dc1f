"""Material-point update: isotropic elasticity, von Mises plasticity with linear isotropic hardening
and transformation plasticity, vectorised over any number of points.

Tensors are axisymmetric Mandel 4-vectors (rr, zz, tt, sqrt(2) rz), so double contractions are dot
products and the tangent is a symmetric 4 x 4 matrix.  Stress is secant (total) elastic:

    sigma = C(T, X) : (eps - eps_free I - eps_p - eps_tp),

the form of Furlan et al. 2025 and of most quench codes, so a change of the moduli with the phases
does not create spurious stress increments.

Radial return (Simo & Hughes, Computational Inelasticity, 1998, Box 3.2) extended by an implicit
TRIP term: with d eps_tp = 3/2 dPhi s_{n+1} (dPhi = sum_i K_i [phi(X_i^{n+1}) - phi(X_i^n)], the
Desalos/Leblond form of the reference notes, section 4b) and d eps_p = 3/2 dp s_{n+1}/q, both flows
are parallel to the trial deviator, so with a = 3 mu dPhi

    q (1 + a) + 3 mu dp = q_trial,    q = sigma_y + H dp   (if plastic)
    dp = (q_trial - (1 + a) sigma_y) / (3 mu + (1 + a) H),

and the consistent tangent is

    D = K m (x) m + 2 mu [beta P + (c - beta) n (x) n],  beta = q/q_trial,  c = dq/dq_trial,

with c = beta = 1/(1 + a) in the elastic(-TRIP) range and c = H/(3 mu + (1 + a) H) when yielding.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

SQRT2 = np.sqrt(2.0)
M_VEC = np.array([1.0, 1.0, 1.0, 0.0])
"""Second-order identity in axisymmetric Mandel form."""
P_DEV = np.eye(4) - np.outer(M_VEC, M_VEC) / 3.0
"""Deviatoric projector in Mandel form."""
YIELD_TOLERANCE = 1e-9
"""A trial state counts as plastic only if q exceeds the yield stress by this relative margin, so a
point that sits on the yield surface and is loaded neutrally (e.g. a uniform free-strain change)
is not flagged plastic by round-off (which would give it the plastic tangent for elastic unloading)."""


def lame_bulk_shear(E_Pa: np.ndarray, nu: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Bulk modulus K = E / (3 (1 - 2 nu)) and shear modulus mu = E / (2 (1 + nu))."""
    return E_Pa / (3.0 * (1.0 - 2.0 * nu)), E_Pa / (2.0 * (1.0 + nu))


def von_mises(stress: np.ndarray) -> np.ndarray:
    """q = sqrt(3/2 s:s) of Mandel stresses shaped (..., 4)."""
    s = stress - (stress @ M_VEC / 3.0)[..., None] * M_VEC
    return np.sqrt(1.5 * np.einsum("...i,...i->...", s, s))


@dataclass(frozen=True)
class PointUpdate:
    """Result of :func:`return_map` (arrays over points)."""

    stress: np.ndarray            # (..., 4) Mandel stress at the end of the step
    tangent: np.ndarray           # (..., 4, 4) consistent tangent d sigma / d eps
    d_plastic_strain: np.ndarray  # (..., 4) Mandel plastic strain increment
    d_trip_strain: np.ndarray     # (..., 4) Mandel TRIP strain increment
    d_eq_plastic: np.ndarray      # (...) equivalent plastic strain increment dp >= 0


def return_map(elastic_trial_strain: np.ndarray, bulk_Pa: np.ndarray, shear_Pa: np.ndarray,
               yield_Pa: np.ndarray | None, hardening_Pa: np.ndarray | None,
               d_trip_Phi_1_Pa: np.ndarray | None) -> PointUpdate:
    """Stress update from the elastic trial strain eps - eps_free I - eps_p^n - eps_tp^n.

    ``yield_Pa`` is the current yield stress sigma_y(T, X) + H p_n (None: elastic);
    ``d_trip_Phi_1_Pa`` the TRIP driving increment dPhi >= 0 in 1/Pa (None: no TRIP).
    """
    eps = elastic_trial_strain
    vol = eps @ M_VEC
    e_dev = eps - (vol / 3.0)[..., None] * M_VEC
    s_trial = 2.0 * shear_Pa[..., None] * e_dev
    norm_trial = np.sqrt(np.einsum("...i,...i->...", s_trial, s_trial))
    q_trial = np.sqrt(1.5) * norm_trial
    a = np.zeros_like(q_trial) if d_trip_Phi_1_Pa is None else 3.0 * shear_Pa * d_trip_Phi_1_Pa
    beta = 1.0 / (1.0 + a)
    c = beta.copy()
    dp = np.zeros_like(q_trial)
    if yield_Pa is not None:
        plastic = q_trial * beta > yield_Pa * (1.0 + YIELD_TOLERANCE)
        H = hardening_Pa
        denom = 3.0 * shear_Pa + (1.0 + a) * H
        dp = np.where(plastic, (q_trial - (1.0 + a) * yield_Pa) / denom, 0.0)
        q = yield_Pa + H * dp
        beta = np.where(plastic, q / np.where(plastic, q_trial, 1.0), beta)
        c = np.where(plastic, H / denom, c)
    s = beta[..., None] * s_trial
    stress = (bulk_Pa * vol)[..., None] * M_VEC + s
    n = s_trial / np.where(norm_trial > 0.0, norm_trial, 1.0)[..., None]
    tangent = ((bulk_Pa[..., None, None] * np.outer(M_VEC, M_VEC))
               + 2.0 * shear_Pa[..., None, None] * (beta[..., None, None] * P_DEV
                                                    + (c - beta)[..., None, None] * n[..., :, None] * n[..., None, :]))
    q_new = np.sqrt(1.5) * beta * norm_trial
    flow = 1.5 * s / np.where(q_new > 0.0, q_new, 1.0)[..., None]
    d_plastic = dp[..., None] * flow
    d_trip = (np.zeros_like(s) if d_trip_Phi_1_Pa is None else 1.5 * d_trip_Phi_1_Pa[..., None] * s)
    return PointUpdate(stress=stress, tangent=tangent, d_plastic_strain=d_plastic, d_trip_strain=d_trip,
                       d_eq_plastic=dp)
