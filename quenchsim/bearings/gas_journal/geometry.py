"""Bearing and groove geometry, the computational grid and the film per control-volume face.

Non-dimensional coordinates (reference: docs/reference/bearing_modules.md section 1): theta circumferential
(radians), Z = z / r axial, measured from a bearing end (Z = 0, ambient) to the mid-plane
(Z = L / D, symmetry). Grooves are inclined by the groove angle beta to the circumferential
direction, so the grid is skewed along them:

    xi = theta - k Z,   eta = Z,   k = cot(beta)   (k = 0 for a plain bearing)

with uniform spacing in xi and eta. A groove is a strip of constant xi, so groove edges are grid
lines; the grooved region covers Z < gamma * L / D from each end (partial grooves, ungrooved land in
the middle -- the configuration of the Cunningham et al. rotors; an assumption where the reference
is silent). Grid level m has (10 * 2**(m-1) + 1) x (2 * 2**(m-1) + 1) nodes (reference, efficiency
study).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from quenchsim.errors import require


@dataclass(frozen=True)
class Grooves:
    """Herringbone groove pattern.

    count: number of grooves N_g; angle_deg: groove angle beta to the circumferential direction;
    depth_ratio: groove depth / radial clearance (0 = plain bearing); width_ratio: groove width over
    groove-plus-ridge width; length_ratio: grooved length over bearing length; on: grooved member.
    """

    count: int
    angle_deg: float
    depth_ratio: float
    width_ratio: float
    length_ratio: float
    on: Literal["sleeve", "rotor"] = "sleeve"

    def __post_init__(self) -> None:
        require(isinstance(self.count, (int, np.integer)) and self.count >= 1, "grooves.count",
                self.count, "must be an integer >= 1")
        require(0.0 < self.angle_deg < 90.0, "grooves.angle_deg", self.angle_deg, "must be in (0, 90) deg")
        require(math.isfinite(self.depth_ratio) and self.depth_ratio >= 0.0, "grooves.depth_ratio",
                self.depth_ratio, "must be >= 0 (0 = plain bearing)")
        require(0.0 < self.width_ratio < 1.0, "grooves.width_ratio", self.width_ratio, "must be in (0, 1)")
        require(0.0 < self.length_ratio < 1.0, "grooves.length_ratio", self.length_ratio, "must be in (0, 1)")
        require(self.on in ("sleeve", "rotor"), "grooves.on", self.on, "must be 'sleeve' or 'rotor'")


@dataclass(frozen=True)
class Bearing:
    """A gas journal bearing: length-to-diameter ratio L/D and an optional groove pattern."""

    length_to_diameter: float = 1.0
    grooves: Grooves | None = None

    def __post_init__(self) -> None:
        require(math.isfinite(self.length_to_diameter) and self.length_to_diameter > 0.0,
                "bearing.length_to_diameter", self.length_to_diameter, "must be > 0")

    @property
    def skew(self) -> float:
        """Grid skew k = cot(beta) (0 without grooves)."""
        if self.grooves is None:
            return 0.0
        return 1.0 / math.tan(math.radians(self.grooves.angle_deg))

    @property
    def grooved_rotor(self) -> bool:
        """True when the grooves are on the rotating member (the film is then always unsteady)."""
        return self.grooves is not None and self.grooves.on == "rotor" and self.grooves.depth_ratio > 0.0


@dataclass(frozen=True)
class Grid:
    """Uniform skewed grid on half the bearing: n_xi cells around (periodic), n_eta cells end -> mid."""

    n_xi: int
    n_eta: int
    eta_max: float
    skew: float

    @property
    def h_xi(self) -> float:
        return 2.0 * math.pi / self.n_xi

    @property
    def h_eta(self) -> float:
        return self.eta_max / self.n_eta

    @property
    def nodes(self) -> int:
        """Number of grid nodes including the periodic seam and the ambient row (paper's count)."""
        return (self.n_xi + 1) * (self.n_eta + 1)

    @property
    def shape(self) -> tuple[int, int]:
        """Node array shape (n_eta + 1, n_xi); row 0 is the ambient end, row n_eta the mid-plane."""
        return (self.n_eta + 1, self.n_xi)

    def can_coarsen(self) -> bool:
        return self.n_xi % 2 == 0 and self.n_eta % 2 == 0 and self.n_eta >= 4 and self.n_xi >= 8

    def coarsen(self) -> "Grid":
        return Grid(self.n_xi // 2, self.n_eta // 2, self.eta_max, self.skew)

    def theta(self, xi_index: np.ndarray, eta_index: np.ndarray) -> np.ndarray:
        """Sleeve-frame angle theta = xi + k eta at fractional grid indices."""
        return xi_index * self.h_xi + self.skew * eta_index * self.h_eta

    def node_area(self) -> np.ndarray:
        """Control-volume area per node (the skew has unit Jacobian); half at the mid-plane."""
        area = np.full(self.shape, self.h_xi * self.h_eta)
        area[-1, :] *= 0.5
        area[0, :] *= 0.5
        return area


def grid_for_level(level: int, bearing: Bearing) -> Grid:
    """Grid of level m: (10 * 2**(m-1) + 1) x (2 * 2**(m-1) + 1) nodes (reference efficiency study)."""
    require(isinstance(level, (int, np.integer)) and 1 <= level <= 9, "level", level, "must be an integer in 1..9")
    return Grid(10 * 2 ** (level - 1), 2 ** level, bearing.length_to_diameter, bearing.skew)


def groove_depth_cells(grid: Grid, grooves: Grooves | None) -> np.ndarray:
    """Groove depth ratio per cell, shape (n_eta, n_xi), cell-centre sampling.

    A cell is groove when its centre lies in a groove strip and in the grooved end region, so each cell
    is wholly groove or ridge and every film discontinuity lies on a grid line (edges snap to the
    nearest grid line when the ratios are not multiples of the spacing; see :func:`effective_ratios`).
    """
    depth = np.zeros((grid.n_eta, grid.n_xi))
    if grooves is None or grooves.depth_ratio == 0.0:
        return depth
    xi_c = (np.arange(grid.n_xi) + 0.5) * grid.h_xi
    eta_c = (np.arange(grid.n_eta) + 0.5) * grid.h_eta
    phase = (xi_c * grooves.count / (2.0 * math.pi)) % 1.0
    in_strip = phase < grooves.width_ratio
    in_region = eta_c < grooves.length_ratio * grid.eta_max
    depth[np.ix_(in_region, in_strip)] = grooves.depth_ratio
    return depth


def coarsen_cells(values: np.ndarray) -> np.ndarray:
    """Area average of a cell field onto the 2x coarser grid (keeps the groove volume on coarse grids)."""
    return 0.25 * (values[0::2, 0::2] + values[1::2, 0::2] + values[0::2, 1::2] + values[1::2, 1::2])


def effective_ratios(grid: Grid, grooves: Grooves) -> tuple[float, float]:
    """Groove width and length ratios actually represented on ``grid`` after snapping to grid lines."""
    xi_c = (np.arange(grid.n_xi) + 0.5) * grid.h_xi
    eta_c = (np.arange(grid.n_eta) + 0.5) * grid.h_eta
    width = float(np.mean((xi_c * grooves.count / (2.0 * math.pi)) % 1.0 < grooves.width_ratio))
    length = float(np.mean(eta_c < grooves.length_ratio * grid.eta_max))
    return width, length
