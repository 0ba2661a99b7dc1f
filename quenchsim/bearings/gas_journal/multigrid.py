"""FAS multigrid (full approximation scheme, Brandt) for the nonlinear Reynolds operator.

V(1, 1) cycles; smoother: circumferential-line Gauss-Seidel-Newton (default) or point
Gauss-Seidel-Newton (the kernel of the Gauss-Seidel and SOR baselines); both use the same cell flux
kernel. Solution restriction by injection, defect restriction by full weighting of R = defect / area,
bilinear prolongation of the correction, many sweeps on the coarsest grid (level 1); full multigrid
(nested iteration) start for steady problems; Anderson mixing of the last cycles (Krylov
acceleration). Upwind weights are refreshed on every level when the cycle reaches it and on the
finest grid before every cycle. Why not the reference's plain point smoother: on the 30-deg skewed
grid the operator has a strong mixed derivative and point relaxation smooths poorly (V(2,1) factor
~0.65 per cycle, measured); line relaxation and the mixing bring it to ~0.3.
Work unit = one sweep on the finest grid (coarse sweeps weighted by node count).
"""

from __future__ import annotations

import time

import numpy as np

from quenchsim.bearings.gas_journal.operator import Operator, inject, prolong, restrict_full_weighting
from quenchsim.bearings.gas_journal.solvers import TOLERANCE, SolveResult
from quenchsim.errors import require


class FASMultigrid:
    """FAS V-cycles on the operator hierarchy ``ops`` (finest first)."""

    def __init__(self, ops: list[Operator], pre_sweeps: int = 1, post_sweeps: int = 1,
                 coarse_sweeps: int = 40, smoother: str = "line", acceleration: int = 4) -> None:
        require(smoother in ("line", "point"), "smoother", smoother, "must be 'line' or 'point'")
        self.ops = ops
        self.memory = acceleration
        self.smoother = smoother
        self.pre = pre_sweeps
        self.post = post_sweeps
        self.coarse = coarse_sweeps
        self.work = 0.0
        self._nodes0 = ops[0].sigma.size

    def _relax(self, level: int, p: np.ndarray, f: np.ndarray, sweeps: int) -> None:
        if self.smoother == "line":
            self.ops[level].relax_lines(p, f, sweeps)
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
        xs: list[np.ndarray] = []
        gs: list[np.ndarray] = []
        while res > tol and cycles < max_cycles and np.isfinite(res):
            x = p.copy()
            self.cycle(0, p, f)
            cycles += 1
            if self.memory:
                xs.append(x)
                gs.append(p.copy())
                del xs[:-self.memory - 1], gs[:-self.memory - 1]
                p[:] = anderson_mix(xs, gs)
            fine.update_weights(p)
            res = fine.residual_norm(p, f)
            history.append(res)
        return SolveResult(p, cycles, res, self.work, time.perf_counter() - start, res <= tol, history)


def anderson_mix(xs: list[np.ndarray], gs: list[np.ndarray]) -> np.ndarray:
    """Anderson (type II) mixing of fixed-point iterates g_k = G(x_k): with f_k = g_k - x_k,
    gamma = argmin ||f_k - dF gamma||_2 (normal equations, m <= 4 columns), x_new = g_k - dG gamma
    (Krylov acceleration of the multigrid cycle, cf. Washio & Oosterlee, ETNA 6 (1997) 271-290).
    Falls back to g_k if P would not stay positive or the least-squares system is singular."""
    g = gs[-1]
    if len(xs) < 2:
        return g
    f = [gk - xk for gk, xk in zip(gs, xs)]
    d_f = [f[k + 1] - f[k] for k in range(len(f) - 1)]
    gram = np.array([[float(np.sum(u * v)) for v in d_f] for u in d_f])
    rhs = np.array([float(np.sum(u * f[-1])) for u in d_f])
    try:
        gamma = np.linalg.solve(gram + 1e-14 * np.trace(gram) * np.eye(len(d_f)), rhs)
    except np.linalg.LinAlgError:
        return g
    mixed = g.copy()
    for k, c in enumerate(gamma):
        mixed -= c * (gs[k + 1] - gs[k])
    return mixed if mixed.min() > 0.0 else g
