"""Film force on the rotor and the attitude angle.

F = W / (pa L D) = -(r / L) * int_0^{L/(2r)} int_0^{2 pi} (P - 1) n(theta_s) dtheta dZ over the solved half
(mid-plane symmetry doubles it), n = (cos theta_s, sin theta_s) the outward normal of the rotor
(reference section 1: M d2X/dT2 = (r/b) int P sin(Phi), F_y = f_y / (2 pa b r)). Periodic
trapezoidal rule around, Simpson's rule along Z (reference: pressure integrals by Simpson's rule).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from quenchsim.bearings.gas_journal.film import FilmFrame
from quenchsim.bearings.gas_journal.geometry import Grid


def simpson_weights(n_intervals: int, h: float) -> np.ndarray:
    """Composite Simpson weights on n_intervals (even) equal intervals."""
    w = np.ones(n_intervals + 1)
    w[1:-1:2] = 4.0
    w[2:-1:2] = 2.0
    return w * h / 3.0


@lru_cache(maxsize=32)
def _weighted_trig(grid: Grid) -> tuple[np.ndarray, np.ndarray]:
    jj, ii = np.meshgrid(np.arange(grid.n_eta + 1, dtype=float), np.arange(grid.n_xi, dtype=float), indexing="ij")
    th = grid.theta(ii, jj)
    wz = simpson_weights(grid.n_eta, grid.h_eta)[:, None] * grid.h_xi * (-1.0 / (2.0 * grid.eta_max))
    return wz * np.cos(th), wz * np.sin(th)


def film_force(grid: Grid, p: np.ndarray, frame: FilmFrame = FilmFrame()) -> np.ndarray:
    """Dimensionless film force (F_x, F_y) on the rotor in the sleeve frame (scale -(r/L), L/r = 2 L/D)."""
    wc, ws = _weighted_trig(grid)
    dp = p - 1.0
    a, b = float(np.sum(dp * wc)), float(np.sum(dp * ws))  # integrals with cos(theta), sin(theta) of the grid
    c, s = math.cos(frame.offset), math.sin(frame.offset)
    sb = frame.sign * b
    # theta_s = sign theta + offset: cos(theta_s) = c cos(theta) - s sign sin(theta), sin(theta_s) = s cos + c sign sin
    return np.array([c * a - s * sb, s * a + c * sb])


def attitude_deg(displacement: np.ndarray, force: np.ndarray) -> float:
    """Angle from the load line (the external load -F balances the film force) to the line of
    centres, positive in the direction of rotation (degrees)."""
    load = -np.asarray(force)
    ang = math.atan2(displacement[1], displacement[0]) - math.atan2(load[1], load[0])
    return math.degrees((ang + math.pi) % (2.0 * math.pi) - math.pi)
