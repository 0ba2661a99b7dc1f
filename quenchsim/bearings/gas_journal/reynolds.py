"""Set up and solve the discrete Reynolds equation on a grid hierarchy with a chosen method."""

from __future__ import annotations

from typing import Literal

import numpy as np

from quenchsim.bearings.gas_journal.film import FilmFrame, film_hierarchy
from quenchsim.bearings.gas_journal.geometry import Bearing, Grid
from quenchsim.bearings.gas_journal.multigrid import FASMultigrid
from quenchsim.bearings.gas_journal.operator import Operator
from quenchsim.bearings.gas_journal.solvers import TOLERANCE, SolveResult, newton_direct, relaxation_solve
from quenchsim.errors import InputError, require

Method = Literal["multigrid", "gauss-seidel", "sor", "direct"]
METHODS: tuple[str, ...] = ("multigrid", "gauss-seidel", "sor", "direct")


def check_inputs(bearing_number: float, eccentricity: float) -> None:
    """Bearing number >= 0 and 0 <= eccentricity ratio < 1 (the film must not touch)."""
    require(np.isfinite(bearing_number) and bearing_number >= 0.0, "bearing_number", bearing_number,
            "must be >= 0 (Lambda = 6 mu omega r^2 / (pa c^2))")
    require(np.isfinite(eccentricity) and 0.0 <= eccentricity < 1.0, "eccentricity", eccentricity,
            "must be in [0, 1) (eccentricity / radial clearance)")


def operator_hierarchy(bearing: Bearing, grid: Grid, bearing_number: float, displacement: tuple[float, float],
                       frame: FilmFrame = FilmFrame(), mass_factor: float = 0.0) -> list[Operator]:
    """Operators of ``grid`` and all its 2x coarsenings (finest first).

    mass_factor multiplies the control-volume film volume into sigma (2 Lambda / dT for
    Crank-Nicolson, 0 for a steady film). Coarse grids carry the area-averaged groove depth.
    """
    ops = []
    for geo in film_hierarchy(grid, bearing.grooves):
        coef = geo.coefficients(displacement, frame)
        sigma = mass_factor * geo.volume(displacement, frame) if mass_factor else np.zeros(geo.grid.shape)
        ops.append(Operator(geo.grid, coef, bearing_number, sigma))
    return ops


def film_volume(bearing: Bearing, grid: Grid, displacement: tuple[float, float], frame: FilmFrame) -> np.ndarray:
    """Film volume V_p of every control volume (for the time derivative)."""
    return film_hierarchy(grid, bearing.grooves)[0].volume(displacement, frame)


def solve(ops: list[Operator], method: str = "multigrid", p0: np.ndarray | None = None,
          f: np.ndarray | None = None, tol: float = TOLERANCE, omega: float = 1.0,
          max_time_s: float = float("inf")) -> SolveResult:
    """Solve L(P) = f on ops[0] (f = 0: steady film) by ``method``; p0 = None starts from P = 1
    (multigrid: from full multigrid)."""
    if method not in METHODS:
        raise InputError("method", method, f"must be one of {', '.join(METHODS)}")
    fine = ops[0]
    if f is None:
        f = np.zeros(fine.sigma.shape)
    if method == "multigrid":
        return FASMultigrid(ops).solve(p0, f, tol)
    start = np.ones(fine.sigma.shape) if p0 is None else p0
    if method == "direct":
        return newton_direct(fine, start, f, tol)
    relax_omega = omega if method == "sor" else 1.0
    return relaxation_solve(fine, start, f, relax_omega, tol, max_time_s=max_time_s)
