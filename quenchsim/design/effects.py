"""What each variable does to each quantity, read from the trials: a quadratic response surface (least squares in
the variables scaled to [0, 1]; linear when there are too few trials for the quadratic terms) gives

* the change of the quantity from the variable's low to its high bound, the others held at a reference point
  (the recommended settings), and
* each variable's share of the quantity's variance over the whole box (first-order Sobol index of the surface,
  Sobol 1993, computed on a grid of the surface), i.e. how much the variable matters,

with the surface's R^2 on the trials, so a poor fit is visible. Choice variables are left out (no slope).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Any

import numpy as np

GRID = 21
"""Points per variable of the grid the variance shares are computed on (sampled at random above 3 variables)."""


def _features(u: np.ndarray, quadratic: bool) -> np.ndarray:
    cols = [np.ones(len(u))] + [u[:, j] for j in range(u.shape[1])]
    if quadratic:
        cols += [u[:, i] * u[:, j] for i, j in itertools.combinations_with_replacement(range(u.shape[1]), 2)]
    return np.column_stack(cols)


def response_surface(u: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, bool, float]:
    """Least-squares coefficients of the quadratic (or, with too few points, linear) surface of ``y`` over
    ``u`` (n, d) in [0, 1], whether it is quadratic, and its R^2 on the points.

    >>> u = np.array([[0.0], [0.5], [1.0], [0.25]]); c, quad, r2 = response_surface(u, 1 + 2 * u[:, 0] ** 2)
    >>> quad, bool(np.allclose(c, [1, 0, 2])), round(r2, 6)
    (True, True, 1.0)
    """
    d = u.shape[1]
    quadratic = len(u) >= 1 + d + d * (d + 1) // 2 + 2   # two points to spare for R^2 to mean something
    X = _features(u, quadratic)
    coef, *_ = np.linalg.lstsq(X, y, rcond=None)
    resid = y - X @ coef
    ss = float(np.sum((y - y.mean()) ** 2))
    return coef, quadratic, 1.0 - float(np.sum(resid ** 2)) / ss if ss > 0 else 1.0


def _evaluate(coef: np.ndarray, quadratic: bool, u: np.ndarray) -> np.ndarray:
    return _features(u, quadratic) @ coef


def variance_shares(coef: np.ndarray, quadratic: bool, d: int, seed: int = 0) -> np.ndarray:
    """First-order Sobol indices of the surface over [0, 1]^d: Var(E[f | u_j]) / Var(f)."""
    if d <= 3:
        axes = np.linspace(0.0, 1.0, GRID)
        grid = np.array(list(itertools.product(axes, repeat=d)))
    else:
        grid = np.random.default_rng(seed).random((20000, d))
    f = _evaluate(coef, quadratic, grid)
    total = float(np.var(f))
    if total <= 0:
        return np.zeros(d)
    shares = []
    for j in range(d):
        if d <= 3:
            means = f.reshape((GRID,) * d).mean(axis=tuple(k for k in range(d) if k != j))
        else:   # a binned estimate of E[f | u_j]
            bins = np.minimum((grid[:, j] * GRID).astype(int), GRID - 1)
            means = np.array([f[bins == b].mean() for b in range(GRID)])
        shares.append(float(np.var(means)) / total)
    return np.array(shares)


def effects(u: np.ndarray, values: dict[str, np.ndarray], names: Sequence[str], reference_u: np.ndarray
            ) -> dict[str, dict[str, Any]]:
    """Per quantity: R^2, whether quadratic, and per variable name the low -> high change at ``reference_u``
    and its variance share. ``u`` (n, d): the numeric variables of the ok trials in [0, 1]."""
    out: dict[str, dict[str, Any]] = {}
    for quantity, y in values.items():
        coef, quadratic, r2 = response_surface(u, y)
        shares = variance_shares(coef, quadratic, u.shape[1])
        per: dict[str, dict[str, float]] = {}
        for j, name in enumerate(names):
            lo, hi = reference_u.copy(), reference_u.copy()
            lo[j], hi[j] = 0.0, 1.0
            change = float(_evaluate(coef, quadratic, np.vstack([hi]))[0] - _evaluate(coef, quadratic, np.vstack([lo]))[0])
            per[name] = {"low_to_high": change, "variance_share": float(shares[j])}
        out[quantity] = {"r2": r2, "quadratic": quadratic, "variables": per}
    return out
