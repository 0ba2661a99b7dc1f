"""Sparse linear-algebra pieces shared by the thermal and the mechanics solvers: a BLAS-free dot product,
preconditioned conjugate gradients that work in place, and the symmetric-mode sparse LU both use as a
reusable preconditioner for their symmetric positive definite step matrices."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla


def dot(a: np.ndarray, b: np.ndarray) -> float:
    """Vector dot product without BLAS: a multi-threaded BLAS dot on a loaded machine costs ~1000x
    more than the product itself (measured: 2 ms vs 3 us for 14,000 entries)."""
    return float(np.einsum("i,i->", a, b))


def norm(a: np.ndarray) -> float:
    return float(np.sqrt(dot(a, a)))


def symmetric_lu(A: sp.spmatrix) -> spla.SuperLU:
    """LU of a symmetric positive definite matrix in symmetric mode (same permutation of rows and
    columns, no pivoting): a smaller factor and faster solves than the general ordering (measured on
    case A, 9882 DOFs: fill 0.69 M vs 0.73 M, solve 1.5 vs 1.9 ms). Raises RuntimeError on a zero pivot."""
    return spla.splu(A.tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})


def pcg(A: sp.spmatrix, b: np.ndarray, x: np.ndarray, target: float, precondition: Callable[[np.ndarray], np.ndarray],
        max_iterations: int) -> tuple[bool | None, int]:
    """Preconditioned conjugate gradients for A x = b from ``x`` (updated in place) until ||b - A x|| <= target.

    Returns (status, iterations): status True converged, None not within ``max_iterations``, False breakdown
    (p.Ap <= 0: A is not positive definite)."""
    r = b - A @ x
    if norm(r) <= target:
        return True, 0
    z = precondition(r)
    p = z.copy()
    rz = dot(r, z)
    for it in range(1, max_iterations + 1):
        Ap = A @ p
        pAp = dot(p, Ap)
        if not pAp > 0.0:
            return False, it
        step = rz / pAp
        x += step * p
        r -= step * Ap
        if norm(r) <= target:
            return True, it
        z = precondition(r)
        rz, rz_old = dot(r, z), rz
        p = z + (rz / rz_old) * p
    return None, max_iterations
