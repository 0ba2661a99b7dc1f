"""Geometric excitation of a ball bearing at every time step: ball positions and the form errors
seen at each ball's contacts (both run-out models start from these arrays).

Kinematics (pure rolling, balls held by the cage; :mod:`quenchsim.bearings.kinematics`):
ball j sits at the azimuth theta_j(t) = 2 pi f_c t + 2 pi j / Z + dtheta_j (dtheta_j: position
error) and spins at f_b relative to the cage, psi(t) = 2 pi f_b t. Its contact on a ring turning
at f_ring lies at the ring-fixed angle phi = theta_j - 2 pi f_ring t.

Form errors (reference sec. 2 and 3, R(phi) = R0 + sum_l A_l cos(l phi + B_l)):

    raceway     w(phi) = (A_pp / 2) cos(l phi - phase)
    ball        the diameter along the contact line through the two opposite contacts:
                dD_j(t) = dD_j + (A_pp / 2) [cos(l psi - phase) + cos(l (psi + pi) - phase)]
                (odd orders cancel, even orders double), dD_j the ball's diameter deviation.

The radial interference of ball j between the raceways is w_inner(phi_i) - w_outer(phi_o): a bump
on the inner raceway or a dip in the outer raceway pushes the ball harder into contact.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from quenchsim.bearings import kinematics

if TYPE_CHECKING:
    from quenchsim.bearings.runout.case import RunoutCase


@dataclass(frozen=True)
class Excitation:
    """Time grid (N,), ball azimuths (N, Z) in rad, raceway interference and ball diametral
    deviation along the line of centres (N, Z) in m."""

    time_s: np.ndarray
    ball_angle_rad: np.ndarray
    race_m: np.ndarray
    ball_m: np.ndarray


def ring_speeds_hz(case: RunoutCase) -> tuple[float, float]:
    """(inner, outer) ring speeds: the rotating ring turns at +speed, the other stands still."""
    return (case.speed_hz, 0.0) if case.rotating == "inner" else (0.0, case.speed_hz)


def kinematic_frequencies(case: RunoutCase) -> kinematics.BearingFrequencies:
    """Cage, spin and ring-relative frequencies of the case's bearing at its contact angle."""
    geometry = kinematics.BearingGeometry(case.pitch_diameter_m, case.ball_diameter_m, case.balls,
                                          case.contact_angle_rad)
    return kinematics.frequencies(geometry, *ring_speeds_hz(case))


def excitation(case: RunoutCase) -> Excitation:
    """Ball azimuths and form-error interference of every ball at every time step (module docstring)."""
    f = kinematic_frequencies(case)
    f_inner, f_outer = ring_speeds_hz(case)
    z = case.balls
    t = np.arange(case.samples) * (case.duration_s / case.samples)
    spacing = 2.0 * np.pi * np.arange(z) / z + np.asarray(case.ball_position_error_rad)
    theta = 2.0 * np.pi * f.cage_hz * t[:, None] + spacing[None, :]
    psi = np.broadcast_to(2.0 * np.pi * f.ball_spin_hz * t[:, None], theta.shape)
    race = np.zeros_like(theta)
    ball = np.broadcast_to(np.asarray(case.ball_diameter_deviation_m)[None, :], theta.shape).copy()
    for w in case.waviness:
        half = 0.5 * w.amplitude_pp_m
        if w.part == "inner":
            race += half * np.cos(w.order * (theta - 2.0 * np.pi * f_inner * t[:, None]) - w.phase_rad)
        elif w.part == "outer":
            race -= half * np.cos(w.order * (theta - 2.0 * np.pi * f_outer * t[:, None]) - w.phase_rad)
        else:
            p = psi[:, w.ball]
            ball[:, w.ball] += half * (np.cos(w.order * p - w.phase_rad)
                                       + np.cos(w.order * (p + np.pi) - w.phase_rad))
    return Excitation(time_s=t, ball_angle_rad=theta, race_m=race, ball_m=ball)
