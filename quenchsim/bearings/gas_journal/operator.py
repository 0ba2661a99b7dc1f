"""The discrete Reynolds operator of one grid level and the grid-transfer operators.

Residual (the same for every solver): R_p = (f_p - L_p(P)) / A_p at every node off the ambient row,
A_p the control-volume area, so R approximates the PDE residual; the convergence measure is its
discrete L2 norm ||R||_2 = sqrt(mean(R_p^2)) over the unknowns (stop at 1e-5, reference section 1).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from quenchsim.bearings.gas_journal import kernels
from quenchsim.bearings.gas_journal.geometry import Grid


@dataclass
class Operator:
    """L(P) = sum of half-face outflows + sigma P on ``grid`` with frozen upwind weights ``w``."""

    grid: Grid
    coef: np.ndarray
    lam: float
    sigma: np.ndarray
    w: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        self.lam = float(self.lam)
        self.w = np.full(self.coef.shape[:3], 0.5)
        self.area = self.grid.node_area()

    def update_weights(self, p: np.ndarray) -> None:
        kernels.upwind_weights(p, self.coef, self.grid.h_xi, self.grid.h_eta, self.lam, self.w)

    def apply(self, p: np.ndarray) -> np.ndarray:
        out = np.empty_like(p)
        kernels.apply_operator(p, self.coef, self.w, self.sigma, self.grid.h_xi, self.grid.h_eta, self.lam, out)
        out[0, :] = 0.0
        return out

    def defect(self, p: np.ndarray, f: np.ndarray) -> np.ndarray:
        """f - L(P) (flux imbalance, zero on the ambient row)."""
        d = f - self.apply(p)
        d[0, :] = 0.0
        return d

    def residual_norm(self, p: np.ndarray, f: np.ndarray) -> float:
        """||R||_2 with R = (f - L(P)) / A (see module docstring)."""
        r = self.defect(p, f)[1:] / self.area[1:]
        return float(np.sqrt(np.mean(r * r)))

    def relax(self, p: np.ndarray, f: np.ndarray, sweeps: int, omega: float = 1.0) -> None:
        """Point Gauss-Seidel-Newton (omega = 1) or SOR (omega > 1) sweeps."""
        kernels.relax(p, f, self.coef, self.w, self.sigma, self.grid.h_xi, self.grid.h_eta, self.lam,
                      omega, sweeps)

    def relax_lines(self, p: np.ndarray, f: np.ndarray, sweeps: int) -> None:
        """Circumferential-line Gauss-Seidel-Newton sweeps."""
        kernels.relax_lines(p, f, self.coef, self.w, self.sigma, self.grid.h_xi, self.grid.h_eta, self.lam,
                            sweeps)


def _next(a: np.ndarray) -> np.ndarray:
    """Value at i + 1 (periodic in xi)."""
    return np.concatenate([a[:, 1:], a[:, :1]], axis=1)


def _previous(a: np.ndarray) -> np.ndarray:
    """Value at i - 1 (periodic in xi)."""
    return np.concatenate([a[:, -1:], a[:, :-1]], axis=1)


def inject(fine: np.ndarray) -> np.ndarray:
    """Coarse-node values taken from the coincident fine nodes."""
    return fine[0::2, 0::2].copy()


def restrict_full_weighting(fine: np.ndarray) -> np.ndarray:
    """Full weighting (1/16 [1 2 1; 2 4 2; 1 2 1]) of a node field, periodic in xi, mirrored at the mid-plane."""
    rows = 0.25 * (_previous(fine) + 2.0 * fine + _next(fine))
    rows = rows[:, 0::2]
    above = np.concatenate([rows[1:], rows[-2:-1]], axis=0)
    below = np.concatenate([rows[:1], rows[:-1]], axis=0)
    return (0.25 * (below + 2.0 * rows + above))[0::2].copy()


def prolong(coarse: np.ndarray) -> np.ndarray:
    """Bilinear interpolation of a coarse node field to the 2x finer grid (periodic in xi)."""
    ny, nx = coarse.shape
    fine = np.empty((2 * (ny - 1) + 1, 2 * nx))
    fine[0::2, 0::2] = coarse
    fine[0::2, 1::2] = 0.5 * (coarse + _next(coarse))
    fine[1::2, :] = 0.5 * (fine[0:-1:2, :] + fine[2::2, :])
    return fine
