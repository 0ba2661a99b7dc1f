"""2-D linear-spring quasi-static model of ball-bearing vibration (reference sec. 2).

Rigid rings and balls; every ball touches both raceways through the same linear spring k on the
line of centres; quasi-static (the rotating ring is advanced step by step and every part is put in
static equilibrium); the axial load is carried through the preload deflection and the axial
displacement follows from the spring deflections through the contact angle alpha.

All form errors act in the radial plane: a ball's radial interference is
u_j = w_inner - w_outer + dD_j (raceway waviness, ball diameter deviation and ball waviness), and
its springs deflect along the contact line by s_j = u_j cos(alpha) + (ring displacement terms), see
:mod:`quenchsim.bearings.runout.equilibrium`. Ball equilibrium k delta_i,j = k delta_e,j splits s_j
equally between the inner and outer spring, so the ball acts on the rings as the series spring
k/2. Consequences (for all balls in contact), the published amplitude ratios of sec. 2:
radial run-out = raceway waviness (ratio 1), axial = cot(alpha) x mean radial interference,
one ball's diameter deviation dD -> radial whirl of 2 dD / Z at the cage frequency.

The paper's spring constant k is an input (bearing.ball_spring_N_per_m); without it the model
takes the Hertz contact linearised at the preload, k/2 = 1.5 Q_0 / s_0 with Q_0 = F_a/(Z sin alpha),
s_0 = (Q_0/K_n)^(2/3) (K_n from :func:`quenchsim.bearings.hertz.ball_race_stiffness`), so that the
linear model is the small-amplitude limit of the Hertz model. While every ball stays loaded the
run-out does not depend on k at all; k matters only once a ball unloads (s_j <= 0).
"""

from __future__ import annotations

import numpy as np

from quenchsim.bearings import hertz
from quenchsim.bearings.runout.case import RunoutCase
from quenchsim.bearings.runout.equilibrium import Trajectory, solve_equilibrium
from quenchsim.bearings.runout.excitation import Excitation, excitation


def series_spring_N_m(case: RunoutCase) -> float:
    """k/2: the inner and outer springs of one ball in series (N/m)."""
    if case.ball_spring_N_m is not None:
        return 0.5 * case.ball_spring_N_m
    K = hertz.ball_race_stiffness(case.ball_diameter_m, case.pitch_diameter_m, case.contact_angle_rad,
                                  case.inner_groove_radius_ratio, case.outer_groove_radius_ratio,
                                  case.youngs_modulus_Pa, case.poisson).combined_N_m15
    q0 = case.axial_load_N / (case.balls * np.sin(case.contact_angle_rad))
    s0 = (q0 / K) ** (2.0 / 3.0)
    return 1.5 * q0 / s0


def solve(case: RunoutCase, exc: Excitation | None = None) -> Trajectory:
    """Free-ring centre at every step of the case (module docstring)."""
    exc = excitation(case) if exc is None else exc
    k = series_spring_N_m(case)
    interference = (exc.race_m + exc.ball_m) * np.cos(case.contact_angle_rad)
    eq = solve_equilibrium(interference, exc.ball_angle_rad, case.contact_angle_rad, case.rotating, k, 1.0,
                           case.axial_load_N)
    s0 = case.axial_load_N / (case.balls * k * np.sin(case.contact_angle_rad))
    return Trajectory(model="linear2d", time_s=exc.time_s, x_m=eq.x_m, y_m=eq.y_m, z_m=eq.z_m, load_N=eq.load_N,
                      stiffness=k, exponent=1.0, preload_approach_m=s0, iterations=eq.iterations)
