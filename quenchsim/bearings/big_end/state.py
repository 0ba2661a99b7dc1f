"""The state vector of a big-end run, defined once.

    y = [q, dq/dt],   q = (x_1..x_N, y_1..y_N, phi_1..phi_N, x_c, y_c, psi_c, x_o, y_o)

roller centres (x, y) and spin angles phi in the crank-pin frame, then the cage centre and angle, then the
outer-ring centre: 3 N + 5 positions followed by their rates (6 N + 10 states). The index functions are
compiled so the right-hand side (numba) uses the same layout as the Python code that reads results;
:class:`StateView` names the parts of a state (or of a history, states x samples).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def n_positions(n_rollers: int) -> int:
    """3 N + 5 generalised coordinates."""
    return 3 * n_rollers + 5


def n_states(n_rollers: int) -> int:
    """6 N + 10: positions and their rates."""
    return 2 * n_positions(n_rollers)


@njit(cache=True)
def cage_index(n_rollers: int) -> int:
    """Index of the cage centre x in q (then y, then the cage angle)."""
    return 3 * n_rollers


@njit(cache=True)
def ring_index(n_rollers: int) -> int:
    """Index of the outer-ring centre x in q (then y)."""
    return 3 * n_rollers + 3


class StateView:
    """Named parts of a state ``y`` (6 N + 10,) or history (6 N + 10, samples); views, not copies."""

    def __init__(self, y: np.ndarray, n_rollers: int) -> None:
        n, nq, c, o = n_rollers, n_positions(n_rollers), cage_index(n_rollers), ring_index(n_rollers)
        self.roller_x, self.roller_y, self.roller_angle = y[0:n], y[n:2 * n], y[2 * n:3 * n]
        self.cage_x, self.cage_y, self.cage_angle = y[c], y[c + 1], y[c + 2]
        self.ring_xy = y[o:o + 2]
        self.ring_x, self.ring_y = y[o], y[o + 1]
        self.roller_vx, self.roller_vy, self.roller_spin = y[nq:nq + n], y[nq + n:nq + 2 * n], y[nq + 2 * n:nq + 3 * n]
        self.cage_vx, self.cage_vy, self.cage_speed = y[nq + c], y[nq + c + 1], y[nq + c + 2]
        self.ring_vx, self.ring_vy = y[nq + o], y[nq + o + 1]
