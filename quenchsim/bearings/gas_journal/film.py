"""Film thickness and the film coefficients of every control-volume half-face.

H = h / c = 1 - e_x cos(theta_s) - e_y sin(theta_s) + G, with (e_x, e_y) the rotor-centre
displacement over the clearance, theta_s the sleeve-frame angle and G the groove depth ratio of the
cell (reference section 1: H = 1 + X sin(Phi) + Y cos(Phi) + G, written here with the displacement
vector). The grid may be the sleeve frame (theta_s = theta) or, for a grooved rotor, the rotor frame
mirrored so that the Couette flux keeps the +theta direction: theta_s = -theta + 2 T
(``FilmFrame(sign=-1, offset=2T)``).

Exact film, flux q = -P H^3 grad P + Lambda P H e_theta; in the skewed coordinates
(xi = theta - k Z, eta = Z) the flux through xi- and eta-faces uses the tensor
D = H^3 [[1 + k^2, -k], [-k, 1]] and the Couette vector (H, 0).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from quenchsim.bearings.gas_journal.geometry import Grid

# fractional (d_xi, d_eta) positions of the half-face midpoints [ab, dc, ad, bc] inside a cell
FACE_POINTS = ((0.5, 0.25), (0.5, 0.75), (0.25, 0.5), (0.75, 0.5))
# quarter-cell centroids of corners [a, b, c, d] and the corner offsets (d_i, d_j)
QUARTER_POINTS = ((0.25, 0.25), (0.75, 0.25), (0.75, 0.75), (0.25, 0.75))
CORNERS = ((0, 0), (1, 0), (1, 1), (0, 1))


@dataclass(frozen=True)
class FilmFrame:
    """Map from grid angle to sleeve angle: theta_s = sign * theta + offset."""

    sign: float = 1.0
    offset: float = 0.0


def sleeve_angle(grid: Grid, xi_index: np.ndarray, eta_index: np.ndarray, frame: FilmFrame) -> np.ndarray:
    """Sleeve-frame angle of points given by fractional grid indices."""
    return frame.sign * grid.theta(xi_index, eta_index) + frame.offset


def smooth_film(theta_s: np.ndarray, eccentricity: tuple[float, float]) -> np.ndarray:
    """H without grooves: 1 - e_x cos(theta_s) - e_y sin(theta_s)."""
    return 1.0 - eccentricity[0] * np.cos(theta_s) - eccentricity[1] * np.sin(theta_s)


def _cell_indices(grid: Grid) -> tuple[np.ndarray, np.ndarray]:
    return np.meshgrid(np.arange(grid.n_xi, dtype=float), np.arange(grid.n_eta, dtype=float))


def face_films(grid: Grid, depth: np.ndarray, eccentricity: tuple[float, float], frame: FilmFrame) -> np.ndarray:
    """H at the four half-face midpoints of each cell, shape (n_eta, n_xi, 4)."""
    ii, jj = _cell_indices(grid)
    out = np.empty((grid.n_eta, grid.n_xi, 4))
    for k, (dx, dy) in enumerate(FACE_POINTS):
        out[..., k] = smooth_film(sleeve_angle(grid, ii + dx, jj + dy, frame), eccentricity) + depth
    return out


def node_mass(grid: Grid, depth: np.ndarray, eccentricity: tuple[float, float], frame: FilmFrame) -> np.ndarray:
    """Film volume of each control volume, sum of H * area over its quarter cells, shape (n_eta + 1, n_xi)."""
    ii, jj = _cell_indices(grid)
    quarter = 0.25 * grid.h_xi * grid.h_eta
    mass = np.zeros(grid.shape)
    for (dx, dy), (ci, cj) in zip(QUARTER_POINTS, CORNERS):
        h = smooth_film(sleeve_angle(grid, ii + dx, jj + dy, frame), eccentricity) + depth
        contrib = h * quarter
        mass[cj:cj + grid.n_eta, :] += np.roll(contrib, ci, axis=1)
    return mass


def exact_coefficients(grid: Grid, depth: np.ndarray, eccentricity: tuple[float, float],
                       frame: FilmFrame) -> np.ndarray:
    """Half-face coefficients [D_main, D_cross, c] of the exact (groove-resolving) film."""
    h = face_films(grid, depth, eccentricity, frame)
    k = grid.skew
    coef = np.empty((grid.n_eta, grid.n_xi, 4, 3))
    h3 = h ** 3
    coef[..., 0:2, 0] = h3[..., 0:2] * (1.0 + k * k)
    coef[..., 0:2, 1] = -k * h3[..., 0:2]
    coef[..., 0:2, 2] = h[..., 0:2]
    coef[..., 2:4, 0] = h3[..., 2:4]
    coef[..., 2:4, 1] = -k * h3[..., 2:4]
    coef[..., 2:4, 2] = 0.0
    return coef


def min_film(grid: Grid, depth: np.ndarray, eccentricity: tuple[float, float], frame: FilmFrame) -> float:
    """Smallest film thickness ratio on the half-face points (must stay positive)."""
    return float(face_films(grid, depth, eccentricity, frame).min())
