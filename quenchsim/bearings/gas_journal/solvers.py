"""Single-grid solvers of L(P) = f: point Gauss-Seidel-Newton, SOR and Newton + sparse direct.

All use :class:`Operator` (the same residual, the same relaxation kernel as the multigrid smoother)
and the same stopping rule ||R||_2 <= tol on the grid solved.
"""

from __future__ import annotations

import time
from functools import lru_cache
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from quenchsim.bearings.gas_journal import kernels
from quenchsim.bearings.gas_journal.operator import Operator

TOLERANCE = 1e-5  # ||R||_2 stopping rule on the finest grid (reference section 1)
DIVERGED = 1e3  # a relaxation run whose residual grows by this factor is stopped as diverged


@dataclass
class SolveResult:
    """Pressure field and solver statistics; ``iterations`` counts sweeps, cycles or Newton steps."""

    p: np.ndarray
    iterations: int
    residual: float
    work_units: float
    wall_time_s: float
    converged: bool
    history: list[float]


def relaxation_solve(op: Operator, p0: np.ndarray, f: np.ndarray, omega: float = 1.0, tol: float = TOLERANCE,
                     max_sweeps: int = 10 ** 7, max_time_s: float = float("inf"),
                     check_every: int = 10) -> SolveResult:
    """Gauss-Seidel-Newton (omega = 1) or SOR (omega > 1) sweeps until ||R||_2 <= tol or the budget ends.

    The residual (and the upwind weights) are refreshed every ``check_every`` sweeps; ``history`` keeps
    the residual at each check so a truncated run can be extrapolated by its asymptotic rate.
    """
    start = time.perf_counter()
    p = p0.copy()
    op.update_weights(p)
    res = op.residual_norm(p, f)
    history = [res]
    sweeps = 0
    while res > tol and sweeps < max_sweeps and time.perf_counter() - start < max_time_s:
        op.relax(p, f, check_every, omega)
        sweeps += check_every
        op.update_weights(p)
        res = op.residual_norm(p, f)
        history.append(res)
        if not np.isfinite(res) or res > DIVERGED * history[0]:
            break
    return SolveResult(p, sweeps, res, float(sweeps), time.perf_counter() - start, res <= tol, history)


@lru_cache(maxsize=16)
def _pattern(shape: tuple[int, int]) -> "_Pattern":
    return _Pattern(shape)


class _Pattern:
    """Sparsity pattern of the cell-local 4x4 Jacobians restricted to the unknowns (rows 1..n_eta)."""

    def __init__(self, shape: tuple[int, int]) -> None:
        ny, nx = shape
        j, i = np.meshgrid(np.arange(ny - 1), np.arange(nx), indexing="ij")
        ip = (i + 1) % nx
        corners = np.stack([j * nx + i, j * nx + ip, (j + 1) * nx + ip, (j + 1) * nx + i], axis=-1)
        rows = np.repeat(corners[..., :, None], 4, axis=-1).ravel()
        cols = np.repeat(corners[..., None, :], 4, axis=-2).ravel()
        keep = (rows >= nx) & (cols >= nx)
        self.keep = keep
        self.rows = rows[keep] - nx
        self.cols = cols[keep] - nx
        self.n = (ny - 1) * nx

    def matrix(self, local: np.ndarray, sigma: np.ndarray) -> sp.csc_matrix:
        mat = sp.csc_matrix((local.ravel()[self.keep], (self.rows, self.cols)), shape=(self.n, self.n))
        return mat + sp.diags(sigma[1:].ravel())


def newton_direct(op: Operator, p0: np.ndarray, f: np.ndarray, tol: float = TOLERANCE,
                  max_iterations: int = 50) -> SolveResult:
    """Newton's method with the exact cell Jacobian (upwind weights frozen per step), SuperLU solves
    and step halving while ||R||_2 does not decrease."""
    start = time.perf_counter()
    pattern = _pattern(op.grid.shape)
    local = np.empty(op.coef.shape[:2] + (4, 4))
    p = p0.copy()
    op.update_weights(p)
    res = op.residual_norm(p, f)
    history = [res]
    it = 0
    while res > tol and it < max_iterations:
        kernels.jacobian_values(p, op.coef, op.w, op.grid.h_xi, op.grid.h_eta, op.lam, local)
        step = spla.spsolve(pattern.matrix(local, op.sigma), op.defect(p, f)[1:].ravel()).reshape(p[1:].shape)
        alpha = 1.0
        while True:
            trial = p.copy()
            trial[1:] += alpha * step
            if trial.min() > 0.0:
                op.update_weights(trial)
                new_res = op.residual_norm(trial, f)
                if new_res < res or alpha < 1e-3:
                    break
            alpha *= 0.5
        p, res = trial, new_res
        history.append(res)
        it += 1
    return SolveResult(p, it, res, float(it), time.perf_counter() - start, res <= tol, history)
