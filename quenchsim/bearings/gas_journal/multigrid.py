"""FAS multigrid (full approximation scheme, Brandt) for the nonlinear Reynolds operator.

V(nu1, nu2) cycles with point Gauss-Seidel-Newton smoothing (the same numba kernel as the
Gauss-Seidel and SOR baselines), solution restriction by injection, defect restriction by full
weighting of R = defect / area, bilinear prolongation of the correction, many sweeps on the
coarsest grid; full multigrid (nested iteration) start for steady problems. Upwind weights are
refreshed on every level when the cycle reaches it and on the finest grid before every cycle.
Work unit = one sweep on the finest grid (coarse sweeps weighted by node count).
"""

from __future__ import annotations

import time

import numpy as np

from quenchsim.bearings.gas_journal.operator import Operator, inject, prolong, restrict_full_weighting
from quenchsim.bearings.gas_journal.solvers import TOLERANCE, SolveResult


class FASMultigrid:
    """FAS V-cycles on the operator hierarchy ``ops`` (finest first)."""

    def __init__(self, ops: list[Operator], pre_sweeps: int = 2, post_sweeps: int = 1,
                 coarse_sweeps: int = 40, smoother: str = "line", cycle_index: int = 1) -> None:
        self.ops = ops
        self.gamma = cycle_index
        self.smoother = smoother
        self.pre = pre_sweeps
        self.post = post_sweeps
        self.coarse = coarse_sweeps
        self.work = 0.0
        self._nodes0 = ops[0].sigma.size

    def _relax(self, level: int, p: np.ndarray, f: np.ndarray, sweeps: int) -> None:
        if self.smoother == "line":
            self.ops[level].relax_lines(p, f, sweeps)
        elif self.smoother == "symmetric-line":
            self.ops[level].relax_lines(p, f, sweeps, True)
            sweeps *= 2
        else:
            self.ops[level].relax(p, f, sweeps)
        self.work += sweeps * self.ops[level].sigma.size / self._nodes0

    def cycle(self, level: int, p: np.ndarray, f: np.ndarray) -> None:
        """One FAS V-cycle on ``level`` (in place)."""
        op = self.ops[level]
        if level == len(self.ops) - 1:
            self._relax(level, p, f, self.coarse)
            return
        self._relax(level, p, f, self.pre)
        coarse_op = self.ops[level + 1]
        r = op.defect(p, f) / op.area
        pc = inject(p)
        coarse_op.update_weights(pc)
        fc = coarse_op.apply(pc) + restrict_full_weighting(r) * coarse_op.area
        fc[0, :] = 0.0
        p_start = pc.copy()
        for _ in range(self.gamma if level + 2 < len(self.ops) else 1):
            self.cycle(level + 1, pc, fc)
        correction = prolong(pc - p_start)
        new = p + correction
        bad = new <= 0.0
        new[bad] = 0.5 * p[bad]
        p[:] = new
        self._relax(level, p, f, self.post)

    def _full_multigrid_start(self) -> np.ndarray:
        p = np.ones(self.ops[-1].sigma.shape)
        for level in range(len(self.ops) - 1, -1, -1):
            op = self.ops[level]
            if level < len(self.ops) - 1:
                p = prolong(p)
            op.update_weights(p)
            self.cycle(level, p, np.zeros_like(p))
        return p

    def solve(self, p0: np.ndarray | None = None, f: np.ndarray | None = None, tol: float = TOLERANCE,
              max_cycles: int = 100) -> SolveResult:
        """Cycle until ||R||_2 <= tol on the finest grid; p0 = None starts by full multigrid (f must be 0)."""
        start = time.perf_counter()
        self.work = 0.0
        fine = self.ops[0]
        if f is None:
            f = np.zeros(fine.sigma.shape)
        p = self._full_multigrid_start() if p0 is None else p0.copy()
        fine.update_weights(p)
        res = fine.residual_norm(p, f)
        history = [res]
        cycles = 0
        while res > tol and cycles < max_cycles and np.isfinite(res):
            self.cycle(0, p, f)
            cycles += 1
            fine.update_weights(p)
            res = fine.residual_norm(p, f)
            history.append(res)
        return SolveResult(p, cycles, res, self.work, time.perf_counter() - start, res <= tol, history)
