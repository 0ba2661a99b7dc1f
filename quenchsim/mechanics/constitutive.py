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
from typing import cast

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
    """Result of :func:`return_map` (arrays over points).  The consistent tangent is
    D = K m (x) m + 2 mu [beta P + (c - beta) n (x) n]; it is kept in this factored form so that the
    assembly never forms 4 x 4 matrices (:attr:`tangent` builds them, for checks)."""

    stress: np.ndarray            # (..., 4) Mandel stress at the end of the step
    bulk: np.ndarray              # (...) K
    shear: np.ndarray             # (...) mu
    beta: np.ndarray              # (...) q / q_trial
    c: np.ndarray                 # (...) dq / dq_trial
    normal: np.ndarray            # (..., 4) unit trial deviator n
    d_plastic_strain: np.ndarray  # (..., 4) Mandel plastic strain increment
    d_trip_strain: np.ndarray     # (..., 4) Mandel TRIP strain increment
    d_eq_plastic: np.ndarray      # (...) equivalent plastic strain increment dp >= 0

    @property
    def tangent(self) -> np.ndarray:
        """(..., 4, 4) consistent tangent d sigma / d eps."""
        n = self.normal
        return (self.bulk[..., None, None] * np.outer(M_VEC, M_VEC)
                + 2.0 * self.shear[..., None, None] * (self.beta[..., None, None] * P_DEV
                                                       + (self.c - self.beta)[..., None, None] * n[..., :, None] * n[..., None, :]))


def return_map(elastic_trial_strain: np.ndarray, bulk_Pa: np.ndarray, shear_Pa: np.ndarray,
               yield_Pa: np.ndarray | None, hardening_Pa: np.ndarray | None,
               d_trip_Phi_1_Pa: np.ndarray | None) -> PointUpdate:
    """Stress update from the elastic trial strain eps - eps_free I - eps_p^n - eps_tp^n.

    ``yield_Pa`` is the current yield stress sigma_y(T, X) + H p_n (None: elastic);
    ``d_trip_Phi_1_Pa`` the TRIP driving increment dPhi >= 0 in 1/Pa (None: no TRIP).
    """
    eps = elastic_trial_strain
    vol = eps[..., 0] + eps[..., 1] + eps[..., 2]
    e_dev = eps - (vol / 3.0)[..., None] * M_VEC
    norm_dev = np.sqrt(np.einsum("...i,...i->...", e_dev, e_dev))
    norm_trial = 2.0 * shear_Pa * norm_dev
    q_trial = np.sqrt(1.5) * norm_trial
    n = e_dev / np.where(norm_dev > 0.0, norm_dev, 1.0)[..., None]
    a = 0.0 if d_trip_Phi_1_Pa is None else 3.0 * shear_Pa * d_trip_Phi_1_Pa
    beta = np.broadcast_to(1.0 / (1.0 + a), q_trial.shape)
    c = beta
    dp = np.zeros_like(q_trial)
    if yield_Pa is not None:
        plastic = q_trial * beta > yield_Pa * (1.0 + YIELD_TOLERANCE)
        if plastic.any():
            H = cast(np.ndarray, hardening_Pa)   # a plastic model gives yield_Pa and hardening_Pa together
            denom = 3.0 * shear_Pa + (1.0 + a) * H
            dp = np.where(plastic, (q_trial - (1.0 + a) * yield_Pa) / denom, 0.0)
            q = yield_Pa + H * dp
            beta = np.where(plastic, q / np.where(plastic, q_trial, 1.0), beta)
            c = np.where(plastic, H / denom, c)
    s_norm = beta * norm_trial  # |s| at the end of the step
    stress = (bulk_Pa * vol)[..., None] * M_VEC + s_norm[..., None] * n
    d_plastic = (np.sqrt(1.5) * dp)[..., None] * n  # 3/2 dp s/q, |s|/q = sqrt(2/3)
    d_trip = (np.zeros_like(n) if d_trip_Phi_1_Pa is None else (1.5 * d_trip_Phi_1_Pa * s_norm)[..., None] * n)
    return PointUpdate(stress=stress, bulk=np.broadcast_to(bulk_Pa, q_trial.shape),
                       shear=np.broadcast_to(shear_Pa, q_trial.shape), beta=np.asarray(beta), c=np.asarray(c),
                       normal=n, d_plastic_strain=d_plastic, d_trip_strain=d_trip, d_eq_plastic=dp)
