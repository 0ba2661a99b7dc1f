"""Sparse linear-algebra pieces shared by the thermal and the mechanics solvers: a BLAS-free dot product,
preconditioned conjugate gradients that work in place (a compiled Jacobi variant), and the sparse LDL'
factorisation both use as a reusable preconditioner for their symmetric positive definite step matrices."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import qdldl
import scipy.sparse as sp
from numba import njit

def dot(a: np.ndarray, b: np.ndarray) -> float:
    """Vector dot product without BLAS: a multi-threaded BLAS dot on a loaded machine costs ~1000x
    more than the product itself (measured: 2 ms vs 3 us for 14,000 entries)."""
    return float(np.einsum("i,i->", a, b))


def norm(a: np.ndarray) -> float:
    return float(np.sqrt(dot(a, a)))


class SparseCholesky:
    """Sparse LDL' factor of a symmetric positive definite matrix (QDLDL, AMD ordering: Stellato et al., OSQP,
    Math. Prog. Comp. 12 (2020) 637), used by both solvers as a reusable preconditioner.

    :meth:`refactorize` redoes only the numeric factorisation when the matrix has the pattern of the first one
    (the step matrices of a run keep their pattern): the ordering and elimination tree are kept. Measured on the
    case-A stress tangents (docs/experiments/stress_preconditioner.md): 7.5 ms against 49 ms for CHOLMOD's full
    factorisation (cholespy, which re-orders every time) at 9882 DOFs, 74 ms against 206 ms at 33,710; solves
    cost the same within the machine's noise.

    ``check_definite``: raise :class:`numpy.linalg.LinAlgError` when the matrix is not positive definite (a
    pivot <= 0; LDL' without pivoting does not refuse an indefinite matrix by itself). The check copies the factor
    (~1/3 of a refactorisation at 33,710 DOFs), so a caller whose matrices are positive definite by construction
    may skip it."""

    _upper: sp.csc_matrix          # the upper triangle of A (set by refactorize)
    _upper_of_A: np.ndarray        # where each entry of _upper sits in A.data
    _solver: qdldl.Solver

    def __init__(self, A: sp.spmatrix, check_definite: bool = True) -> None:
        self.check_definite = check_definite
        self._pattern: tuple[np.ndarray, np.ndarray] | None = None
        self.refactorize(A)

    def refactorize(self, A: sp.spmatrix) -> None:
        """Factorise ``A`` (numerically only, when its pattern is the first matrix's)."""
        A = sp.csr_matrix(A)
        if self._pattern is not None and _same_pattern(A, self._pattern):
            self._upper.data = A.data[self._upper_of_A]
            self._solver.update(self._upper, upper=True)
        else:
            self._pattern = (A.indptr, A.indices)
            numbered = sp.csr_matrix((np.arange(1.0, A.nnz + 1.0), A.indices, A.indptr), shape=A.shape)
            upper = sp.triu(numbered, format="csc")   # its entries, numbered by their place in A.data
            self._upper_of_A = upper.data.astype(np.int64) - 1
            self._upper = sp.csc_matrix((A.data[self._upper_of_A], upper.indices, upper.indptr), shape=A.shape)
            try:
                self._solver = qdldl.Solver(self._upper, upper=True)
            except RuntimeError as exc:   # a structurally zero pivot
                raise np.linalg.LinAlgError(str(exc)) from exc
        if self.check_definite and not np.all(self._solver.factors()[1] > 0.0):
            raise np.linalg.LinAlgError("matrix is not positive definite (an LDL' pivot <= 0)")

    def solve(self, b: np.ndarray) -> np.ndarray:
        return self._solver.solve(np.ascontiguousarray(b, dtype=float))


def _same_pattern(A: sp.csr_matrix, pattern: tuple[np.ndarray, np.ndarray]) -> bool:
    indptr, indices = pattern
    return (A.indptr is indptr and A.indices is indices) or (
        np.array_equal(A.indptr, indptr) and np.array_equal(A.indices, indices))


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


@njit(cache=True)
def _dot(a, b):  # pragma: no cover (compiled): a loop, not BLAS (see :func:`dot`)
    s = 0.0
    for i in range(a.size):
        s += a[i] * b[i]
    return s


@njit(cache=True)
def _jacobi_pcg(indptr, indices, data, b, x, inv_diag, target, max_iterations):  # pragma: no cover (compiled)
    n = b.size
    r = b.copy()
    for i in range(n):
        s = 0.0
        for k in range(indptr[i], indptr[i + 1]):
            s += data[k] * x[indices[k]]
        r[i] -= s
    if np.sqrt(_dot(r, r)) <= target:
        return 1, 0
    z = inv_diag * r
    p = z.copy()
    Ap = np.empty(n)
    rz = _dot(r, z)
    for it in range(1, max_iterations + 1):
        for i in range(n):
            s = 0.0
            for k in range(indptr[i], indptr[i + 1]):
                s += data[k] * p[indices[k]]
            Ap[i] = s
        pAp = _dot(p, Ap)
        if not pAp > 0.0:
            return 0, it
        step = rz / pAp
        x += step * p
        r -= step * Ap
        if np.sqrt(_dot(r, r)) <= target:
            return 1, it
        z = inv_diag * r
        rz_old = rz
        rz = _dot(r, z)
        p = z + (rz / rz_old) * p
    return -1, max_iterations


def jacobi_pcg(A: sp.csr_matrix, b: np.ndarray, x: np.ndarray, target: float,
               max_iterations: int) -> tuple[bool | None, int]:
    """:func:`pcg` with the Jacobi (diagonal) preconditioner, compiled: the same iteration without the Python
    overhead of ~10 small array operations per iteration (the thermal solver runs ~24,000 of them per case-A
    run). Same return values; ``x`` is updated in place."""
    A = sp.csr_matrix(A)
    status, iterations = _jacobi_pcg(A.indptr, A.indices, np.ascontiguousarray(A.data, dtype=float),
                                     np.ascontiguousarray(b, dtype=float), x, 1.0 / A.diagonal(), float(target),
                                     int(max_iterations))
    return {1: True, 0: False, -1: None}[status], iterations
