"""Linear solves of the implicit heat-conduction steps.

The step matrix A = C (rho c_p - dQ/dT)/dt + K(k) + R(dq/dT) is symmetric and, away from a boiling
curve whose flux falls with the surface temperature, positive definite. Which solver is cheapest
depends on the step (measured on the case-A mesh, 4941 P2 DOFs):

* short steps (dt up to ~0.5 s): the mass term dominates and Jacobi-preconditioned CG warm-started
  from the last iterate converges in 20-50 iterations (2-4 ms), cheaper than one factorisation (13 ms);
* long steps (air cooling, dt 10-120 s): Jacobi CG needs 180-430 iterations (13-32 ms), while CG
  preconditioned by the Cholesky factor of an earlier step matrix converges in a few iterations of 0.5 ms.

:class:`StepLinearSolver` starts with Jacobi CG and, once that needs more than ``jacobi_max``
iterations, keeps a factorisation for the rest of the run (steps only grow, except when cut).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from quenchsim.fem.linalg import SparseCholesky, jacobi_pcg, norm, pcg


class StepLinearSolver:
    """Solves A x = b to ``||b - A x|| <= rtol ||b||`` for the step matrices of one thermal run."""

    def __init__(self, rtol: float = 1e-9, jacobi_max: int = 50, max_cg: int = 25) -> None:
        self.rtol = rtol
        self.jacobi_max = jacobi_max
        self.max_cg = max_cg
        self.use_factor = False
        self._factor: SparseCholesky | None = None
        self._factored_matrix: sp.csr_matrix | None = None
        self.factorizations = 0
        self.cg_iterations = 0

    def checkpoint_state(self) -> dict[str, Any]:
        """What the next solves depend on: the mode and the matrix of the kept factorisation."""
        return {"use_factor": self.use_factor, "factored_matrix": self._factored_matrix}

    def restore_state(self, state: dict[str, Any]) -> None:
        """Continue from :meth:`checkpoint_state` (refactorises the kept matrix: the same factor)."""
        self.use_factor = bool(state["use_factor"])
        self._factored_matrix = state.get("factored_matrix")
        self._factor = None if self._factored_matrix is None else SparseCholesky(self._factored_matrix)

    def solve(self, A: sp.csr_matrix, b: np.ndarray, x0: np.ndarray) -> np.ndarray:
        target = self.rtol * norm(b)
        x = x0.copy()
        if not self.use_factor:
            done, its = jacobi_pcg(A, b, x, target, self.jacobi_max)
            self.cg_iterations += its
            if done is not None:
                return x if done else spla.spsolve(A.tocsc(), b)
            self.use_factor = True  # from here on the steps are long: keep a factorisation
        if self._factor is not None:
            done, its = pcg(A, b, x, target, self._factor.solve, self.max_cg)
            self.cg_iterations += its
            if done:
                return x
        return self._factor_and_solve(A, b)

    def _factor_and_solve(self, A: sp.csr_matrix, b: np.ndarray) -> np.ndarray:
        """Refactorise (sparse Cholesky) and solve; sparse LU with pivoting if the matrix is not positive
        definite."""
        try:
            self._factor, self._factored_matrix = SparseCholesky(A), A
        except np.linalg.LinAlgError:  # not positive definite
            self._factor = self._factored_matrix = None
            return spla.spsolve(A.tocsc(), b)
        self.factorizations += 1
        x = self._factor.solve(b)
        if not norm(b - A @ x) <= 1e3 * self.rtol * norm(b):
            # an inaccurate factor (ill-conditioned step matrix): do not reuse it
            self._factor = self._factored_matrix = None
            return spla.spsolve(A.tocsc(), b)
        return x
