"""Cage guidance on the outer-ring bore: short (Ocvirk) journal bearing with squeeze film.

Short-bearing Reynolds equation with the pi-film (half-Sommerfeld) boundary condition; the cage land
is the journal (radius R, land width L, radial clearance c), the outer-ring bore the bearing.
In the line-of-centres frame (e_r along the eccentricity, e_t = z x e_r), with
eps = e/c, omega_bar = (Omega_journal + Omega_bearing)/2, phi_dot the whirl rate:
    F_r = -(mu R L^3 / c^2) [ 2 eps^2 (omega_bar - phi_dot) / (1 - eps^2)^2
                              + pi eps_dot (1 + 2 eps^2) / (2 (1 - eps^2)^(5/2)) ]
    F_t =  (mu R L^3 / c^2) [ pi eps (omega_bar - phi_dot) / (2 (1 - eps^2)^(3/2))
                              + 2 eps eps_dot / (1 - eps^2)^2 ]
(Ocvirk, NACA TN 2808, 1952; with squeeze terms e.g. Childs, Turbomachinery Rotordynamics, 1993,
ch. 3). Viscous (Couette) torque on the journal, full film:
    T = -2 pi mu R^3 L (Omega_journal - Omega_bearing) / (c sqrt(1 - eps^2))
(Petroff with the eccentricity factor; Hamrock, Schmid & Jacobson 2004, ch. 10).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def short_bearing_force(ex: float, ey: float, vx: float, vy: float, omega_journal: float,
                        omega_bearing: float, radius_m: float, length_m: float, clearance_m: float,
                        viscosity_pa_s: float, eps_max: float) -> tuple[float, float, float]:
    """Film force (Fx, Fy) [N] and Couette torque [N m] on the journal.

    (ex, ey): journal centre minus bearing centre [m]; (vx, vy) its rate [m/s]; eccentricity ratio
    clipped to ``eps_max`` (the solid land contact takes over beyond it).
    """
    e = np.hypot(ex, ey)
    base = viscosity_pa_s * radius_m * length_m**3 / clearance_m**2
    omega_bar = 0.5 * (omega_journal + omega_bearing)
    if e < 1e-15:
        erx, ery = 1.0, 0.0
        phi_dot = 0.0
    else:
        erx, ery = ex / e, ey / e
        phi_dot = (ex * vy - ey * vx) / (e * e)
    eps = min(e / clearance_m, eps_max)
    eps_dot = (erx * vx + ery * vy) / clearance_m
    s = 1.0 - eps * eps
    a = omega_bar - phi_dot
    fr = -base * (2.0 * eps * eps * a / s**2 + np.pi * eps_dot * (1.0 + 2.0 * eps * eps) / (2.0 * s**2.5))
    ft = base * (np.pi * eps * a / (2.0 * s**1.5) + 2.0 * eps * eps_dot / s**2)
    torque = -2.0 * np.pi * viscosity_pa_s * radius_m**3 * length_m * (omega_journal - omega_bearing) / (
        clearance_m * np.sqrt(s))
    return fr * erx - ft * ery, fr * ery + ft * erx, torque
