"""Narrow-groove theory (NGT) film coefficients: the limit of infinitely many grooves.

Vohr & Chow (1965, "Characteristics of herringbone-grooved, gas-lubricated journal bearings",
J. Basic Eng. 87, 568-578) replace the groove-ridge pattern by a smoothed film: P is constant across
one groove period, the pressure gradient along the grooves (direction s = (cos beta, sin beta)) is
common to groove and ridge, and the flux across the grooves (direction n = (sin beta, -cos beta)) is
common to both. Averaging over a period with <f> = alpha f(h_g) + (1 - alpha) f(h_r)
(alpha = groove width ratio, h_g = h_r + groove depth):

    q = -P K grad P + Lambda P b
    K = <h^3> s s^T + n n^T / <h^-3>
    b = <h> cos(beta) s + (<h^-2> / <h^-3>) sin(beta) n

(own derivation of the locally one-dimensional flow balance; ungrooved land: K = h^3 I, b = h e_theta).
Solved with the same finite-volume operator and solvers on an unskewed grid (k = 0).
"""

from __future__ import annotations

import math

import numpy as np

from quenchsim.bearings.gas_journal.film import FACE_POINTS, FilmFrame, FilmGeometry
from quenchsim.bearings.gas_journal.geometry import Bearing, Grid, grid_for_level
from quenchsim.bearings.gas_journal.operator import Operator
from quenchsim.errors import require


def ngt_face_coefficients(geo: FilmGeometry, bearing: Bearing, displacement: tuple[float, float]) -> np.ndarray:
    """Half-face coefficients [D_main, D_cross, c] of the narrow-groove film on an unskewed grid."""
    grooves = bearing.grooves
    assert grooves is not None   # the narrow-groove film is that of a grooved bearing
    grid = geo.grid
    hr = geo.face_films(displacement, FilmFrame())
    hg = hr + grooves.depth_ratio
    a = grooves.width_ratio
    beta = math.radians(grooves.angle_deg)
    cb, sb = math.cos(beta), math.sin(beta)
    h3 = a * hg ** 3 + (1 - a) * hr ** 3
    h1 = a * hg + (1 - a) * hr
    inv3 = a / hg ** 3 + (1 - a) / hr ** 3
    inv2 = a / hg ** 2 + (1 - a) / hr ** 2
    knn = 1.0 / inv3
    hn = inv2 / inv3
    k_tt = h3 * cb * cb + knn * sb * sb
    k_tz = (h3 - knn) * cb * sb
    k_zz = h3 * sb * sb + knn * cb * cb
    b_t = h1 * cb * cb + hn * sb * sb
    b_z = (h1 - hn) * cb * sb
    eta = np.stack([(np.arange(grid.n_eta)[:, None] + dy) * grid.h_eta * np.ones((1, grid.n_xi))
                    for _, dy in FACE_POINTS], axis=-1)
    grooved = eta < grooves.length_ratio * grid.eta_max
    h = hr
    coef = np.empty(hr.shape + (3,))
    coef[..., 0:2, 0] = np.where(grooved, k_tt, h ** 3)[..., 0:2]
    coef[..., 0:2, 1] = np.where(grooved, k_tz, 0.0)[..., 0:2]
    coef[..., 0:2, 2] = np.where(grooved, b_t, h)[..., 0:2]
    coef[..., 2:4, 0] = np.where(grooved, k_zz, h ** 3)[..., 2:4]
    coef[..., 2:4, 1] = np.where(grooved, k_tz, 0.0)[..., 2:4]
    coef[..., 2:4, 2] = np.where(grooved, b_z, 0.0)[..., 2:4]
    return coef


def ngt_operator_hierarchy(bearing: Bearing, level: int, bearing_number: float,
                           displacement: tuple[float, float]) -> list[Operator]:
    """Steady NGT operators of grid ``level`` and its coarsenings (unskewed grids)."""
    require(bearing.grooves is not None, "bearing.grooves", None, "narrow-groove theory needs a groove pattern")
    fine = grid_for_level(level, bearing)
    grid = Grid(fine.n_xi, fine.n_eta, fine.eta_max, 0.0)
    ops = []
    while True:
        geo = FilmGeometry(grid, np.zeros((grid.n_eta, grid.n_xi)))
        ops.append(Operator(grid, ngt_face_coefficients(geo, bearing, displacement), bearing_number,
                            np.zeros(grid.shape)))
        if not grid.can_coarsen():
            return ops
        grid = grid.coarsen()
