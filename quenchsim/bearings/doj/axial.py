"""Axial force a DOJ induces on its outer race over a revolution (the generated axial force, GAF, of a plunging joint).

The outer race's tracks and bore are parallel to its axis, so frictionless contacts push it only radially and
circumferentially: the quasi-static model's axial force on the outer race is zero at every phase
(PhaseResult.outer_race_axial_N, to rounding). A plunging joint's axial force comes from friction (the generated
axial force of plunging constant-velocity joints is induced by the internal friction at the contacts: e.g.
J. Lee et al., "An experimental and numerical study on reduction of generated axial force", Appl. Sci. 11 (2021)
8836, for the tripod joint; Hayama 2001 sec. 4 names friction as what the DOJ model still lacks).

Here friction enters to first order, as an option: Coulomb friction ``mu`` at the ball - outer-track contacts on the
normal forces of the frictionless equilibrium. At operating angle theta ball i (track psi_i = phase + 60 i deg)
moves along its outer track as z_i = PCR sin(psi_i) tan(theta / 2) (model.py), i.e. with axial velocity of the sign
of cos(psi_i) (phase increasing); assumed to slide there (no rolling along the track), it drags the outer race
along with friction mu P_o,i:

    F_axial(phase) = mu sum_i P_o,i(phase) sign(cos psi_i)

With six equally loaded balls the signs cancel three against three; what remains follows the balls' load
variation over the revolution, so it repeats every 60 deg of phase (orders 0, 6, 12, ...: the paper's "6th-order
generated axial force", sec. 3.2), and it is linear in mu and, through P_o, in the torque. Ball - window, cage -
sphere friction and the balls' rolling resistance are not included (no published friction data for them).
"""

from __future__ import annotations

import math

import numpy as np

from quenchsim.bearings.doj.output import Revolution, harmonic_amplitude
from quenchsim.errors import require


def friction_axial_force_N(rev: Revolution, friction: float) -> np.ndarray:
    """F_axial(phase) on the outer race (N, shape of ``rev.phase_deg``) from ball - outer-track sliding friction
    ``friction`` to first order (module docstring); positive along +z.

    >>> import numpy as np
    >>> phase = np.array([10.0])
    >>> rev = Revolution(phase, np.ones((1, 6)), np.array([[2.0, 1, 1, 1, 1, 1]]), np.zeros((1, 6)),
    ...                  np.zeros((1, 6)), np.zeros(1), np.zeros(1), np.zeros(1), np.zeros((1, 3)), 1.0)
    >>> float(friction_axial_force_N(rev, 0.1)[0])   # ball 0 (cos > 0) carries one extra newton
    0.1
    """
    require(math.isfinite(friction) and friction >= 0.0, "friction", friction, "must be a friction coefficient >= 0")
    psi = np.radians(rev.phase_deg[:, None] + 60.0 * np.arange(rev.p_outer_N.shape[1])[None, :])
    return friction * np.sum(rev.p_outer_N * np.sign(np.cos(psi)), axis=1)


def axial_force_summary(rev: Revolution, friction: float) -> dict:
    """The axial force over the revolution: the frictionless one (largest |F| / P_n), and with ``friction`` its mean,
    peak-to-peak and harmonics of orders 1-12 over mu P_n, and the dominant order (mean excluded)."""
    pn = rev.p_n_N
    frictionless = rev.outer_race_axial_N if rev.outer_race_axial_N is not None else np.zeros_like(rev.phase_deg)
    force = friction_axial_force_N(rev, friction)
    scale = friction * pn if friction > 0.0 else 1.0
    harmonics = {str(k): harmonic_amplitude(rev.phase_deg, force, k) / scale for k in range(1, 13)}
    values = force[:-1] if rev.phase_deg[-1] - rev.phase_deg[0] >= 360.0 - 1e-9 else force
    return {"frictionless_max_over_p_n": float(np.abs(frictionless).max() / pn), "friction": friction,
            "mean_over_mu_p_n": float(values.mean() / scale), "peak_to_peak_over_mu_p_n": float(np.ptp(values) / scale),
            "harmonics_over_mu_p_n": harmonics,
            "dominant_order": int(max(harmonics, key=lambda k: harmonics[k])) if friction > 0.0 else 0,
            "peak_to_peak_N": float(np.ptp(values))}
