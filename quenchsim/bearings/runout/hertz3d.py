"""3-D quasi-static NRRO model with nonlinear Hertz contacts and a fixed contact angle
(reference sec. 3).

The contact angle is fixed at its preloaded value (ball spin axis fixed, ball moment balance
ignored); the non-rotating ring is fixed with its centre at the origin and the rotating ring's
centre (x, y, z) is the unknown. Elastic approach of ball j along its contact line:

    delta_j = (W_ij - W_oj) cos(alpha) + W_bj + d_pl + sigma (x cos th_j + y sin th_j) cos(alpha) + z sin(alpha)

(raceway waviness projected on the contact line, the ball's diameter deviation along it; d_pl the
preload approach, here part of the axial approach z; sigma = -1 for the outer ring free as in the
reference, whose z has the opposite sign; see :mod:`quenchsim.bearings.runout.equilibrium`), Hertz
law Q_j = K_n delta_j^1.5 with the exact
elliptic-integral constant K_n = K_i K_o / (K_i^(2/3) + K_o^(2/3))^1.5 of
:func:`quenchsim.bearings.hertz.ball_race_stiffness`, and force balance
sum Q_j cos a cos th_j = sum Q_j cos a sin th_j = 0, sum Q_j sin a = F_a, solved at every step by
the batched, warm-started Newton method of :func:`~quenchsim.bearings.runout.equilibrium.solve_equilibrium`.
"""

from __future__ import annotations

import numpy as np

from quenchsim.bearings import hertz
from quenchsim.bearings.runout.case import RunoutCase
from quenchsim.bearings.runout.equilibrium import Trajectory, solve_equilibrium
from quenchsim.bearings.runout.excitation import Excitation, excitation


def hertz_constant_N_m15(case: RunoutCase) -> float:
    """K_n of one ball (inner and outer contact in series), Q = K_n delta^1.5."""
    return hertz.ball_race_stiffness(case.ball_diameter_m, case.pitch_diameter_m, case.contact_angle_rad,
                                     case.inner_groove_radius_ratio, case.outer_groove_radius_ratio,
                                     case.youngs_modulus_Pa, case.poisson).combined_N_m15


def solve(case: RunoutCase, exc: Excitation | None = None) -> Trajectory:
    """Rotating-ring centre at every step of the case (module docstring)."""
    exc = excitation(case) if exc is None else exc
    K = hertz_constant_N_m15(case)
    interference = exc.race_m * np.cos(case.contact_angle_rad) + exc.ball_m
    eq = solve_equilibrium(interference, exc.ball_angle_rad, case.contact_angle_rad, case.rotating, K, 1.5,
                           case.axial_load_N)
    s0 = (case.axial_load_N / (case.balls * K * np.sin(case.contact_angle_rad))) ** (2.0 / 3.0)
    return Trajectory(model="hertz3d", time_s=exc.time_s, x_m=eq.x_m, y_m=eq.y_m, z_m=eq.z_m, load_N=eq.load_N,
                      stiffness=K, exponent=1.5, preload_approach_m=s0, iterations=eq.iterations)
