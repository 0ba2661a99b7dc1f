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
from functools import lru_cache

import numpy as np

from quenchsim.bearings.gas_journal.geometry import Grid, Grooves, coarsen_cells, groove_depth_cells

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

    def grid_displacement(self, displacement: tuple[float, float]) -> tuple[float, float]:
        """(a, b) with e_x cos(theta_s) + e_y sin(theta_s) = a cos(theta) + b sin(theta)."""
        c, s = np.cos(self.offset), np.sin(self.offset)
        ex, ey = displacement
        return (ex * c + ey * s, self.sign * (ey * c - ex * s))


class FilmGeometry:
    """Groove depth and the trigonometry of every half-face and quarter-cell point of one grid."""

    def __init__(self, grid: Grid, depth: np.ndarray) -> None:
        self.grid = grid
        self.depth = depth
        ii, jj = np.meshgrid(np.arange(grid.n_xi, dtype=float), np.arange(grid.n_eta, dtype=float))
        face = np.stack([grid.theta(ii + dx, jj + dy) for dx, dy in FACE_POINTS], axis=-1)
        quarter = np.stack([grid.theta(ii + dx, jj + dy) for dx, dy in QUARTER_POINTS], axis=-1)
        self.face_cos, self.face_sin = np.cos(face), np.sin(face)
        self.quarter_cos, self.quarter_sin = np.cos(quarter), np.sin(quarter)
        nj, ni = np.meshgrid(np.arange(grid.n_eta + 1, dtype=float), np.arange(grid.n_xi, dtype=float), indexing="ij")
        node = grid.theta(ni, nj)
        self.node_cos, self.node_sin = np.cos(node), np.sin(node)

    def face_films(self, displacement: tuple[float, float], frame: FilmFrame) -> np.ndarray:
        """H at the four half-face midpoints of each cell, shape (n_eta, n_xi, 4)."""
        a, b = frame.grid_displacement(displacement)
        return 1.0 + self.depth[..., None] - a * self.face_cos - b * self.face_sin

    def coefficients(self, displacement: tuple[float, float], frame: FilmFrame) -> np.ndarray:
        """Half-face coefficients [D_main, D_cross, c] of the exact (groove-resolving) film."""
        h = self.face_films(displacement, frame)
        k = self.grid.skew
        coef = np.empty(h.shape + (3,))
        h3 = h ** 3
        coef[..., 0:2, 0] = h3[..., 0:2] * (1.0 + k * k)
        coef[..., 0:2, 1] = -k * h3[..., 0:2]
        coef[..., 0:2, 2] = h[..., 0:2]
        coef[..., 2:4, 0] = h3[..., 2:4]
        coef[..., 2:4, 1] = -k * h3[..., 2:4]
        coef[..., 2:4, 2] = 0.0
        return coef

    def volume_derivatives(self) -> np.ndarray:
        """dV/da and dV/db of every control volume, shape (2,) + node shape (V is linear in (a, b))."""
        base = self.volume((0.0, 0.0), FilmFrame())
        return np.stack([self.volume((1.0, 0.0), FilmFrame()) - base, self.volume((0.0, 1.0), FilmFrame()) - base])

    def volume(self, displacement: tuple[float, float], frame: FilmFrame) -> np.ndarray:
        """Film volume of each control volume (sum of H * area over its quarter cells), node shape."""
        a, b = frame.grid_displacement(displacement)
        h = (1.0 + self.depth[..., None] - a * self.quarter_cos - b * self.quarter_sin)
        h *= 0.25 * self.grid.h_xi * self.grid.h_eta
        n = self.grid.n_eta
        vol = np.zeros(self.grid.shape)
        vol[:n] += h[..., 0]
        vol[:n, 1:] += h[:, :-1, 1]
        vol[:n, 0] += h[:, -1, 1]
        vol[1:, 1:] += h[:, :-1, 2]
        vol[1:, 0] += h[:, -1, 2]
        vol[1:] += h[..., 3]
        return vol


@lru_cache(maxsize=32)
def film_hierarchy(grid: Grid, grooves: Grooves | None) -> tuple[FilmGeometry, ...]:
    """Film geometry of ``grid`` and its 2x coarsenings (finest first); coarse cells carry the
    area-averaged groove depth of their fine cells."""
    depth = groove_depth_cells(grid, grooves)
    levels = [FilmGeometry(grid, depth)]
    while grid.can_coarsen():
        grid = grid.coarsen()
        depth = coarsen_cells(depth)
        levels.append(FilmGeometry(grid, depth))
    return tuple(levels)
